#!/usr/bin/env bash
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
# Build LAMMPS (MPI, FFTW3, KSPACE, PLUGIN, SPH, shared library) into a cache outside the repo
# and install it there (cmake --install), so that find_package(LAMMPS) finds it.
# Usage: tools/build_lammps.sh [LAMMPS_SOURCE_DIR]
# Prints the cache directory on its last line; it holds `src` (a link to the LAMMPS source
# tree), `build` (the CMake build) and `install` (the installed LAMMPS: bin/lmp,
# lib/liblammps.so, lib/cmake/LAMMPS/LAMMPSConfig.cmake). The cache key is the tarball
# checksum (or the given source directory) plus the configure options, so a changed option
# gives a fresh build.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
cache=${SPH_ASTRO_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/sph-astro}
jobs=${SPH_ASTRO_JOBS:-$(nproc)}
opts=(-D CMAKE_BUILD_TYPE=Release -D BUILD_SHARED_LIBS=on -D BUILD_MPI=on -D BUILD_OMP=off
      -D FFT=FFTW3 -D PKG_KSPACE=on -D PKG_PLUGIN=on -D PKG_SPH=on -D LAMMPS_EXCEPTIONS=on
      -D WITH_JPEG=off -D WITH_PNG=off -D WITH_FFMPEG=off -D WITH_GZIP=on)
if [ $# -ge 1 ] && [ -n "$1" ]; then
  src=$(cd "$1" && pwd)
  [ -f "$src/cmake/CMakeLists.txt" ] || { echo "build_lammps: $src is not a LAMMPS source tree (no cmake/CMakeLists.txt)" >&2; exit 1; }
  origin="dir:$src"
else
  src=$("$here/fetch_lammps.sh" "$cache/src" | tail -1)
  origin="sha:3671165bd52fad36734e0a9136c5bc5ecb225e03988f8c89aa13366a8b53b1c7"
fi
key=$(printf '%s\n' "$origin" "${opts[@]}" "$(c++ --version | head -1)" | sha256sum | cut -c1-16)
dir="$cache/lammps-$key"
if [ -x "$dir/build/lmp" ] && [ -f "$dir/build/liblammps.so" ] && [ -f "$dir/complete" ]; then
  echo "build_lammps: reusing cached LAMMPS build $dir" >&2
else
  rm -f "$dir/installed"
  echo "build_lammps: building LAMMPS from $src into $dir (about 12 minutes on 2 cores)" >&2
  mkdir -p "$dir"
  ln -sfn "$src" "$dir/src"
  cmake -S "$src/cmake" -B "$dir/build" "${opts[@]}" >"$dir/configure.log" 2>&1 ||
    { tail -30 "$dir/configure.log" >&2; exit 1; }
  cmake --build "$dir/build" -j "$jobs" >"$dir/build.log" 2>&1 ||
    { tail -40 "$dir/build.log" >&2; exit 1; }
  touch "$dir/complete"
fi
exec 9>"$dir/install.lock"
flock 9
if [ ! -f "$dir/installed" ]; then
  cmake --install "$dir/build" --prefix "$dir/install" >"$dir/install.log" 2>&1 ||
    { tail -20 "$dir/install.log" >&2; exit 1; }
  touch "$dir/installed"
fi
echo "$dir"
