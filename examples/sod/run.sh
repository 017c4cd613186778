#!/usr/bin/env bash
# Run the Sod shock tube and print its L1 errors against the exact Riemann solution and
# its wall time. Usage: examples/sod/run.sh [NP] [extra lmp args, e.g. -var nx 96]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${SPH_ASTRO_BUILD:-$here/../../build}" && pwd)
# shellcheck disable=SC1091
source "$build/env.sh"
np=${1:-1}; shift || true
out=${SPH_ASTRO_OUT:-$build/output/sod}
mkdir -p "$out"
cd "$out"
start=$(date +%s%N)
mpirun -np "$np" lmp -in "$here/in.sod" -log log.sod -screen none -var out dump.sod "$@"
end=$(date +%s%N)
echo "Sod shock tube (gamma 5/3, t = 0.2) on $np MPI rank(s): output in $out"
grep -E "^Loop time" log.sod
"$SPH_ASTRO_PYTHON" "$here/analyse.py" dump.sod --periodic --png sod.png
ms=$(( (end - start) / 1000000 ))
printf 'wall time = %d.%03d s\n' $((ms / 1000)) $((ms % 1000))
echo "profile plot: $out/sod.png"
