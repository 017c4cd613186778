#!/usr/bin/env bash
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
# Run the whole SPH-ASTRO test suite: checks that the set-up is there (Debian packages, the
# installed LAMMPS, build/, the in-tree lmp of the current sources), brings build/ up to date
# with the sources and runs ctest (arguments are passed on: tools/test.sh -L unit).
# Installs nothing: when something is missing it names it and the command that sets it up.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
problems=()
while read -r p; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
    problems+=("Debian package $p is not installed")
done < <(grep -v '^#' "$root/tools/debian-packages.txt")
cache_value() { sed -n "s/^$1:[A-Z]*=//p" "$root/build/CMakeCache.txt" 2>/dev/null; }
lammps_dir=$(cache_value LAMMPS_DIR)
lammps_src=$(cache_value LAMMPS_SOURCE_DIR)
if [ ! -f "$root/build/CMakeCache.txt" ] || [ ! -f "$root/build/env.sh" ]; then
  problems+=("build/ is not configured")
elif [ ! -f "$lammps_dir/LAMMPSConfig.cmake" ]; then
  problems+=("no installed LAMMPS at '$lammps_dir' (LAMMPS_DIR of build/)")
elif ! LAMMPS_SOURCE_DIR=$lammps_src "$root/tools/lammps_in_tree.sh" --path >/dev/null 2>&1; then
  problems+=("no lmp with SPH-ASTRO built in for the current src/SPH-ASTRO")
fi
if [ ${#problems[@]} -gt 0 ]; then
  printf 'test: %s\n' "${problems[@]}" >&2
  echo "test: set up first with:  tools/setup.sh --no-run" >&2
  exit 1
fi
cmake --build "$root/build" -j "$(nproc)" >/dev/null
ctest --test-dir "$root/build" --output-on-failure "$@"
