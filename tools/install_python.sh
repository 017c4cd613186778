#!/usr/bin/env bash
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
# Install the sphastro Python package (python/) into the virtual environment build/venv:
# made from Debian's /usr/bin/python3 with --system-site-packages (numpy, matplotlib, h5py,
# pytest come from Debian), the package installed editable without a download
# (--no-build-isolation --no-deps: Debian's setuptools >= 64 builds it, PEP 660).
#   tools/install_python.sh [BUILD_DIR]      (default: ./build)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
venv=$build/venv
python=${SPH_ASTRO_BASE_PYTHON:-/usr/bin/python3}

if [ ! -x "$venv/bin/python" ]; then
  "$python" -m venv --system-site-packages "$venv"
fi
# an editable install is a .pth file pointing at python/: reinstalling is needed only when
# pyproject.toml changes (the console script, the package list)
stamp=$venv/.sphastro-installed
if [ ! -f "$stamp" ] || [ "$root/python/pyproject.toml" -nt "$stamp" ] \
   || ! "$venv/bin/python" -c "import sphastro" 2>/dev/null; then
  PIP_NO_INDEX=1 PIP_DISABLE_PIP_VERSION_CHECK=1 "$venv/bin/python" -m pip install -q \
    --no-build-isolation --no-deps -e "$root/python"
  touch "$stamp"
fi
"$venv/bin/python" -c "import sphastro, numpy, matplotlib" || {
  echo "install_python: the venv cannot import sphastro, numpy and matplotlib" >&2; exit 1; }
echo "install_python: sphastro installed in $venv (command: $venv/bin/sphastro)"
