#!/usr/bin/env bash
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
#
# The plugin built for the build machine's instruction set (SPH_ASTRO_NATIVE, the default)
# gives the same numbers bit for bit as the plugin built for the generic one: both compile with
# -ffp-contract=off (cmake/CMakeLists.txt), so no product and sum is fused into an FMA.
#
# Usage: plugin_generic_same_bits.sh WORKDIR LAMMPS_DIR LAMMPS_SOURCE_DIR BUILD_DIR
#
# In WORKDIR: the project configured with SPH_ASTRO_NATIVE=OFF and its plugin built; then
# Sedov (n 10, individual steps, 2 ranks), the Evrard collapse (n 6, MSM gravity, to t 0.3) and
# with the tree (n 8, individual steps, 2 ranks, to t 0.3: its sums run in a fixed number of
# lanes, whatever the vector width) run with each plugin, and their final dumps must be the same
# bytes. Skipped (77) when the
# plugin of BUILD_DIR is not compiled with -march=native (nothing to compare).
set -euo pipefail
[ $# = 4 ] || { sed -n '9p' "$0" >&2; exit 2; }
work=$1 lammps_dir=$2 lammps_src=$3 build=$4
root=$(cd "$(dirname "$0")/.." && pwd)
fail() { echo "FAIL: $*"; exit 1; }

grep -q -- '-march=native' "$build/CMakeFiles/sphastroplugin.dir/flags.make" ||
  { echo "the plugin of $build is not built with -march=native: nothing to compare"; exit 77; }
rm -rf "$work"
mkdir -p "$work"
echo "+ configure and build the plugin with SPH_ASTRO_NATIVE=OFF"
cmake -S "$root/cmake" -B "$work/generic" -D "LAMMPS_DIR=$lammps_dir" \
      -D "LAMMPS_SOURCE_DIR=$lammps_src" -D CMAKE_BUILD_TYPE=Release -D SPH_ASTRO_TESTS=OFF \
      -D SPH_ASTRO_NATIVE=OFF >"$work/configure.log" 2>&1 ||
  { cat "$work/configure.log"; fail "configure failed"; }
! grep -q -- '-march=native' "$work/generic/CMakeFiles/sphastroplugin.dir/flags.make" ||
  fail "SPH_ASTRO_NATIVE=OFF still compiles with -march=native"
cmake --build "$work/generic" --target sphastroplugin -j 2 >"$work/build.log" 2>&1 ||
  { tail -40 "$work/build.log"; fail "the generic plugin did not build"; }

cd "$work"
for kind in native generic; do
  plugins=$build/plugins
  [ $kind = generic ] && plugins=$work/generic/plugins
  echo "+ Sedov and Evrard with the $kind plugin ($plugins)"
  LAMMPS_PLUGIN_PATH=$plugins mpirun -np 2 lmp -in "$root/examples/sedov/in.sedov" -var n 10 \
    -var steps individual -var out "sedov.$kind" -log "log.sedov.$kind" >/dev/null ||
    fail "Sedov with the $kind plugin"
  LAMMPS_PLUGIN_PATH=$plugins lmp -in "$root/examples/evrard/in.evrard" -var n 6 -var tend 0.3 \
    -var gravity msm -var out "evrard.$kind" -log "log.evrard.$kind" >/dev/null ||
    fail "Evrard with the $kind plugin"
  LAMMPS_PLUGIN_PATH=$plugins mpirun -np 2 lmp -in "$root/examples/evrard/in.evrard" -var n 8 \
    -var tend 0.3 -var steps individual -var gravity tree -var out "evrard_tree.$kind" \
    -log "log.evrard_tree.$kind" >/dev/null || fail "Evrard (tree) with the $kind plugin"
done
for scene in sedov evrard evrard_tree; do
  [ -s "$scene.native" ] || fail "no dump $scene.native"
  cmp "$scene.native" "$scene.generic" || fail "the $scene dumps of the two plugins differ"
  echo "ok: the $scene dumps are the same bytes ($(wc -l <"$scene.native") lines)"
done
