"""Re-run every transient member of a two-plane design (docs/rotor.md "Design", "Two planes",
"Transients") by separate `autobal rotor transient` runs and compare P(balance), the median and the
worst time to balance with the design's.  The member list is rebuilt here from the documented rule,
not read from the design: start angles (n_start each) plane 1 ball 1 at k step, ball 2 at (k + 1/2)
step, plane 2's balls at (a + 1/4) step and (b + 3/4) step, step = 2 pi / n_start; each plane's
unbalance at both ends of its range; the speed at both ends of the range.

usage: rotor_design_two_planes_transients.py AUTOBAL best.ini design.json n_start t_end
       w_min w_max u1_min u1_max u2_min u2_max r0_1 r0_2"""
import itertools, json, math, subprocess, sys

autobal, best, djson = sys.argv[1:4]
n = int(sys.argv[4]); t_end = float(sys.argv[5])
w = [float(sys.argv[6]), float(sys.argv[7])]
u1 = [float(sys.argv[8]), float(sys.argv[9])]
u2 = [float(sys.argv[10]), float(sys.argv[11])]
r01, r02 = float(sys.argv[12]), float(sys.argv[13])
d = json.load(open(djson))["designs"][0]
step = 2 * math.pi / n
times, nbal = [], 0
for (om, a, b, c, e, s1, s2) in itertools.product(w, range(n), range(n), range(n), range(n), u1, u2):
    psi1 = "%.17g,%.17g" % (a * step, (b + 0.5) * step)
    psi2 = "%.17g,%.17g" % ((c + 0.25) * step, (e + 0.75) * step)
    out = subprocess.run([autobal, "rotor", "transient", best, "--json",
                          "--set", "rotor.omega=%.17g" % om, "--set", "plane1.m0=%.17g" % (s1 / r01),
                          "--set", "plane2.m0=%.17g" % (s2 / r02), "--set", "plane1.ball_psi=" + psi1,
                          "--set", "plane2.ball_psi=" + psi2, "--set", "transient.t_end=%g" % t_end,
                          "--set", "transient.stop_at_balance=true", "--set", "transient.revs_out=10"],
                         capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit("rotor transient failed: " + out.stderr)
    j = json.loads(out.stdout)
    ok = bool(j["balanced"]) and j["time_to_balance"] is not None
    nbal += ok
    times.append(j["time_to_balance"] if ok else math.inf)
times.sort()
m = len(times)
med = times[m // 2] if m % 2 else 0.5 * (times[m // 2 - 1] + times[m // 2])
P = nbal / m
print("direct runs: %d members, P %.4f, median %.4g s, worst %.4g s; design: P %s, median %s, worst %s, members %s"
      % (m, P, med, times[-1], d["p_balance"], d["time_to_balance_median"], d["time_to_balance_worst"],
         d["transient_members"]))
assert d["transient_members"] == m, "member count"
assert abs(d["p_balance"] - P) < 1e-12, "P(balance)"
def close(x, y):  # JSON writes inf as null
    if x is None or y == math.inf: return x is None and y == math.inf
    return abs(x - y) <= 0.02 * y + 0.01
assert close(d["time_to_balance_median"], med), "median time"
assert close(d["time_to_balance_worst"], times[-1]), "worst time"
