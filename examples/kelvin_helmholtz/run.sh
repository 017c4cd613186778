#!/usr/bin/env bash
# Run the Kelvin-Helmholtz scene (McNally, Lyra & Passy 2012) and print its mode amplitude M(t)
# against the grid reference (kh_grid_reference.txt), with the wall time; the M(t) plot goes to
# the output folder.
# Usage: examples/kelvin_helmholtz/run.sh [NP] [extra lmp args, e.g. -var n 128 -var switch cd]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${SPH_ASTRO_BUILD:-$here/../../build}" && pwd)
# shellcheck disable=SC1091
source "$build/env.sh"
np=${1:-1}; shift || true
out=${SPH_ASTRO_OUT:-$build/output/kelvin_helmholtz}
mkdir -p "$out"
cd "$out"
start=$(date +%s%N)
mpirun -np "$np" lmp -in "$here/in.kelvin_helmholtz" -log log.kh -screen none -var out dump.kh \
       -var root "$SPH_ASTRO_ROOT" -var py "$SPH_ASTRO_PYTHON" "$@"
end=$(date +%s%N)
echo "Kelvin-Helmholtz (McNally et al. 2012, to t = 2) on $np MPI rank(s): output in $out"
grep -E "^Loop time" log.kh
"$SPH_ASTRO_PYTHON" "$here/analyse.py" log.kh --labels SPH --png kh_M.png \
    --reference grid
ms=$(( (end - start) / 1000000 ))
printf 'wall time = %d.%03d s\n' $((ms / 1000)) $((ms % 1000))
echo "density dumps at t = 0, 1, 2: $out/dump.kh.render; M(t) plot: $out/kh_M.png"
