#!/usr/bin/env bash
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
# Obtain the LAMMPS 4 Feb 2025 source from Debian's source package.
# Usage: tools/fetch_lammps.sh DESTDIR   -> prints the path of the unpacked source tree
# Only the upstream tarball is used; its sha256 is checked, apt's exit code is not trusted
# (the registry may answer 404 for the .dsc while the tarball arrives).
set -euo pipefail
dest=${1:?usage: fetch_lammps.sh DESTDIR}
tarball=lammps_20250204+dfsg.1.orig.tar.xz
sha=3671165bd52fad36734e0a9136c5bc5ecb225e03988f8c89aa13366a8b53b1c7
mkdir -p "$dest"
cd "$dest"
have_ok() { [ -f "$tarball" ] && echo "$sha  $tarball" | sha256sum -c --status; }
if ! have_ok; then
  sudo=""; [ "$(id -u)" = 0 ] || sudo=sudo
  # derive a deb-src entry for trixie from the machine's own deb822 sources (no host written here)
  srcfile=/etc/apt/sources.list.d/sph-astro-trixie-src.sources
  if [ ! -f "$srcfile" ]; then
    first=$(ls /etc/apt/sources.list.d/*.sources 2>/dev/null | grep -v sph-astro | head -1 || true)
    if [ -n "$first" ]; then
      awk 'BEGIN{RS="";ORS="\n\n"} NR==1' "$first" |
        sed -e 's/^Types:.*/Types: deb-src/' -e 's/^Suites:.*/Suites: trixie/' |
        $sudo tee "$srcfile" >/dev/null
    else
      uri=$(awk '$1=="deb"{print $2; exit}' /etc/apt/sources.list)
      printf 'Types: deb-src\nURIs: %s\nSuites: trixie\nComponents: main\nSigned-By: /usr/share/keyrings/debian-archive-keyring.gpg\n' "$uri" |
        $sudo tee "$srcfile" >/dev/null
    fi
    $sudo apt-get update -qq || true
  fi
  version=$(apt-cache showsrc lammps 2>/dev/null | awk '/^Version: 20250204/{print $2; exit}')
  [ -n "$version" ] || { echo "fetch_lammps: no lammps source version 20250204* in the apt source lists" >&2; exit 1; }
  apt-get source --download-only "lammps=$version" >/dev/null 2>&1 || true
  have_ok || { echo "fetch_lammps: $tarball missing or its sha256 differs from $sha" >&2; exit 1; }
fi
srcdir=$({ tar -tJf "$tarball" 2>/dev/null || true; } | head -1 | cut -d/ -f1)
[ -d "$srcdir/cmake" ] || tar -xJf "$tarball"
echo "$dest/$srcdir"
