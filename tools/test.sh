#!/usr/bin/env bash
# Run the whole SPH-ASTRO test suite (sets everything up first if needed).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/tools/setup.sh" --no-run
ctest --test-dir "$root/build" --output-on-failure "$@"
