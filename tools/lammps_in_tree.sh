#!/usr/bin/env bash
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
#
# SPH-ASTRO as a standard LAMMPS package: copies a LAMMPS source tree to a scratch folder,
# adds src/SPH-ASTRO to it, registers the package there the way LAMMPS registers its own
# packages, and builds lmp with -D PKG_SPH-ASTRO=on (no plugin involved).
#
#   tools/lammps_in_tree.sh                  build (or update) the in-tree lmp; prints its path
#   tools/lammps_in_tree.sh --register TREE  only register SPH-ASTRO in the LAMMPS tree TREE
#                                            (copy of src/SPH-ASTRO included); nothing built
#   tools/lammps_in_tree.sh --path           print the path of the lmp built from the current
#                                            src/SPH-ASTRO; exit 1 (with the command to run)
#                                            when there is none
#   tools/lammps_in_tree.sh --run CMD...     run CMD with that lmp first on PATH and no
#                                            LAMMPS_PLUGIN_PATH (used by the in-tree ctest);
#                                            exit 77 (skipped) when there is none
#
# The LAMMPS source tree is $LAMMPS_SOURCE_DIR, else the 4 Feb 2025 tree that
# tools/fetch_lammps.sh unpacks into the cache (fetched when missing, build mode only).
# Registration (what a LAMMPS developer does by hand, see src/SPH-ASTRO/README):
#   src/SPH-ASTRO/                           the package sources
#   cmake/CMakeLists.txt                     SPH-ASTRO in STANDARD_PACKAGES (after SPH),
#                                            pkg_depends(SPH-ASTRO KSPACE), SPH-ASTRO in the
#                                            list of packages with a Packages/<PKG>.cmake
#   cmake/Modules/Packages/SPH-ASTRO.cmake   HDF5 (C API) for the package (from
#                                            cmake/lammps/Packages/SPH-ASTRO.cmake here)
#   src/Makefile                             sph-astro in PACKAGE and PACKEXT (make yes-sph-astro)
# Cache: ${SPH_ASTRO_CACHE:-~/.cache/sph-astro}/intree-<key>, key = LAMMPS source tree + the
# build options + compiler; it holds the registered tree (lammps/), one CMake build (build/),
# reused incrementally, and bin-<hash>/lmp for each package-source hash built (the newest
# three kept), hash = src/SPH-ASTRO, the CMake module and this script.
set -euo pipefail
shopt -s inherit_errexit
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
cache=${SPH_ASTRO_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/sph-astro}
jobs=${SPH_ASTRO_JOBS:-$(nproc)}
pkg_dir=$root/src/SPH-ASTRO
module=$root/cmake/lammps/Packages/SPH-ASTRO.cmake
opts=(-D CMAKE_BUILD_TYPE=Release -D BUILD_SHARED_LIBS=off -D BUILD_MPI=on -D BUILD_OMP=off
      -D FFT=FFTW3 -D PKG_KSPACE=on -D PKG_SPH-ASTRO=on -D WITH_JPEG=off -D WITH_PNG=off
      -D WITH_FFMPEG=off -D WITH_GZIP=on)

die() { echo "lammps_in_tree: $*" >&2; exit 1; }

# register_package TREE: SPH-ASTRO sources and registration in the LAMMPS tree TREE (idempotent)
register_package() {
  local tree=$1 f
  [ -f "$tree/cmake/CMakeLists.txt" ] && [ -f "$tree/src/Makefile" ] ||
    die "$tree is not a LAMMPS source tree (no cmake/CMakeLists.txt or src/Makefile)"
  # the package folder: changed files copied (unchanged ones keep their time stamps, so an
  # incremental build recompiles only what changed), files gone from the package removed
  mkdir -p "$tree/src/SPH-ASTRO"
  for f in "$pkg_dir"/*; do
    cmp -s "$f" "$tree/src/SPH-ASTRO/${f##*/}" || cp "$f" "$tree/src/SPH-ASTRO/"
  done
  for f in "$tree/src/SPH-ASTRO"/*; do
    [ -e "$pkg_dir/${f##*/}" ] || rm -f "$f"
  done
  cmp -s "$module" "$tree/cmake/Modules/Packages/SPH-ASTRO.cmake" ||
    cp "$module" "$tree/cmake/Modules/Packages/SPH-ASTRO.cmake"
  local cm=$tree/cmake/CMakeLists.txt mk=$tree/src/Makefile
  if ! grep -q '^  SPH-ASTRO$' "$cm"; then
    grep -q '^  SPH$' "$cm" || die "$cm: no '  SPH' line in STANDARD_PACKAGES to add SPH-ASTRO after"
    sed -i '/^  SPH$/a\  SPH-ASTRO' "$cm"
  fi
  if ! grep -q '^pkg_depends(SPH-ASTRO KSPACE)$' "$cm"; then
    grep -q '^pkg_depends(' "$cm" || die "$cm: no pkg_depends() lines"
    sed -i '0,/^pkg_depends(/s//pkg_depends(SPH-ASTRO KSPACE)\n&/' "$cm"
  fi
  if ! grep -q '^foreach(PKG_WITH_INCL KSPACE SPH-ASTRO ' "$cm"; then
    grep -q '^foreach(PKG_WITH_INCL KSPACE ' "$cm" ||
      die "$cm: no 'foreach(PKG_WITH_INCL KSPACE ...)' list to add SPH-ASTRO to"
    sed -i 's/^foreach(PKG_WITH_INCL KSPACE /&SPH-ASTRO /' "$cm"
  fi
  # make: the first list (PACKAGE) and the packages needing external libraries (PACKEXT)
  if ! grep -q $'^\tsph-astro \\\\$' "$mk"; then
    grep -q $'^\tsph \\\\$' "$mk" && grep -q '^PACKEXT = \\$' "$mk" ||
      die "$mk: no 'sph' entry in PACKAGE or no PACKEXT list"
    sed -i $'0,/^\tsph \\\\$/s//&\\n\tsph-astro \\\\/' "$mk"
    sed -i $'s/^PACKEXT = \\\\$/&\\n\tsph-astro \\\\/' "$mk"
  fi
}

# the LAMMPS source tree; fetched only when building
lammps_source() {
  if [ -n "${LAMMPS_SOURCE_DIR:-}" ]; then
    (cd "$LAMMPS_SOURCE_DIR" && pwd -P)
  elif [ "${1:-}" = fetch ]; then
    cd "$("$here/fetch_lammps.sh" "$cache/src" | tail -1)" && pwd -P
  else
    local d=$cache/src/lammps-4Feb2025
    [ -d "$d/cmake" ] || die "no LAMMPS source tree at $d: run tools/setup.sh --no-run"
    (cd "$d" && pwd -P)
  fi
}

package_hash() {
  { (cd "$pkg_dir" && sha256sum -- *); sha256sum <"$module"; sha256sum <"$0"; } |
    sha256sum | cut -c1-16
}

cache_dir() {
  local key
  key=$(printf '%s\n' "dir:$1" "${opts[@]}" "$(c++ --version | head -1)" | sha256sum | cut -c1-16)
  echo "$cache/intree-$key"
}

# the lmp of the current package sources, or exit 1 saying how to build it
find_lmp() {
  local src dir hash
  src=$(lammps_source)
  dir=$(cache_dir "$src")
  hash=$(package_hash)
  if [ ! -x "$dir/bin-$hash/lmp" ]; then
    echo "lammps_in_tree: no in-tree lmp for the current src/SPH-ASTRO (sources $hash) in $dir." >&2
    echo "lammps_in_tree: build it with: tools/lammps_in_tree.sh   (or tools/setup.sh --no-run)" >&2
    exit 1
  fi
  echo "$dir/bin-$hash/lmp"
}

case "${1:-}" in
  --register)
    [ $# = 2 ] || die "usage: lammps_in_tree.sh --register LAMMPS_TREE"
    register_package "$2"
    echo "lammps_in_tree: SPH-ASTRO registered in $2 (cmake: -D PKG_SPH-ASTRO=on -D PKG_KSPACE=on)"
    exit 0
    ;;
  --path)
    find_lmp
    exit 0
    ;;
  --run)
    shift
    [ $# -ge 1 ] || die "usage: lammps_in_tree.sh --run CMD..."
    # (not built for the current sources: exit status 77, which ctest reports as skipped)
    lmp=$(find_lmp) || { echo "lammps_in_tree: skipped: no in-tree lmp for the current sources"; exit 77; }
    # the binary must be the in-tree one: SPH-ASTRO among its installed packages
    help=$("$lmp" -h) || die "$lmp -h failed"
    pkgs=$(sed -n '/^Installed packages:/,/^List of individual style/p' <<<"$help")
    grep -qw 'SPH-ASTRO' <<<"$pkgs" || die "$lmp does not list SPH-ASTRO among its installed packages"
    unset LAMMPS_PLUGIN_PATH
    export PATH="${lmp%/lmp}:$PATH"
    echo "lammps_in_tree: lmp = $lmp (SPH-ASTRO built in, no plugin path)"
    exec "$@"
    ;;
  "") ;;
  *) die "unknown option $1 (see the head of $0)" ;;
esac

src=$(lammps_source fetch)
dir=$(cache_dir "$src")
hash=$(package_hash)
mkdir -p "$dir"
exec 9>"$dir/lock"
flock 9
if [ -x "$dir/bin-$hash/lmp" ]; then
  echo "lammps_in_tree: reusing $dir/bin-$hash/lmp" >&2
  echo "$dir/bin-$hash/lmp"
  exit 0
fi
if [ ! -f "$dir/lammps/copied" ]; then
  echo "lammps_in_tree: copying the LAMMPS tree $src to $dir/lammps" >&2
  rm -rf "$dir/lammps"
  mkdir -p "$dir/lammps"
  # what the CMake build reads (no examples, benchmarks, potentials, manual sources)
  (cd "$src" && tar -cf - --exclude=./doc/src --exclude=./doc/utils --exclude=./doc/graphviz \
     ./cmake ./src ./lib ./python ./doc ./tools ./fortran ./LICENSE ./README) |
    (cd "$dir/lammps" && tar -xf -)
  mkdir -p "$dir/lammps/potentials" "$dir/lammps/bench"
  touch "$dir/lammps/copied"
fi
register_package "$dir/lammps"
if [ -f "$dir/build/CMakeCache.txt" ]; then
  echo "lammps_in_tree: updating lmp with SPH-ASTRO in $dir/build (changed files only)" >&2
else
  echo "lammps_in_tree: building lmp with SPH-ASTRO in $dir/build (about 10 minutes on 2 cores)" >&2
fi
start=$(date +%s)
cmake -S "$dir/lammps/cmake" -B "$dir/build" "${opts[@]}" >"$dir/configure.log" 2>&1 ||
  { tail -30 "$dir/configure.log" >&2; die "configure failed (log: $dir/configure.log)"; }
grep -q 'SPH-ASTRO' "$dir/build/styles/lmpinstalledpkgs.h" ||
  die "SPH-ASTRO is not among the enabled packages (see $dir/configure.log)"
cmake --build "$dir/build" --target lmp -j "$jobs" >"$dir/build.log" 2>&1 ||
  { grep -B2 -A8 'error' "$dir/build.log" | head -60 >&2; die "build failed (log: $dir/build.log)"; }
mkdir -p "$dir/bin-$hash"
cp "$dir/build/lmp" "$dir/bin-$hash/lmp.tmp"
mv "$dir/bin-$hash/lmp.tmp" "$dir/bin-$hash/lmp"
# keep the three newest binaries
ls -1dt "$dir"/bin-* | tail -n +4 | xargs -r rm -rf
echo "lammps_in_tree: built $dir/bin-$hash/lmp in $(($(date +%s) - start)) s" >&2
echo "$dir/bin-$hash/lmp"
