#!/usr/bin/env python3
"""Accretion rate of the Bondi scene (examples/bondi/in.bondi) against Bondi's (1952).

Usage (python3 of build/venv, on PATH after source build/env.sh)::

    python3 examples/bondi/analyse.py bondi.dat [--t0 0.2] [--t1 TEND] [--rho 1e-3]
        [--assert 'ratio=0.72,mass=1e-14']

bondi.dat is the file of in.bondi's fix ave/time: step, time, sink mass M, accreted mass,
accreted particles, mass(all), the sinks' mass with its round-off (fix sph/astro/sink
vector[6]), the number of gas particles and their mass m; the total mass is taken as the
sinks' + N_gas m (mass(all) adds its own round-off, about N eps). The measured rate is the least-squares slope of the accreted
mass against time over t0 <= t <= t1 (default: t0 to the end); the analytic one is Bondi's
(1952, MNRAS 112, 195) isothermal rate

    dM/dt = 4 pi lambda G^2 M^2 rho_inf / c_s^3,   lambda = e^(3/2) / 4,

with G = c_s = 1 (in.bondi's units) at the mean sink mass over the interval. Printed: both
rates and their ratio, and the largest relative change of the total mass (gas + sink) over the
run. ``--assert``: ``ratio`` is a lower bound on measured/analytic, ``mass`` an upper bound on
the mass change.
"""

import argparse
import math
import sys

import numpy as np

from sphastro import cli

LAMBDA_ISOTHERMAL = math.exp(1.5) / 4.0


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("series", help="bondi.dat of in.bondi")
    parser.add_argument("--t0", type=float, default=0.2, help="start of the fit (0.2)")
    parser.add_argument("--t1", type=float, default=None, help="end of the fit (the last time)")
    parser.add_argument("--rho", type=float, default=1e-3, help="rho_inf of the run (1e-3)")
    cli.add_assert_argument(parser, "e.g. ratio=0.72,mass=1e-14 (ratio: a lower bound)")
    args = parser.parse_args(argv)

    data = np.loadtxt(args.series, comments="#")
    t, msink, macc, nacc = data[:, 1], data[:, 2], data[:, 3], data[:, 4]
    mtot = np.array([math.fsum([a, n * m]) for a, n, m in data[:, 6:9]])
    t1 = t[-1] if args.t1 is None else args.t1
    sel = (t >= args.t0) & (t <= t1)
    if sel.sum() < 3:
        parser.error(f"fewer than 3 rows with {args.t0} <= t <= {t1}")
    slope = np.polyfit(t[sel], macc[sel], 1)[0]
    mean_m = msink[sel].mean()
    analytic = 4.0 * math.pi * LAMBDA_ISOTHERMAL * mean_m ** 2 * args.rho
    ratio = slope / analytic
    mass = np.max(np.abs(mtot - mtot[0])) / mtot[0]
    print(f"Bondi: {int(nacc[-1])} particles accreted by t = {t[-1]:g} "
          f"(mass {macc[-1]:.6g}; sink mass {msink[-1]:.6g})")
    print(f"Bondi: rate over {args.t0:g} <= t <= {t1:g}: measured {slope:.5g}, analytic "
          f"4 pi lambda G^2 M^2 rho / c^3 = {analytic:.5g} (M = {mean_m:.6g}): "
          f"ratio {ratio:.4f}")
    print(f"Bondi: largest relative change of the total mass {mass:.3e}")
    if args.bounds:
        return cli.assert_bounds(args.bounds, {"ratio": ratio, "mass": mass},
                                 lower=("ratio",), error=parser.error)
    return 0


if __name__ == "__main__":
    sys.exit(main())
