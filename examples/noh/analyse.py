#!/usr/bin/env python3
"""Compare the last frame of an SPH-ASTRO Noh implosion dump with the exact solution.

Usage (from anywhere; python3 of build/venv, on PATH after source build/env.sh)::

    python3 examples/noh/analyse.py DUMPFILE [--log log.lammps] [--png out.png]
        [--time T] [--gamma 1.6666667] [--u0 1e-6] [--radius 1] [--nbins 40]
        [--window 0.25,0.75]
        [--assert 'rhopost=0.1,rshock=0.05,umin=0,wallheat=3,energy=1e-3']

The dump must be a LAMMPS text ``dump custom`` with the columns x, y, z, vx, vy, vz, rho,
pressure and u (examples/noh/in.noh writes them); the implosion is centred at the origin,
the gas initially had rho = 1, v = -r_hat and fills a sphere of radius ``--radius``.
The time defaults to the dump's ``ITEM: TIME``, else 0.6.

Exact solution (3D, gamma = 5/3): the shock is at R_s = t/3 (in general
R_s = (gamma - 1) t / 2); behind it rho = ((gamma + 1)/(gamma - 1))^3 = 64, v = 0,
u = 1/2 (all the kinetic energy per unit mass v^2/2 turned into heat); in front of it
rho = (1 + t/r)^2, v_r = -1 and u = u0 rho^(gamma - 1) (adiabatic compression of the cold
gas).  Printed, one figure a line:

* the post-shock density: the mean particle density over the WINDOW of radii
  (default 0.25 R_s < r < 0.75 R_s, i.e. 0.05 < r < 0.15 at t = 0.6: away from the centre,
  where the wall heating sits, and from the smoothed shock), against 64, in %;
* the shock radius: where the density averaged in ``nbins`` radial bins over
  r < radius - t (the gas still present) falls through half the measured post-shock density,
  outside the densest bin beyond the window's inner edge (linear interpolation between bin
  centres), against R_s, in % (the HEADLINE figure, asserted as ``rshock``); and the same
  for half the exact post-shock density, 32 (nan if the binned density never reaches it);
  and, for information (not the headline), where it falls through the midpoint of the jump,
  (measured post-shock density + exact pre-shock density (1 + t/r)^2) / 2: the centre of a
  symmetrically smeared step, which half the post-shock density (ignoring the pre-shock 16)
  places outside it by a fraction of the smearing width;
* the smallest u of all particles (must stay >= 0);
* the wall heating: the mean u (and entropy function A = P / rho^gamma) of the particles
  at r < window inner edge (0.05 at t = 0.6), and of the innermost particle, against the
  post-shock u = 1/2 (and A = (gamma - 1) u / rho^(gamma - 1)); and the mean u in the window;
* the pre-shock state between 1.5 R_s and 2 h inside the free surface (at radius - t; h
  the median of the outermost particles): the mean u, v_r and rho / rho_exact, which show
  the viscous pre-heating of the converging cold flow (nan if the range is empty);
* the per-particle L1 error of rho, divided by 64, over r < 1.5 R_s;
* with ``--log``: the relative total-energy error of the run (compute sph/astro/global,
  final and largest over the thermo lines), the particles held at the h cap, steps, loop time.

``--assert`` fails (exit 1) unless every listed figure is within its bound: ``rhopost``
(|relative error| of the post-shock density), ``rshock`` (|relative error| of the shock
radius), ``wallheat`` (central u / 0.5), ``preheat`` (mean pre-shock u), ``l1rho``,
``energy`` (|final relative energy error|, needs --log), ``capped`` (largest number of
particles at the h cap over all steps, else over the thermo lines; needs --log): upper
bounds; ``umin`` (smallest u): a LOWER bound.
"""

import argparse
import math
import os
import sys

import numpy as np

from sphastro import cli
from sphastro.dump import read_last_frame
from sphastro.noh import binned, exact, noh_measures, parse_log


def plot(d, t, png, gamma, u0, radius, nbins, title):
    from matplotlib.figure import Figure     # no pyplot: no GUI backend, no global state

    rs = 0.5 * (gamma - 1.0) * t
    rmax = radius - t
    rr = np.linspace(1e-4, rmax, 2001)
    ex = exact(rr, t, gamma, u0)
    ex["A"] = ex["p"] / ex["rho"] ** gamma
    edges = np.linspace(0.0, rmax, nbins + 1)
    fig = Figure(figsize=(13, 8))
    axes = fig.subplots(2, 2).ravel()
    labels = {"rho": r"$\rho$", "v": r"$v_r$", "u": r"$u$", "A": r"$A = P/\rho^\gamma$"}
    sel = d["r"] < rmax * 1.1
    for ax, key in zip(axes, ("rho", "v", "u", "A")):
        ax.plot(d["r"][sel], d[key][sel], ".", ms=1.0, alpha=0.4, color="tab:blue",
                label="SPH particles", rasterized=True)
        centres, means, _ = binned(d["r"], d[key], edges)
        ax.plot(centres, means, "o", ms=3, color="tab:red", label="SPH, binned")
        ax.plot(rr, ex[key], "-", lw=1.2, color="black", label="exact")
        ax.axvline(rs, color="grey", lw=0.8, ls=":")
        ax.set_xlabel("r")
        ax.set_ylabel(labels[key])
        ax.set_xlim(0.0, rmax * 1.1)
        ax.grid(alpha=0.3)
    axes[2].set_yscale("log")
    axes[2].set_ylim(max(1e-7, u0 / 3), None)
    axes[3].set_yscale("log")
    axes[0].legend(loc="upper right", markerscale=3, fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(png, dpi=120)
    return png


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("dump", help="LAMMPS text dump custom file (the last frame is used)")
    parser.add_argument("--log", default=None, help="LAMMPS log of the run (energy error, "
                        "capped particles, steps)")
    parser.add_argument("--time", type=float, default=None,
                        help="time of the frame (default: the dump's TIME item, else 0.6)")
    parser.add_argument("--gamma", type=float, default=5.0 / 3.0,
                        help="ratio of specific heats (default 5/3; the exact solution "
                             "here is written for 3D)")
    parser.add_argument("--u0", type=float, default=1e-6,
                        help="initial specific internal energy (default 1e-6)")
    parser.add_argument("--radius", type=float, default=1.0,
                        help="initial radius of the gas sphere (default 1)")
    parser.add_argument("--nbins", type=int, default=40,
                        help="radial bins over r < radius - t (default 40)")
    parser.add_argument("--window", default="0.25,0.75",
                        help="post-shock window in units of R_s (default 0.25,0.75: "
                             "0.05 < r < 0.15 at t = 0.6)")
    parser.add_argument("--png", default=None, help="write rho, v_r, u, A profiles to this PNG")
    cli.add_assert_argument(parser, "fail (exit 1) unless every figure is within its bound, "
                            "e.g. rhopost=0.1,rshock=0.05,umin=0 (see the docstring)")
    args = parser.parse_args(argv)

    frame = read_last_frame(args.dump)
    t = args.time if args.time is not None else (frame.time if frame.time is not None else 0.6)
    window = tuple(float(w) for w in args.window.split(","))
    res, d = noh_measures(frame, t, args.gamma, args.u0, args.radius, args.nbins, window)

    print(f"particles = {res['n']}, t = {t:g}, all values finite: {res['finite']}")
    print(f"R_s exact = {res['rs']:.5f}; post-shock window {res['wlo']:.4f} < r < "
          f"{res['whi']:.4f} ({res['n_window']} particles); bin width {res['bin_width']:.4g}")
    print(f"post-shock density (window mean) = {res['rho_post']:.3f} (exact "
          f"{res['rho_post_exact']:g}): {100 * res['err_rho_post']:+.1f} %")
    print(f"shock radius (binned rho through half the post-shock value) = "
          f"{res['r_shock']:.5f}: {100 * res['err_r_shock']:+.1f} %")
    print(f"shock radius (binned rho through half the exact post-shock value, "
          f"{0.5 * res['rho_post_exact']:g}) = {res['r_shock32']:.5f}: "
          f"{100 * res['err_r_shock32']:+.1f} %")
    print(f"shock radius (for information: binned rho through the midpoint of the jump, "
          f"(post-shock + exact pre-shock (1+t/r)^2)/2) = {res['r_shock_mid']:.5f}: "
          f"{100 * res['err_r_shock_mid']:+.1f} %")
    print(f"smallest u = {res['umin']:.4e} ({res['n_negative_u']} particles with u < 0)")
    print(f"post-shock u (window mean) = {res['u_window']:.4f} (exact 0.5)")
    print(f"wall heating: mean u over r < {res['wlo']:.4f} ({res['n_centre']} particles) = "
          f"{res['u_centre']:.4f} = {res['wallheat']:.2f} x 0.5; rho there "
          f"{res['rho_centre']:.2f}; A there {res['A_centre']:.4g} = "
          f"{res['A_centre'] / res['A_post']:.2f} x the post-shock {res['A_post']:.4g}")
    print(f"innermost particle (r = {res['r_innermost']:.3g}): u = {res['u_innermost']:.4f}, "
          f"rho = {res['rho_innermost']:.2f}")
    lo, hi = res["pre_range"]
    print(f"pre-shock gas {lo:.3f} < r < {hi:.3f} ({res['n_pre']} particles): mean u = "
          f"{res['u_pre']:.4g} (exact ~{args.u0 * 16 ** (args.gamma - 1):.2g} or less), "
          f"mean v_r = {res['v_pre']:+.4f} (exact -1), rho/rho_exact = "
          f"{res['rho_pre_ratio']:.3f}")
    print(f"L1(rho)/64 over r < 1.5 R_s = {res['l1rho']:.4f}")
    log = None
    if args.log:
        log = parse_log(args.log)
        print(f"relative energy error (log, final) = {log['energy']:+.3e}, largest |error| "
              f"over the thermo lines = {log['energy_max']:.3e}")
        print(f"particles at the h cap (final) = {log['capped']:g}, most at a thermo line = "
              f"{log['capped_max']:g}, most at any step = {log['capped_steps']:g}")
        print(f"run: {log['natoms']} particles, {log['steps']} steps in {log['runs']} "
              f"run(s) ({log['widenings']} ghost-cutoff widenings), loop time "
              f"{log['loop_s']:.2f} s on {log['procs']} procs")

    if args.png:
        plot(d, t, args.png, args.gamma, args.u0, args.radius, args.nbins,
             f"Noh implosion, {os.path.basename(args.dump)}: {res['n']} particles, "
             f"t = {t:g}, step {frame.timestep}")
        print(f"plot: {args.png}")

    if args.bounds:
        values = {"rhopost": abs(res["err_rho_post"]), "rshock": abs(res["err_r_shock"]),
                  "umin": res["umin"], "wallheat": res["wallheat"], "preheat": res["u_pre"],
                  "l1rho": res["l1rho"]}
        if log is not None:
            values["energy"] = abs(log["energy"])
            values["capped"] = max(log["capped_max"], log["capped_steps"]) \
                if math.isfinite(log["capped_steps"]) else log["capped_max"]
        return cli.assert_bounds(
            args.bounds, values, lower=("umin",), error=parser.error,
            unavailable={} if log is not None else {"energy": "needs --log",
                                                    "capped": "needs --log"},
            conditions={"all values finite": res["finite"]})
    return 0


if __name__ == "__main__":
    sys.exit(main())
