#!/bin/bash
# app_archive_python: the sample archive written by the C library (test_archive --write)
# read back by Debian's python3 with h5py and xarray (h5netcdf, and netCDF-C when the
# netCDF4 module exists).  Environment from tests/CMakeLists.txt: AUTOBAL (the CLI,
# used only to locate the build tree), SCRATCH, PY.
set -euo pipefail
: "${AUTOBAL:?AUTOBAL not set}" "${SCRATCH:?SCRATCH not set}"
PY="${PY:-/usr/bin/python3}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
writer="$(dirname "$AUTOBAL")/../tests/test_archive"
if [ ! -x "$writer" ]; then
  echo "FAIL: writer $writer not built" >&2
  exit 1
fi
if ! "$PY" -c "import h5py, xarray, h5netcdf" 2>/dev/null; then
  echo "FAIL: $PY lacks h5py/xarray/h5netcdf" >&2
  exit 1
fi
mkdir -p "$SCRATCH"
out="$SCRATCH/sample.h5"
rm -f "$out" "$out".partial-*
"$writer" --write "$out"
test -f "$out"
if ls "$out".partial-* >/dev/null 2>&1; then
  echo "FAIL: temporary file left next to $out" >&2
  exit 1
fi
"$PY" "$here/../archive_readback.py" "$out"
