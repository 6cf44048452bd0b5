#!/usr/bin/env bash
# Install everything autobal needs on Debian (idempotent; run as root or with sudo).
#   scripts/deps.sh           build, tests, examples, pictures
#   scripts/deps.sh --bench   also what the benchmarks compare against (SUNDIALS) and perf (a sampling
#                             profiler: bench/issue20.py's time share of the right-hand side)
set -euo pipefail
PKGS="build-essential cmake ninja-build pkg-config git libgsl-dev libhdf5-dev hdf5-tools libinih-dev libudunits2-dev libgmp-dev udunits-bin
      python3 python3-numpy python3-scipy python3-sympy python3-h5py python3-xarray python3-h5netcdf python3-matplotlib valgrind
      libopenmpi-dev openmpi-bin"
if [ "${1:-}" = --bench ]; then PKGS="$PKGS libsundials-dev linux-perf"; fi
missing=""
for p in $PKGS; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  echo "autobal: installing Debian packages:$missing"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends $missing
fi
