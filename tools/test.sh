#!/usr/bin/env bash
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
# Run the whole SPH-ASTRO test suite (sets everything up first if needed).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/tools/setup.sh" --no-run
ctest --test-dir "$root/build" --output-on-failure "$@"
