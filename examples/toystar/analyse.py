#!/usr/bin/env python3
"""Compare an SPH-ASTRO toy star (examples/toystar/in.toystar) with its equilibrium profile.

Usage (python3 of build/venv, on PATH after source build/env.sh)::

    python3 examples/toystar/analyse.py dump.toystar.relaxed [dump.toystar]
        [--log log.lammps] [--png toystar.png] [--M 2 --R 0.75 --k 0.1 --npoly 1]
        [--assert 'l1=0.05,rfit=0.02,drift_l1=0.01,ekin=1e-4']

The first dump is the star at the end of the damped relaxation, the optional second one the
same star after the undamped continuation. The reference is python/sphastro/toystar.py:
rho(r) = [lambda/(2k(1+n)) (R^2 - r^2)]^n, centred at the origin (the centre
of the linear force). Printed, one figure a line, for each dump:

* ``L1(rho)`` = mean over all particles of |rho_i - rho(r_i)|, also relative to the
  central density rho_c, and over the inner particles (r < 0.8 R) only;
* the star's radius, three ways, each with its relative error against R:
  ``R_fit`` (HEADLINE, asserted as ``rfit``): rho^(1/n) = A (R^2 - r^2) is a straight line
  in r^2, fitted by least squares to the particles with r < 0.8 R (the surface layer, where
  SPH smooths the density over a kernel, is left out); the fitted A = lambda/(2k(1+n)) is
  printed as a check of the force/pressure balance; ``R_rms`` from the mass-weighted mean
  square radius (<r^2> = 3R^2/(2n+5)); ``R_max``, the outermost particle;
* the central density (mean over r < 0.2 R), the centre-of-mass offset and the rms speed.

With both dumps: the drift of L1 and R_fit during the undamped continuation. With ``--log``:
the kinetic energy at the end of the relaxation and its largest value in the continuation
(relative to the thermal energy), the relative total-energy error of the continuation
(compute ``free``: Ekin + Eth + the potential energy of the linear force), particles at the
h cap, steps and loop time.

``--assert`` fails (exit 1) unless each figure is within its bound (upper bounds on
absolute values): ``l1`` (relative L1, L1/rho_c, of the relaxed star), ``rfit`` (|R_fit
error|), ``rrms`` (|R_rms error|), ``lambda`` (|relative error of the fitted A|);
with the second dump ``l1free``, ``rfitfree`` (the same after the continuation),
``drift_l1`` (|change of L1/rho_c|), ``drift_r`` (|change of R_fit| / R); with --log
``ekin`` (largest Ekin/Eth in the continuation), ``energy`` (|relative energy error of the
continuation|), ``capped`` (particles at the h cap: the largest count over all steps that
in.toystar prints, else the thermo lines of the continuation).
"""

import argparse
import math
import sys

from sphastro import cli, toystar
from sphastro.dump import read_last_frame
from sphastro.toystar import parse_log


def report(label, frame, args):
    err = toystar.toystar_errors(frame, args.M, args.R, args.k, args.npoly,
                                 fit_fraction=args.fit_fraction)
    t = frame.time
    print(f"[{label}] t = {t:g}, {err['n']} particles ({err['n_inner']} with r < "
          f"{args.fit_fraction:g} R)")
    print(f"[{label}] L1(rho) = {err['l1']:.4e} = {err['l1_rel']:.4e} rho_c; inner: "
          f"{err['l1_inner']:.4e}")
    print(f"[{label}] R_fit (headline) = {err['r_fit']:.5f}: {100 * err['err_r_fit']:+.2f} %; "
          f"fitted lambda/(2k(1+n)) {100 * err['err_lambda']:+.2f} %")
    print(f"[{label}] R_rms = {err['r_rms']:.5f}: {100 * err['err_r_rms']:+.2f} %; "
          f"R_max (outermost particle) = {err['r_max']:.5f}: {100 * err['err_r_max']:+.2f} %")
    print(f"[{label}] rho_c SPH (r < 0.2 R) = {err['rho_c_sph']:.5f}, exact {err['rho_c']:.5f}: "
          f"{100 * (err['rho_c_sph'] / err['rho_c'] - 1):+.2f} %; centre of mass at "
          f"{err['com']:.2e}; v_rms = {err.get('vrms', math.nan):.3e}")
    return err


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("relaxed", help="dump at the end of the damped relaxation")
    parser.add_argument("free", nargs="?", default=None,
                        help="dump at the end of the undamped continuation")
    parser.add_argument("--log", default=None, help="LAMMPS log of the run")
    parser.add_argument("--png", default=None, help="write rho(r) of the dumps to this PNG")
    parser.add_argument("--M", type=float, default=2.0)
    parser.add_argument("--R", type=float, default=0.75)
    parser.add_argument("--k", type=float, default=0.1)
    parser.add_argument("--npoly", type=float, default=1.0, help="polytropic index n")
    parser.add_argument("--fit-fraction", type=float, default=0.8,
                        help="fit R over the particles with r < this fraction of R (0.8)")
    cli.add_assert_argument(parser)
    args = parser.parse_args(argv)

    lam = toystar.toystar_lambda(args.M, args.R, args.k, args.npoly)
    print(f"toy star M = {args.M:g}, R = {args.R:g}, k = {args.k:g}, n = {args.npoly:g}: "
          f"lambda = {lam:.8g}, rho_c = {toystar.central_density(args.M, args.R, args.k, args.npoly):.6g}")
    relaxed = read_last_frame(args.relaxed)
    e1 = report("relaxed", relaxed, args)
    values = {"l1": e1["l1_rel"], "rfit": abs(e1["err_r_fit"]), "rrms": abs(e1["err_r_rms"]),
              "lambda": abs(e1["err_lambda"])}
    frames = [(f"relaxed, t = {relaxed.time:g}", relaxed)]
    if args.free:
        free = read_last_frame(args.free)
        e2 = report("free", free, args)
        d_l1 = e2["l1_rel"] - e1["l1_rel"]
        d_r = (e2["r_fit"] - e1["r_fit"]) / args.R
        print(f"drift over the undamped continuation (t = {relaxed.time:g} -> {free.time:g}): "
              f"L1/rho_c {d_l1:+.3e}, R_fit {100 * d_r:+.3f} % of R, R_rms "
              f"{100 * (e2['r_rms'] - e1['r_rms']) / args.R:+.3f} % of R")
        values.update(l1free=e2["l1_rel"], rfitfree=abs(e2["err_r_fit"]), drift_l1=abs(d_l1),
                      drift_r=abs(d_r))
        frames.append((f"free, t = {free.time:g}", free))
    if args.log:
        log = parse_log(args.log)
        ratio = log["ekin_free_max"] / log["eth_relaxed"]
        print(f"kinetic energy: {log['ekin_relaxed']:.3e} at the end of the relaxation, largest "
              f"in the continuation {log['ekin_free_max']:.3e} (final {log['ekin_free_end']:.3e})"
              f" = {ratio:.3e} of the thermal energy {log['eth_relaxed']:.5g}")
        print(f"relative energy error of the continuation (final) = {log['energy']:+.3e}, largest "
              f"|error| = {log['energy_max']:.3e}")
        print(f"particles at the h cap (most at any step, else at a thermo line) = "
              f"{log['capped']:g}")
        print(f"run: {log['natoms']} particles, {log['steps']} steps, loop time "
              f"{log['loop_s']:.2f} s on {log['procs']} procs")
        values.update(ekin=ratio, energy=abs(log["energy"]), capped=log["capped"])
    if args.png:
        toystar.plot_profile(frames, args.png, args.M, args.R, args.k, args.npoly,
                             title=f"toy star, {e1['n']} particles, n = {args.npoly:g}: "
                                   f"L1/rho_c {e1['l1_rel']:.3g}, R_fit {100 * e1['err_r_fit']:+.2f} %")
        print(f"plot: {args.png}")

    if args.bounds:
        return cli.assert_bounds(args.bounds, values, error=parser.error)
    return 0


if __name__ == "__main__":
    sys.exit(main())
