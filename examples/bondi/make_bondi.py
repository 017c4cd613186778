#!/usr/bin/env python3
"""Initial state of the Bondi scene (in.bondi): Bondi's (1952) isothermal transonic flow.

Usage::

    python3 make_bondi.py [--n 200] [--R 3.0] [--rho 1e-3] [--hfact 1.2] [--seed 4711]
        [--data bondi.data] [--hfile bondi.h]

Units G = M = c_s = 1 (r_B = G M / c_s^2 = 1). The steady isothermal flow onto a point mass,
with the accretion rate dM/dt = 4 pi lambda rho_inf (lambda = e^(3/2)/4), obeys

    4 pi r^2 rho v = dM/dt,   v^2/2 + ln(rho/rho_inf) - 1/r = 0,

i.e. g(v) = v^2/2 - ln v = 2 ln r + 1/r - ln lambda, whose transonic root is subsonic
(v < 1) outside the sonic point r_s = 1/2 and supersonic inside. The particles of an fcc
lattice of number density n (mass rho_inf / n each: the density rho_inf) filling a sphere of
radius R are moved radially, r -> r', so that the mass inside r' of the Bondi density equals
the lattice's inside r, and given the inflow speed v(r'). Written: a LAMMPS data file (type 1
gas, type 2 the sink of mass 1 at the origin, last ID) and an atomfile of the smoothing length
guesses h = hfact (m / rho(r'))^(1/3).
"""

import argparse
import math

import numpy as np

LAMBDA = math.exp(1.5) / 4.0


def bondi_speed(r):
    """The transonic root v(r) of v^2/2 - ln v = 2 ln r + 1/r - ln lambda (bisection)."""
    r = np.asarray(r, dtype=float)
    rhs = 2.0 * np.log(r) + 1.0 / r - math.log(LAMBDA)
    rhs = np.maximum(rhs, 0.5)    # (round-off at the sonic point, where the minimum g(1) = 1/2)
    supersonic = r < 0.5
    lo = np.where(supersonic, 1.0, 1e-12)
    hi = np.where(supersonic, 1e6, 1.0)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        g = 0.5 * mid * mid - np.log(mid)
        # g falls below v = 1 and rises above: keep the root of the branch inside [lo, hi]
        above = g > rhs
        lo = np.where(supersonic, np.where(above, lo, mid), np.where(above, mid, lo))
        hi = np.where(supersonic, np.where(above, mid, hi), np.where(above, hi, mid))
    return 0.5 * (lo + hi)


def bondi_density(r, rho_inf):
    return rho_inf * LAMBDA / (r * r * bondi_speed(r))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--n", type=float, default=200.0, help="lattice number density")
    parser.add_argument("--R", type=float, default=3.0, help="radius of the lattice sphere")
    parser.add_argument("--rho", type=float, default=1e-3, help="rho_inf")
    parser.add_argument("--hfact", type=float, default=1.2)
    parser.add_argument("--seed", type=int, default=4711)
    parser.add_argument("--data", default="bondi.data")
    parser.add_argument("--hfile", default="bondi.h")
    args = parser.parse_args()

    a = (4.0 / args.n) ** (1.0 / 3.0)    # fcc cell
    k = int(math.ceil(args.R / a)) + 1
    basis = np.array([[0, 0, 0], [0.5, 0.5, 0], [0.5, 0, 0.5], [0, 0.5, 0.5]])
    g = np.arange(-k, k + 1)
    cells = np.stack(np.meshgrid(g, g, g, indexing="ij"), axis=-1).reshape(-1, 3)
    pts = ((cells[:, None, :] + basis[None, :, :]).reshape(-1, 3) + 0.25) * a
    rng = np.random.default_rng(args.seed)
    pts += rng.uniform(-0.02 * a, 0.02 * a, pts.shape)
    r = np.linalg.norm(pts, axis=1)
    keep = (r < args.R) & (r > 0.0)
    pts, r = pts[keep], r[keep]
    mass = args.rho / args.n

    # mass of the Bondi density inside r' on a fine grid, inverted at the lattice's masses
    grid = np.concatenate([[0.0], np.geomspace(1e-6, 2.0 * args.R, 200000)])
    rho_grid = np.empty_like(grid)
    rho_grid[1:] = bondi_density(grid[1:], args.rho)
    rho_grid[0] = 0.0
    shell = 4.0 * math.pi * grid * grid * rho_grid
    m_grid = np.concatenate([[0.0], np.cumsum(0.5 * (shell[1:] + shell[:-1]) * np.diff(grid))])
    order = np.argsort(r)
    m_lattice = np.empty_like(r)
    m_lattice[order] = (np.arange(len(r)) + 0.5) * mass    # the mass inside each particle
    r_new = np.interp(m_lattice, m_grid, grid)
    x = pts * (r_new / r)[:, None]
    v = -(bondi_speed(r_new) / r_new)[:, None] * x
    h = args.hfact * (mass / bondi_density(r_new, args.rho)) ** (1.0 / 3.0)

    n = len(r_new)
    box = args.R + 0.5
    with open(args.data, "w") as f:
        f.write(f"Bondi flow: {n} gas particles and the sink (make_bondi.py --n {args.n:g} "
                f"--R {args.R:g} --rho {args.rho:g})\n\n{n + 1} atoms\n2 atom types\n\n")
        for d in "xyz":
            f.write(f"{-box:.6f} {box:.6f} {d}lo {d}hi\n")
        f.write("\nAtoms # atomic\n\n")
        for i in range(n):
            f.write(f"{i + 1} 1 {x[i, 0]:.17g} {x[i, 1]:.17g} {x[i, 2]:.17g}\n")
        f.write(f"{n + 1} 2 0 0 0\n\nVelocities\n\n")
        for i in range(n):
            f.write(f"{i + 1} {v[i, 0]:.17g} {v[i, 1]:.17g} {v[i, 2]:.17g}\n")
        f.write(f"{n + 1} 0 0 0\n")
    with open(args.hfile, "w") as f:
        f.write(f"# smoothing lengths of the Bondi particles\n{n + 1}\n")
        for i in range(n):
            f.write(f"{i + 1} {h[i]:.17g}\n")
        f.write(f"{n + 1} 0\n")
    print(f"make_bondi: {n} particles of mass {mass:.6g} inside r = {r_new.max():.4f} "
          f"(lattice {args.R:g}); {args.data}, {args.hfile}")


if __name__ == "__main__":
    main()
