#!/usr/bin/env bash
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
# SPH-ASTRO one-command setup: installs the Debian packages, obtains and builds LAMMPS
# 4 Feb 2025 (cached in ~/.cache/sph-astro, reused when present), builds the plugin and
# the tests in ./build, then runs the flagship Sod shock tube and prints its errors and
# wall time.
#   tools/setup.sh                 set up and run the flagship scene
#   tools/setup.sh --no-run        set up only
#   LAMMPS_SOURCE_DIR=/path tools/setup.sh   use your own LAMMPS source tree
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
run_flagship=1
[ "${1:-}" = "--no-run" ] && run_flagship=0

packages=(cmake g++ make xz-utils dpkg-dev libopenmpi-dev openmpi-bin libfftw3-dev libgtest-dev
          python3 python3-numpy python3-matplotlib python3-h5py python3-venv python3-pip
          python3-setuptools python3-wheel python3-pytest libhdf5-dev python3-yt)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  sudo=""; [ "$(id -u)" = 0 ] || sudo=sudo
  echo "setup: installing Debian packages: ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
fi

cmake_args=()
[ -n "${LAMMPS_SOURCE_DIR:-}" ] && cmake_args+=(-D "LAMMPS_SOURCE_DIR=$LAMMPS_SOURCE_DIR")
cmake -S "$root/cmake" -B "$root/build" "${cmake_args[@]}" >/dev/null
cmake --build "$root/build" -j "$(nproc)" >/dev/null
"$root/tools/install_python.sh" "$root/build"
echo "setup: built $root/build/plugins/sphastroplugin.so; 'source build/env.sh' puts lmp in reach"

if [ $run_flagship = 1 ]; then
  "$root/examples/sod/run.sh" 1
fi
