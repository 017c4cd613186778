#!/usr/bin/env bash
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
#
# The plugin's integer sizes come from the LAMMPS it is configured against, and a plugin whose
# sizes differ from the loading LAMMPS' refuses to load.
#
# Usage: plugin_lammps_sizes.sh WORKDIR LAMMPS_DIR LAMMPS_SOURCE_DIR GOOD_PLUGIN
#
# In WORKDIR: a LAMMPS installation that declares LAMMPS_BIGBIG (a copy of the LAMMPSConfig
# files of LAMMPS_DIR with LAMMPS_SMALLBIG replaced, the library, headers and lmp linked from
# the real smallbig installation), the project configured against it (-O0: only the integer
# sizes matter here), its plugin and the probe unittest/sizes_probe_plugin.cpp built. Checks:
#   1. the configure reports bigbig and the plugin's compile flags carry -DLAMMPS_BIGBIG only;
#   2. the real lmp does not take the bigbig plugin's styles: "plugin load" is refused (by the
#      dynamic linker: the mangled names of LAMMPS functions with tagint arguments differ, or
#      by the plugin's size check) and pair_style sph/astro is then an error;
#   3. the probe (the plugin's size check alone, compiled bigbig) stops lmp with the check's
#      error message;
#   4. the same lmp loads GOOD_PLUGIN (the plugin of the build under test) and runs.
set -euo pipefail
[ $# = 4 ] || { sed -n '8p' "$0" >&2; exit 2; }
work=$1 lammps_dir=$2 lammps_src=$3 good_plugin=$4
root=$(cd "$(dirname "$0")/.." && pwd)
fail() { echo "FAIL: $*"; exit 1; }

prefix=$(cd "$lammps_dir/../../.." && pwd)
grep -q 'INTERFACE_COMPILE_DEFINITIONS "LAMMPS_SMALLBIG"' "$lammps_dir/LAMMPS_Targets.cmake" ||
  fail "$lammps_dir/LAMMPS_Targets.cmake does not declare LAMMPS_SMALLBIG (the test expects it)"
rm -rf "$work"
fake=$work/fake_bigbig
mkdir -p "$fake/lib/cmake" "$fake/bin"
cp -r "$lammps_dir" "$fake/lib/cmake/LAMMPS"
sed -i 's/"LAMMPS_SMALLBIG"/"LAMMPS_BIGBIG"/' "$fake/lib/cmake/LAMMPS/LAMMPS_Targets.cmake"
ln -s "$prefix"/lib/liblammps.so* "$fake/lib/"
ln -s "$prefix/include" "$fake/include"
ln -s "$prefix/bin/lmp" "$fake/bin/lmp"

echo "+ configure against $fake (declares LAMMPS_BIGBIG)"
cmake -S "$root/cmake" -B "$work/build" -D "LAMMPS_DIR=$fake/lib/cmake/LAMMPS" \
      -D "LAMMPS_SOURCE_DIR=$lammps_src" -D CMAKE_BUILD_TYPE=None -D CMAKE_CXX_FLAGS=-O0 >"$work/configure.log" 2>&1 ||
  { cat "$work/configure.log"; fail "configure failed"; }
grep 'SPH-ASTRO: LAMMPS' "$work/configure.log"
grep -q 'SPH-ASTRO: LAMMPS [0-9]* (bigbig)' "$work/configure.log" ||
  fail "configure did not take LAMMPS_SIZES bigbig from the LAMMPS found"
flags=$work/build/CMakeFiles/sphastroplugin.dir/flags.make
grep -q -- '-DLAMMPS_BIGBIG' "$flags" || fail "the plugin is not compiled with -DLAMMPS_BIGBIG"
! grep -q -- '-DLAMMPS_SMALLBIG' "$flags" || fail "the plugin is compiled with -DLAMMPS_SMALLBIG too"
echo "ok: the plugin is compiled with -DLAMMPS_BIGBIG"

echo "+ build the bigbig plugin and probe"
cmake --build "$work/build" --target sphastroplugin sizes_probe -j 2 >"$work/build.log" 2>&1 ||
  { tail -40 "$work/build.log"; fail "the plugin did not build with LAMMPS_BIGBIG"; }

cd "$work"
unset LAMMPS_PLUGIN_PATH
size_error='SPH-ASTRO plugin: integer sizes (bytes) tagint 8 imageint 8 bigint 8 differ from this LAMMPS. tagint 4 imageint 4 bigint 8'
printf 'plugin load %s\npair_style sph/astro\n' "$work/build/plugins/sphastroplugin.so" >in.bigbig
echo "+ lmp (smallbig) -in in.bigbig"
if lmp -in in.bigbig -log none >bigbig.out 2>&1; then
  cat bigbig.out
  fail "the smallbig lmp took pair_style sph/astro from the bigbig plugin"
fi
cat bigbig.out
if grep -q "$size_error" bigbig.out; then
  echo "ok: the bigbig plugin is refused by its size check"
elif grep -q 'Open of file .*sphastroplugin.so failed: .*undefined symbol' bigbig.out &&
     grep -q "Unrecognized pair style 'sph/astro'" bigbig.out; then
  echo "ok: the bigbig plugin is refused by the dynamic linker; pair_style sph/astro is unknown"
else
  fail "lmp failed, but neither with the size check's error nor with a refused plugin load"
fi

printf 'plugin load %s\n' "$work/build/unittest/sizes_probe.so" >in.probe
echo "+ lmp (smallbig) -in in.probe"
if lmp -in in.probe -log none >probe.out 2>&1; then
  cat probe.out
  fail "the smallbig lmp loaded the bigbig probe without an error"
fi
cat probe.out
grep -q "$size_error" probe.out || fail "lmp failed without the size check's error"
echo "ok: the size check stops lmp with its error"

printf 'plugin load %s\nplugin list\n' "$good_plugin" >in.good
lmp -in in.good -log none >good.out 2>&1 || { cat good.out; fail "the plugin under test did not load"; }
grep -q 'pair style plugin sph/astro$' good.out || { cat good.out; fail "pair sph/astro not registered"; }
echo "ok: the plugin of this build loads and registers its styles"
