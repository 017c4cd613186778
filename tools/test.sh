#!/usr/bin/env bash
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
# Run the SPH-ASTRO test suite: checks that the set-up is there (Debian packages, the installed
# LAMMPS, build/), brings build/ up to date with the sources and runs ctest on all cores, all
# tests but those labelled long (a minute or more each); --all runs them too (CI does). Other
# arguments are passed on to ctest (tools/test.sh -L unit). The in-tree test is skipped unless
# tools/setup.sh --in-tree has built that lmp for the current sources.
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
fi
if [ ${#problems[@]} -gt 0 ]; then
  printf 'test: %s\n' "${problems[@]}" >&2
  echo "test: set up first with:  tools/setup.sh --no-run" >&2
  exit 1
fi
cmake --build "$root/build" -j "$(nproc)" >/dev/null
select=(-LE long)
if [ "${1:-}" = --all ]; then
  select=()
  shift
fi
ctest --test-dir "$root/build" --output-on-failure -j "$(nproc)" ${select[@]+"${select[@]}"} "$@"
