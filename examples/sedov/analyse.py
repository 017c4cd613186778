#!/usr/bin/env python3
"""Compare the last frame of an SPH-ASTRO Sedov-Taylor dump with the self-similar solution.

Usage (from anywhere; python3 of build/venv, on PATH after source build/env.sh)::

    python3 examples/sedov/analyse.py DUMPFILE [--log log.lammps] [--png out.png]
        [--time T] [--E 1] [--rho0 1] [--gamma 1.6666667] [--pbg 1e-6] [--nbins 60]
        [--assert 'rshock=0.03,l1rho=0.1,peak=2.5,energy=1e-3']

The dump must be a LAMMPS text ``dump custom`` with the columns x, y, z, vx, vy, vz, rho,
pressure and u (examples/sedov/in.sedov writes them); the blast is centred at the origin.
The time defaults to the dump's ``ITEM: TIME``, else 0.1.  Printed, one figure a line:

* the analytic shock radius R_s = xi0 (E t^2 / rho0)^(1/5) (python/sphastro/sedov.py);
* the shock radius from the SPH data, measured on the density averaged in ``nbins`` radial
  bins over r < 1.2 R_s in two ways, each with its relative error in %: ``r_peak``, the
  radius of the binned density maximum (refined by a parabola through three bins; the
  HEADLINE shock radius, asserted as ``rshock``: the measure Phantom's Sedov figure uses,
  nearly independent of the bin width, and the faster converging one, about as n^-1.3
  against n^-0.8 over n = 12-28), and ``r_half``, where the binned density falls through
  (rho0 + peak) / 2 outside the peak (the middle of the smeared jump; it lies outside R_s
  because SPH spreads the jump further ahead of the shock than behind it);
* the binned peak density against the strong-shock value (gamma + 1)/(gamma - 1) rho0 = 4;
* the per-particle L1 errors of rho, radial velocity v_r and P over r < 1.2 R_s against
  the Sedov solution at each particle's radius (as SWIFT reports L1(rho));
* the kinetic + thermal energy of the particles in the dump (equal masses rho0 V_box / N)
  against E + the background's thermal energy;
* with ``--log``: the relative total-energy error of the run (compute sph/astro/global,
  final and largest over the thermo lines), the number of particles held at the h cap
  (f_hvar[4]) and the steps, particles and loop time.

``--assert`` fails (exit 1) unless every listed figure is within its bound: ``rshock``
(|relative error| of r_peak), ``rhalf`` (|relative error| of r_half), ``l1rho``, ``l1v``,
``l1p`` (L1 errors), ``energy`` (|final relative energy error|, needs --log), ``edump``
(|relative error| of the energy in the dump), ``capped`` (particles at the cap, needs
--log; upper bounds) and ``peak`` (binned peak density: a LOWER bound).
"""

import argparse
import os
import sys

from sphastro import cli, sedov
from sphastro.dump import read_last_frame
from sphastro.runs import parse_sph_log


def parse_log(path):
    """Energy error, capped particles and run size from the scene's LAMMPS log."""
    return parse_sph_log(path, loops="sum")    # the run 0 adds no steps


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("dump", help="LAMMPS text dump custom file (the last frame is used)")
    parser.add_argument("--log", default=None, help="LAMMPS log of the run (energy error, "
                        "capped particles, steps)")
    parser.add_argument("--time", type=float, default=None,
                        help="time of the frame (default: the dump's TIME item, else 0.1)")
    parser.add_argument("--E", type=float, default=1.0, help="blast energy (default 1)")
    parser.add_argument("--rho0", type=float, default=1.0, help="ambient density (default 1)")
    parser.add_argument("--gamma", type=float, default=5.0 / 3.0,
                        help="ratio of specific heats (default 5/3)")
    parser.add_argument("--pbg", type=float, default=1e-6,
                        help="background pressure, for the energy budget (default 1e-6)")
    parser.add_argument("--nbins", type=int, default=60,
                        help="radial bins over r < 1.2 R_s for the shock measures (default 60)")
    parser.add_argument("--png", default=None, help="write rho, v_r, P profiles to this PNG")
    cli.add_assert_argument(parser, "fail (exit 1) unless every figure is within its bound, "
                            "e.g. rshock=0.03,l1rho=0.1,peak=2.5,energy=1e-3 (see the docstring)")
    args = parser.parse_args(argv)

    frame = read_last_frame(args.dump)
    t = args.time if args.time is not None else (frame.time if frame.time is not None else 0.1)
    res = sedov.sedov_errors(frame, t, args.E, args.rho0, args.gamma, nbins=args.nbins)
    box_volume = float((frame.box[:, 1] - frame.box[:, 0]).prod())
    e_expected = args.E + args.pbg / (args.gamma - 1.0) * box_volume
    e_dump_err = (res["e_particles"] - e_expected) / e_expected
    rho_jump = (args.gamma + 1.0) / (args.gamma - 1.0) * args.rho0
    nparticles = len(frame.columns["x"])

    print(f"particles = {nparticles}, t = {t:g}, measured over r < 1.2 R_s: {res['n']} "
          f"particles, bin width {res['bin_width']:.4g}")
    print(f"R_s analytic = {res['rs']:.5f} (xi0 = {sedov.xi0(args.gamma):.5f})")
    print(f"R_s SPH, binned density peak (headline) = {res['r_peak']:.5f}: "
          f"{100 * res['err_r_peak']:+.2f} %")
    print(f"R_s SPH, half height of the jump = {res['r_half']:.5f}: "
          f"{100 * res['err_r_half']:+.2f} %")
    print(f"peak density (binned) = {res['rho_peak']:.4f} (strong shock {rho_jump:g}: "
          f"{res['rho_peak'] / rho_jump:.3f} of it)")
    print(f"L1(rho) = {res['rho']:.4e}")
    print(f"L1(v_r) = {res['v']:.4e}")
    print(f"L1(P) = {res['p']:.4e}")
    print(f"energy in the dump (kinetic + thermal) = {res['e_particles']:.8g}, expected "
          f"{e_expected:.8g}: relative error {e_dump_err:+.3e}")
    log = None
    if args.log:
        log = parse_log(args.log)
        print(f"relative energy error (log, final) = {log['energy']:+.3e}, largest |error| "
              f"over the thermo lines = {log['energy_max']:.3e}")
        print(f"particles at the h cap (final) = {log['capped']:g}, most at a thermo line = "
              f"{log['capped_max']:g}")
        print(f"run: {log['natoms']} particles, {log['steps']} steps, loop time "
              f"{log['loop_s']:.2f} s on {log['procs']} procs")

    if args.png:
        sedov.plot_profiles(frame, t, args.png, args.E, args.rho0, args.gamma, nbins=args.nbins,
                            title=f"{os.path.basename(args.dump)}: {nparticles} particles, "
                                  f"t = {t:g}, step {frame.timestep}")
        print(f"plot: {args.png}")

    if args.bounds:
        values = {"rshock": abs(res["err_r_peak"]), "rhalf": abs(res["err_r_half"]),
                  "l1rho": res["rho"], "l1v": res["v"], "l1p": res["p"],
                  "edump": abs(e_dump_err), "peak": res["rho_peak"]}
        if log is not None:
            values["energy"] = abs(log["energy"])
            values["capped"] = log["capped"]
        return cli.assert_bounds(
            args.bounds, values, lower=("peak",), error=parser.error,
            unavailable={} if log is not None else {"energy": "needs --log",
                                                    "capped": "needs --log"})
    return 0


if __name__ == "__main__":
    sys.exit(main())
