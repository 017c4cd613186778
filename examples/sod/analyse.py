#!/usr/bin/env python3
"""Compare the last frame of an SPH-ASTRO Sod shock-tube dump with the exact solution.

Usage (from anywhere; python3 of build/venv, on PATH after source build/env.sh)::

    python3 examples/sod/analyse.py DUMPFILE [--gamma 1.6666667] [--time T]
        [--png out.png] [--left rho,v,p] [--right rho,v,p] [--x0 0]
        [--xmin -0.5 --xmax 0.5] [--periodic]

The dump must be a LAMMPS text ``dump custom`` with the columns x, vx, rho,
pressure and u.  The time defaults to the dump's ``ITEM: TIME`` (written with
``dump_modify time yes``), else 0.2.  Prints the per-particle L1 errors of
rho, vx, P and u over xmin <= x <= xmax, one per line, and the number of
particles measured.  The exact solution is Toro's exact Riemann solver
(Riemann Solvers and Numerical Methods for Fluid Dynamics, 3rd ed., ch. 4).
"""

import argparse
import os
import sys

from sphastro import cli
from sphastro.dump import read_last_frame
from sphastro.sod import assert_values, plot_profiles, sod_errors


def _state(text):
    """Parse 'rho,v,p' into a tuple of three floats."""
    try:
        values = tuple(float(v) for v in text.split(","))
    except ValueError:
        values = ()
    if len(values) != 3:
        raise argparse.ArgumentTypeError(f"expected rho,v,p (three numbers), got {text!r}")
    return values


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("dump", help="LAMMPS text dump custom file (the last frame is used)")
    parser.add_argument("--gamma", type=float, default=5.0 / 3.0,
                        help="ratio of specific heats (default 5/3)")
    parser.add_argument("--time", type=float, default=None,
                        help="time of the frame (default: the dump's TIME item, else 0.2)")
    parser.add_argument("--png", default=None, help="write a 4-panel profile plot to this file")
    parser.add_argument("--left", type=_state, default=(1.0, 0.0, 1.0),
                        help="left state rho,v,p (default 1,0,1)")
    parser.add_argument("--right", type=_state, default=(0.125, 0.0, 0.1),
                        help="right state rho,v,p (default 0.125,0,0.1)")
    parser.add_argument("--x0", type=float, default=0.0,
                        help="initial position of the discontinuity (default 0)")
    parser.add_argument("--xmin", type=float, default=-0.5, help="measurement window start")
    parser.add_argument("--xmax", type=float, default=0.5, help="measurement window end")
    parser.add_argument("--periodic", action="store_true",
                        help="x is periodic over the dump's box, with the mirrored second "
                             "discontinuity at the box boundary")
    cli.add_assert_argument(parser, "fail (exit 1) unless every listed L1 error is below its "
                            "bound, e.g. rho=0.02,vx=0.03,P=0.02,u=0.03")
    args = parser.parse_args(argv)

    frame = read_last_frame(args.dump)
    t = args.time if args.time is not None else (frame.time if frame.time is not None else 0.2)
    x_periodic = tuple(frame.box[0]) if args.periodic else None
    err = sod_errors(frame, args.gamma, t, args.left, args.right, args.x0,
                     (args.xmin, args.xmax), x_periodic)
    print(f"L1(rho) = {err['rho']:.3e}")
    print(f"L1(vx) = {err['vx']:.3e}")
    print(f"L1(P) = {err['p']:.3e}")
    print(f"L1(u) = {err['u']:.3e}")
    print(f"particles measured = {err['n']}")
    if args.png:
        plot_profiles(frame, args.gamma, t, args.left, args.right, args.x0, args.png,
                      xlim=(args.xmin, args.xmax),
                      title=f"{os.path.basename(args.dump)}: step {frame.timestep}, t = {t:g}",
                      x_periodic=x_periodic)
    if args.bounds:
        return cli.assert_bounds(args.bounds, assert_values(err), error=parser.error,
                                 conditions={"particles in the measured window": err["n"] > 0})
    return 0


if __name__ == "__main__":
    sys.exit(main())
