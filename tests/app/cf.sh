#!/usr/bin/env bash
# App test: the archives follow netCDF-CF where CF has a word for it (docs/archive.md):
# Conventions = "CF-1.8 autobal-1", the CF attributes title, history, source, references;
# every units attribute (datasets, groups, root; also the *_units attributes of parameters) is
# a string UDUNITS-2 parses (checked with units_parse_check, the parser of the configuration);
# coordinates are dimension scales with units and long_name; the configuration's comments survive
# into effective_config and through `autobal rerun`.
set -u
: "${AUTOBAL:?}" "${SCRATCH:?}" "${PY:=/usr/bin/python3}" "${UNITS_CHECK:?}" "${DATA:?}"
rm -rf "$SCRATCH" && mkdir -p "$SCRATCH" && cd "$SCRATCH" || exit 1
fail=0
run() { "$@" -q >out.txt 2>err.txt || { echo "FAIL: $*"; cat err.txt; fail=1; }; }
run "$AUTOBAL" rotor transient --set transient.t_end=0.2 -o rt.h5
run "$AUTOBAL" rotor transient "$DATA/rotor_two_planes.ini" --set transient.t_end=0.2 -o rt2.h5
run "$AUTOBAL" rotor transient "$DATA/runup.ini" --set transient.t_end=12 -o rru.h5
run "$AUTOBAL" rotor stability -o rs.h5
run "$AUTOBAL" rotor sweep --set sweep.n=40 -o rsw.h5
run "$AUTOBAL" rotor map --set map.n1=6 --set map.n2=5 -o rm.h5
run "$AUTOBAL" rotor campbell --set campbell.n=40 -o rc.h5
run "$AUTOBAL" rotor ensemble --set ensemble.n1=2 --set ensemble.n2=2 --set transient.t_end=0.5 -o re.h5
run "$AUTOBAL" pendulum roots "$DATA/pendulum_physical.ini" -o pr.h5
run "$AUTOBAL" pendulum critical --set critical.n_Rm=20 -o pc.h5
run "$AUTOBAL" pendulum map --set map.n_Rm=8 --set map.n_Rw=8 -o pm.h5
run "$AUTOBAL" pendulum transient --set transient.t_end=20 -o pt.h5
run "$AUTOBAL" pendulum ensemble --set ensemble.n1=2 --set ensemble.n2=2 --set transient.t_end=20 -o pe.h5
cat > commented.ini <<'INI'
; a commented configuration: these comments must survive
[rotor]
; the running speed
omega = 3000 rpm   ; 314.16 rad/s
[transient]
t_end = 0.1
INI
run "$AUTOBAL" rotor transient commented.ini -o com.h5
run "$AUTOBAL" rerun com.h5 -o com2.h5
"$PY" - > units.txt <<'PY' || fail=1
import h5py, glob, sys
bad = 0
for f in sorted(glob.glob("*.h5")):
    h = h5py.File(f, "r")
    conv = h.attrs.get("Conventions", "")
    toks = conv.replace(",", " ").split()
    for need in ("CF-1.8", "autobal-1"):
        if need not in toks:
            print(f"FAIL {f}: Conventions = {conv!r} lacks {need}", file=sys.stderr); bad += 1
    for a in ("title", "history", "source", "references"):
        if not str(h.attrs.get(a, "")).strip():
            print(f"FAIL {f}: no CF root attribute {a}", file=sys.stderr); bad += 1
    def visit(name, obj):
        global bad
        for k, v in obj.attrs.items():
            if k == "units" or k.endswith("_units"):
                print(v if isinstance(v, str) else v.decode())
        if isinstance(obj, h5py.Dataset) and obj.attrs.get("CLASS", b"") == b"DIMENSION_SCALE":
            for a in ("units", "long_name"):
                if a not in obj.attrs:
                    print(f"FAIL {f}: coordinate {obj.name} has no {a}", file=sys.stderr); bad += 1
    for k, v in h.attrs.items():
        if k.endswith("_units"): print(v)
    h.visititems(visit)
for f in ("com.h5", "com2.h5"):
    eff = h5py.File(f)["/"].attrs["effective_config"]
    for c in ("a commented configuration: these comments must survive", "the running speed", "314.16 rad/s"):
        if c not in eff:
            print(f"FAIL {f}: comment {c!r} not in effective_config", file=sys.stderr); bad += 1
sys.exit(1 if bad else 0)
PY
# --json summaries: every command's has a units map; its units join the UDUNITS check below
for cmd in "rotor transient --set transient.t_end=0.2" "rotor stability" "rotor sweep --set sweep.n=40" \
           "rotor map --set map.n1=6 --set map.n2=5" "rotor campbell --set campbell.n=40" \
           "rotor ensemble --set ensemble.n1=2 --set ensemble.n2=2 --set transient.t_end=0.5" \
           "pendulum roots" "pendulum critical --set critical.n_Rm=20" "pendulum map --set map.n_Rm=8 --set map.n_Rw=8" \
           "pendulum transient --set transient.t_end=20" \
           "pendulum ensemble --set ensemble.n1=2 --set ensemble.n2=2 --set transient.t_end=20"; do
  # shellcheck disable=SC2086
  "$AUTOBAL" $cmd --json > j.json 2>err.txt || { echo "FAIL: $cmd --json"; cat err.txt; fail=1; continue; }
  "$PY" -c "
import json, sys
j = json.load(open('j.json'))
u = j.get('units')
if not isinstance(u, dict) or not u:
    print('FAIL: $cmd --json has no units map', file=sys.stderr); sys.exit(1)
missing = [k for k in u if k not in j]
if missing:
    print('FAIL: $cmd --json: units for absent members', missing, file=sys.stderr); sys.exit(1)
for v in u.values(): print(v)
" >> units.txt && echo "ok   $cmd --json has a units map" || fail=1
done
sort -u units.txt > units_unique.txt
echo "distinct unit strings: $(wc -l < units_unique.txt)"
if "$UNITS_CHECK" < units_unique.txt; then echo "ok   every units attribute parses with UDUNITS-2"
else echo "FAIL some units attributes do not parse with UDUNITS-2"; fail=1; fi
exit $fail
