#!/usr/bin/env bash
# Installs every Debian package the project builds, tests and reports with.
# Idempotent: packages already present are skipped; safe to run repeatedly.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev            # small fixed-size vectors and matrices
  libgtest-dev libgmock-dev # unit tests and gates
  libbenchmark-dev         # benchmarks/
  libhdf5-dev              # fields.h5, reference_data/*.h5
  libopenmpi-dev openmpi-bin # distributed runs (solver/dist/), mpirun for their tests
  libgsl-dev               # quadrature and ODE cross-checks
  libtomlplusplus-dev      # scene files
  libcli11-dev             # the pdmpm command line
  libfmt-dev               # messages and tables
  nlohmann-json3-dev       # summary.json, gates.json
  python3-matplotlib python3-numpy python3-h5py python3-jinja2 python3-scipy  # reports/
  lammps                   # independent PERI implementation to compare against
)

# Opt-in: ParaView (pvpython) and a virtual X server for the test that opens the
# fields in ParaView (verification/unit/io/fields_writer_paraview_test.cpp, skipped without them).
if [ "${PDMPM_WITH_PARAVIEW:-0}" = "1" ]; then
  packages+=(paraview python3-paraview xvfb x11-utils)  # x11-utils: xdpyinfo, the X server readiness check
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install_deps: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
