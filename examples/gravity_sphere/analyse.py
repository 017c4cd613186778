#!/usr/bin/env python3
"""Uniform-density sphere: softened self-gravity against the analytic solution.

Reads the dump of in.gravity_sphere (id x y z mass fx fy fz c_pe [c_ref[1..4]]) and compares
the acceleration a_i = f_i / m_i and the potential phi_i = 2 pe_i / m_i with those of a uniform
sphere of mass M and radius R (G = 1):
    phi = -G M (3 R^2 - r^2) / (2 R^3),  a = -G M r / R^3     (r < R)
    phi = -G M / r,                      a = -G M r / r^3     (r >= R)
R is the radius of the volume the particles fill, (3 N v / 4 pi)^(1/3) with v the volume per
particle (fcc: a^3/4, taken from the mean spacing), M the total mass.
Prints L1 and RMS errors (relative to the mean |a| or |phi| of the exact solution) over all
particles and over the interior r < 0.8 R (away from the lattice-cut surface), and, if the dump
has the reference compute, the relative RMS difference from the direct sum.
Usage: analyse.py DUMP [--n N] [--png FILE] [--assert key=bound,...]
"""
import argparse
import sys

import numpy as np

from sphastro import cli
from sphastro.dump import read_last_frame


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("dump")
    p.add_argument("--n", type=int, default=16, help="fcc cells across the diameter (as -var n)")
    p.add_argument("--png")
    cli.add_assert_argument(p, "e.g. l1a=0.02,rmsa=0.03,l1phi=0.01,ref=1e-4 (interior L1/RMS, "
                               "reference)")
    args = p.parse_args()

    c = read_last_frame(args.dump).columns
    x = np.column_stack([c["x"], c["y"], c["z"]])
    m = np.asarray(c["mass"])
    acc = np.column_stack([c["fx"], c["fy"], c["fz"]]) / m[:, None]
    phi = 2.0 * np.asarray(c["c_pe"]) / m
    N, M = len(m), m.sum()
    lattice = 2.0 / args.n
    R = (3.0 * N * lattice**3 / 4.0 / (4.0 * np.pi)) ** (1.0 / 3.0)
    r = np.linalg.norm(x, axis=1)
    inside = r < R
    phi_ex = np.where(inside, -M * (3 * R**2 - r**2) / (2 * R**3), -M / np.maximum(r, 1e-12))
    a_ex = -x * np.where(inside, M / R**3, M / np.maximum(r, 1e-12) ** 3)[:, None]

    results = {}
    print(f"uniform sphere: N = {N}, M = {M:.6g}, R = {R:.6f} (lattice {lattice:.5f})")
    for name, sel in (("all", np.ones(N, bool)), ("r<0.8R", r < 0.8 * R)):
        da = np.linalg.norm(acc[sel] - a_ex[sel], axis=1)
        amean = np.mean(np.linalg.norm(a_ex[sel], axis=1))
        dphi = np.abs(phi[sel] - phi_ex[sel])
        pmean = np.mean(np.abs(phi_ex[sel]))
        l1a, rmsa = np.mean(da) / amean, np.sqrt(np.mean(da**2)) / amean
        l1p, rmsp = np.mean(dphi) / pmean, np.sqrt(np.mean(dphi**2)) / pmean
        print(f"  {name:7s} ({sel.sum():6d} particles): acceleration L1 {l1a:.3e} RMS {rmsa:.3e}; "
              f"potential L1 {l1p:.3e} RMS {rmsp:.3e}")
        if name != "all":
            results.update(l1a=l1a, rmsa=rmsa, l1phi=l1p, rmsphi=rmsp)
    if "c_ref[1]" in c:
        fref = np.column_stack([c["c_ref[1]"], c["c_ref[2]"], c["c_ref[3]"]])
        f = acc * m[:, None]
        ref = np.sqrt(np.sum((f - fref) ** 2) / np.sum(fref**2))
        phiref = np.asarray(c["c_ref[4]"])
        refphi = np.sqrt(np.mean((phi - phiref) ** 2) / np.mean(phiref**2))
        print(f"  against the direct sum: relative RMS force {ref:.3e}, potential {refphi:.3e}")
        results.update(ref=ref, refphi=refphi)

    if args.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        rr = np.linspace(0, 1.2 * R, 300)
        fig, ax = plt.subplots(1, 2, figsize=(10, 4))
        ar = -np.sum(acc * x, axis=1) / np.maximum(r, 1e-12)
        ax[0].plot(r, ar, ",", alpha=0.5, label="particles")
        ax[0].plot(rr, np.where(rr < R, M * rr / R**3, M / np.maximum(rr, 1e-12)**2), "k-", label="exact")
        ax[0].set_xlabel("r"); ax[0].set_ylabel("-a_r"); ax[0].legend()
        ax[1].plot(r, phi, ",", alpha=0.5, label="particles")
        ax[1].plot(rr, np.where(rr < R, -M * (3 * R**2 - rr**2) / (2 * R**3), -M / np.maximum(rr, 1e-12)),
                   "k-", label="exact")
        ax[1].set_xlabel("r"); ax[1].set_ylabel("phi"); ax[1].legend()
        fig.tight_layout()
        fig.savefig(args.png, dpi=120)
        print(f"wrote {args.png}")

    if args.bounds:
        missing = {} if "ref" in results else {
            "ref": "needs the c_ref columns in the dump", "refphi": "needs the c_ref columns"}
        return cli.assert_bounds(args.bounds, results, unavailable=missing, error=p.error)
    return 0


if __name__ == "__main__":
    sys.exit(main())
