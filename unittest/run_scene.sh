#!/usr/bin/env bash
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
# SPH-ASTRO - astrophysical SPH for LAMMPS. This software is distributed under the GNU General
# Public License version 2 (the same licence as LAMMPS); see the LICENSE file.
#
# Run one scene in its own directory and analyse it: the driver of the ctests declared with
# add_scene_test (cmake/SphAstroTesting.cmake).
#
# Usage: run_scene.sh WORKDIR RANKS INPUT [--copy FILE]... [lmp arguments...]
#                     --analyse SCRIPT [analysis arguments...]
#
# In WORKDIR (created if needed): copies the FILEs, runs
#   [mpirun -np RANKS] lmp -in INPUT -log log.lammps -screen none [lmp arguments...]
# (lmp itself for RANKS 1), then $SPH_ASTRO_PYTHON SCRIPT [analysis arguments...].
# Exit status: the first that failed. On a failed lmp run the end of log.lammps is printed.
set -euo pipefail
usage() { sed -n '8,9p' "$0" | sed 's/^# //' >&2; exit 2; }
[ $# -ge 5 ] || usage
work=$1 ranks=$2 input=$3
shift 3
copies=()
while [ $# -gt 0 ] && [ "$1" = --copy ]; do
  copies+=("$2")
  shift 2
done
lmp_args=()
while [ $# -gt 0 ] && [ "$1" != --analyse ]; do
  lmp_args+=("$1")
  shift
done
[ $# -ge 2 ] || usage
shift
script=$1
shift

mkdir -p "$work"
cd "$work"
for f in ${copies[@]+"${copies[@]}"}; do
  cp -f "$f" .
done
run=(lmp -in "$input" -log log.lammps -screen none ${lmp_args[@]+"${lmp_args[@]}"})
if [ "$ranks" -gt 1 ]; then
  run=(mpirun -np "$ranks" "${run[@]}")
fi
echo "in $work:"
echo "+ ${run[*]}"
"${run[@]}" || {
  status=$?
  echo "lmp failed (exit status $status); end of log.lammps:"
  tail -n 20 log.lammps 2>/dev/null || true
  exit "$status"
}
echo "+ ${SPH_ASTRO_PYTHON:-python3} $script $*"
exec "${SPH_ASTRO_PYTHON:-python3}" "$script" "$@"
