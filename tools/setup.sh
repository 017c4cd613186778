#!/usr/bin/env bash
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
# SPH-ASTRO one-command setup: installs the Debian packages (tools/debian-packages.txt),
# obtains, builds and installs LAMMPS 4 Feb 2025 (cached in ~/.cache/sph-astro, reused when
# present), builds the plugin and the tests in ./build against it (find_package(LAMMPS)),
# then runs the flagship Sod shock tube and prints its errors and wall time.
#   tools/setup.sh                 set up and run the flagship scene
#   tools/setup.sh --no-run        set up only
#   tools/setup.sh --in-tree       also build lmp with SPH-ASTRO as a standard package
#                                  (tools/lammps_in_tree.sh, about 10 minutes the first time;
#                                  its ctest is skipped without it)
#   LAMMPS_SOURCE_DIR=/path tools/setup.sh
#                                  build your own LAMMPS source tree (nothing downloaded)
#   LAMMPS_DIR=<prefix>/lib/cmake/LAMMPS LAMMPS_SOURCE_DIR=/path tools/setup.sh
#                                  use an installed LAMMPS (shared library, PLUGIN and KSPACE
#                                  packages) and the source tree it was built from
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
run_flagship=1 in_tree=0
for arg in "$@"; do
  case $arg in
    --no-run) run_flagship=0 ;;
    --in-tree) in_tree=1 ;;
    *) echo "setup: unknown option $arg (allowed: --no-run, --in-tree)" >&2; exit 2 ;;
  esac
done

mapfile -t packages < <(grep -v '^#' "$root/tools/debian-packages.txt")
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

if [ -n "${LAMMPS_DIR:-}" ]; then
  [ -n "${LAMMPS_SOURCE_DIR:-}" ] ||
    { echo "setup: LAMMPS_DIR needs LAMMPS_SOURCE_DIR (the source tree it was built from)" >&2; exit 1; }
  lammps_dir=$LAMMPS_DIR
  lammps_src=$(cd "$LAMMPS_SOURCE_DIR" && pwd -P)
else
  cache=$("$root/tools/build_lammps.sh" "${LAMMPS_SOURCE_DIR:-}" | tail -1)
  lammps_dir=$cache/install/lib/cmake/LAMMPS
  lammps_src=$(cd "$cache/src" && pwd -P)
fi
echo "setup: LAMMPS $lammps_dir (source $lammps_src)"
cmake -S "$root/cmake" -B "$root/build" -D "LAMMPS_DIR=$lammps_dir" \
      -D "LAMMPS_SOURCE_DIR=$lammps_src" >/dev/null
cmake --build "$root/build" -j "$(nproc)" >/dev/null
"$root/tools/install_python.sh" "$root/build"
echo "setup: built $root/build/plugins/sphastroplugin.so; 'source build/env.sh' puts lmp in reach"
if [ $in_tree = 1 ]; then
  LAMMPS_SOURCE_DIR=$lammps_src "$root/tools/lammps_in_tree.sh" >/dev/null
  echo "setup: built lmp with SPH-ASTRO as a standard package ($(LAMMPS_SOURCE_DIR=$lammps_src "$root/tools/lammps_in_tree.sh" --path))"
fi

if [ $run_flagship = 1 ]; then
  "$root/examples/sod/run.sh" 1
fi
