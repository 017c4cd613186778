#!/usr/bin/env bash
# Run a scene's input on NP ranks and assert its L1 errors.
# Usage: run_scene_check.sh BUILD_DIR NP SCENE "rho=MAX,vx=MAX,..." [lmp args...]
set -euo pipefail
build=$1 np=$2 scene=$3 bounds=$4; shift 4
here=$(cd "$(dirname "$0")/.." && pwd)
work=$build/test_output/${scene}_np${np}_$(echo "$*" | tr -c "a-zA-Z0-9.\n" "_")
mkdir -p "$work" && cd "$work"
mpirun -np "$np" lmp -in "$here/examples/$scene/in.$scene" -log log.$scene -screen none \
  -var out dump.$scene "$@"
"$SPH_ASTRO_PYTHON" "$here/examples/$scene/analyse.py" dump.$scene --periodic --assert "$bounds"
