#!/usr/bin/env python3
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
"""Equal-mass particle positions for the Kelvin-Helmholtz scene (McNally, Lyra & Passy 2012,
ApJS 201, 18): a LAMMPS data file (atom_style atomic, 2D, box [0, 1]^2) whose particles
follow rho(y) of their eqs. 1-4.

Two hexagonal row lattices: n particles a row in the light gas (rho ~ 1, |y - 1/2| > 1/4)
and n2 = round(sqrt(2) n) a row in the dense band (rho ~ 2), so that equal masses give
nearly regular hexagons in both (spacing ratio 1/sqrt(2)). Inside each region the rows are
placed in the mass coordinate m(y) = integral rho dy (the stretch mapping of Herant 1994,
Mem. Soc. Astron. Ital. 65, 1013, along y): row j of a region sits where the mass from
the region's edge is (j + 1/2) times the row mass, so the mean density follows rho(y),
including the smooth ramps of width L = 0.025. The boundary between the lattices is put
at y_b ~ 1/4 (and 1 - y_b) where the dense band holds exactly its rows' mass. Alternate rows
are shifted by half a spacing in x. Atom IDs are sorted by (y, x), so they do not depend on
the number of MPI ranks.

Usage::

    python3 kh_setup.py --n 64 --out kh.data

prints N, the particle mass and the largest relative deviation of the rows' mean density
from rho(y) (the set-up error).
"""

import argparse
import math
import sys

import numpy as np

RHO1, RHO2, L = 1.0, 2.0, 0.025


def rho_profile(y):
    """rho(y) of McNally et al. (2012), eqs. 1-4, rho_m = (rho1 - rho2)/2."""
    y = np.mod(np.asarray(y, dtype=float), 1.0)
    rhom = 0.5 * (RHO1 - RHO2)
    return np.select([y < 0.25, y < 0.5, y < 0.75],
                     [RHO1 - rhom * np.exp((y - 0.25) / L),
                      RHO2 + rhom * np.exp((0.25 - y) / L),
                      RHO2 + rhom * np.exp((y - 0.75) / L)],
                     RHO1 - rhom * np.exp((0.75 - y) / L))


def mass_coordinate(nfine=400000):
    """(y, m(y)) on a fine grid over [0, 1.25]: m(y) = integral_0^y rho dy (trapezoid)."""
    y = np.linspace(0.0, 1.25, nfine + 1)
    r = rho_profile(y)
    m = np.concatenate([[0.0], np.cumsum(0.5 * (r[1:] + r[:-1]) * np.diff(y))])
    return y, m


def build(n):
    """Positions (x, y) of all particles, the particle mass and the lattice boundary y_b."""
    n1 = int(n)
    n2 = int(round(math.sqrt(2.0) * n1))
    yg, mg = mass_coordinate()
    total = np.interp(1.0, yg, mg)
    m_dense = np.interp(0.75, yg, mg) - np.interp(0.25, yg, mg)
    m_light = total - m_dense
    # hexagonal lattice of spacing a at density rho: particle mass rho sqrt(3)/2 a^2
    m_target = 0.5 * (RHO1 * math.sqrt(3.0) / 2.0 / n1 ** 2 + RHO2 * math.sqrt(3.0) / 2.0 / n2 ** 2)
    rows2 = max(2, int(round(m_dense / (n2 * m_target))))
    rows1 = max(2, int(round(m_light / (n1 * m_target))))
    mass = total / (rows1 * n1 + rows2 * n2)
    # the dense band [y_b, 1 - y_b] holds rows2 n2 mass; by symmetry each half holds half
    half = 0.5 * rows2 * n2 * mass
    m_half = np.interp(0.5, yg, mg)
    y_b = float(np.interp(m_half - half, mg, yg))
    xs, ys = [], []
    # dense band: rows from y_b upwards
    m0 = np.interp(y_b, yg, mg)
    for j in range(rows2):
        y = float(np.interp(m0 + (j + 0.5) * n2 * mass, mg, yg))
        xs.append((np.arange(n2) + 0.25 + 0.5 * (j % 2)) / n2)
        ys.append(np.full(n2, y))
    # light gas: rows from 1 - y_b upwards, through y = 1 (periodic), to 1 + y_b
    m0 = np.interp(1.0 - y_b, yg, mg)
    for j in range(rows1):
        y = float(np.interp(m0 + (j + 0.5) * n1 * mass, mg, yg))
        xs.append((np.arange(n1) + 0.25 + 0.5 * (j % 2)) / n1)
        ys.append(np.full(n1, math.fmod(y, 1.0)))
    x = np.concatenate(xs)
    y = np.concatenate(ys)
    order = np.lexsort((x, y))
    return x[order], y[order], mass, y_b, (n1, rows1, n2, rows2)


def row_density_error(y, n1, n2, mass):
    """Largest |rho_rows / rho(y) - 1| of the rows' mean density (row mass over the mean
    distance to the neighbouring rows), over rows whose neighbours are of the same lattice."""
    rows = np.unique(np.round(y, 12))
    counts = [np.count_nonzero(np.abs(y - yr) < 1e-11) for yr in rows]
    worst = 0.0
    for k, yr in enumerate(rows):
        kn = (k + 1) % len(rows)
        if not counts[k - 1] == counts[k] == counts[kn]:
            continue
        yn = rows[kn] + (1.0 if kn == 0 else 0.0)
        yp = rows[k - 1] - (1.0 if k == 0 else 0.0)
        count = counts[k]
        dens = count * mass / (0.5 * (yn - yp))
        worst = max(worst, abs(dens / float(rho_profile(yr)) - 1.0))
    return worst


def write_data(path, x, y, mass):
    with open(path, "w", encoding="utf-8") as f:
        f.write("Kelvin-Helmholtz (McNally, Lyra & Passy 2012) particles: "
                "examples/kelvin_helmholtz/kh_setup.py\n\n")
        f.write(f"{len(x)} atoms\n1 atom types\n\n")
        f.write("0.0 1.0 xlo xhi\n0.0 1.0 ylo yhi\n-0.5 0.5 zlo zhi\n\n")
        f.write(f"Masses\n\n1 {mass:.17g}\n\nAtoms # atomic\n\n")
        for i, (xi, yi) in enumerate(zip(x, y)):
            f.write(f"{i + 1} 1 {xi:.17g} {yi:.17g} 0.0\n")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--n", type=int, default=64,
                        help="particles a row in the light gas (rho ~ 1); default 64")
    parser.add_argument("--out", default="kh.data", help="LAMMPS data file to write")
    args = parser.parse_args(argv)
    if args.n < 4:
        parser.error(f"--n must be at least 4 (got {args.n})")
    x, y, mass, y_b, (n1, rows1, n2, rows2) = build(args.n)
    write_data(args.out, x, y, mass)
    err = row_density_error(y, n1, n2, mass)
    print(f"kh_setup: N = {len(x)} ({rows1} rows of {n1} light, {rows2} rows of {n2} dense), "
          f"mass = {mass:.6e}, lattice boundary y_b = {y_b:.5f}, "
          f"largest row-density error (away from the lattice boundary) = {err:.2e} -> {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
