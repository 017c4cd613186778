#!/usr/bin/env python3
"""Compare an SPH-ASTRO Gresho-Chan vortex dump with the exact (steady) vortex.

Usage (from anywhere; python3 of build/venv, on PATH after source build/env.sh)::

    python3 examples/gresho/analyse.py DUMPFILE [--rmax 0.5] [--png out.png]
        [--log LOGFILE] [--log-png out_log.png] [--series DUMP.series]
        [--assert 'l1=0.05,vr=0.01']

The dump must be a LAMMPS text ``dump custom`` of the last frame with the columns x, y, vx,
vy (and rho, pressure, u, alpha if present), as written by ``in.gresho``. The vortex is
centred at the origin. Per particle, r = |(x, y)|, v_phi = (x vy - y vx) / r and
v_r = (x vx + y vy) / r; the exact solution at every time is the initial profile::

    v_phi = 5 r, 2 - 5 r, 0        P = 5 + 12.5 r^2, 9 + 12.5 r^2 - 20 r + 4 ln(5 r), 3 + 4 ln 2

for r < 0.2, 0.2 <= r < 0.4, r >= 0.4 (Gresho & Chan 1990; Springel 2010, MNRAS 401, 791),
rho = 1, v_r = 0. Printed, one per line: L1(v_phi) = mean |v_phi - v_phi,exact| over the
particles with r < rmax (the headline figure; ``l1`` in --assert), L1(v_r), L1(P), L1(rho)
over the same particles, the particle count, and from the LAMMPS log (``--log``, default
``log.X`` beside ``dump.X``) the relative total-energy error, the change of the kinetic
energy and of L_z, and the mean alpha of a viscosity switch.

--png writes the v_phi(r) profile (particles, binned mean, exact) with P(r) and alpha(r);
--log-png the energy, L_z and mean-alpha time series from the log; --series (a dump with
several frames, ``-var every 0.1`` in in.gresho) adds L1(v_phi) against time to --log-png.
``--periodic`` is accepted and ignored (the box is always periodic), so the script takes the
same arguments as examples/sod/analyse.py.
"""

import argparse
import os
import sys

import numpy as np

from sphastro import cli
from sphastro.dump import read_last_frame
from sphastro.gresho import (assert_values, default_log, gresho_errors, log_figures, plot_log,
                             plot_profiles, read_thermo, series_errors)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("dump", help="LAMMPS text dump custom file (the last frame is used)")
    parser.add_argument("--rmax", type=float, default=0.5,
                        help="measure over particles with r < rmax (default 0.5)")
    parser.add_argument("--png", default=None, help="write the v_phi, P, alpha profile plot")
    parser.add_argument("--log", default=None,
                        help="LAMMPS log of the run (default: log.X beside dump.X)")
    parser.add_argument("--log-png", default=None,
                        help="write energy / L_z / alpha (and --series L1) against time")
    parser.add_argument("--series", default=None,
                        help="multi-frame dump (in.gresho -var every DT): L1(v_phi) vs time")
    parser.add_argument("--periodic", action="store_true", help="accepted and ignored")
    cli.add_assert_argument(parser, "fail (exit 1) unless every listed L1 error is below its "
                            "bound, e.g. l1=0.05,vr=0.01 (l1 = v_phi; also vr, P, rho)")
    args = parser.parse_args(argv)

    frame = read_last_frame(args.dump)
    err = gresho_errors(frame, args.rmax)
    t = frame.time
    print(f"time = {t:g}" if t is not None else "time = (no TIME item)")
    print(f"L1(vphi) = {err['vphi']:.3e}")
    print(f"L1(vr) = {err['vr']:.3e}")
    print(f"L1(P) = {err['p']:.3e}")
    print(f"L1(rho) = {err['rho']:.3e}")
    if "alpha_mean" in err:
        print(f"mean alpha (r < {args.rmax:g}) = {err['alpha_mean']:.3e}")
    print(f"particles measured = {err['n']} of {len(frame.columns['x'])}")

    log = args.log or default_log(args.dump)
    thermo = None
    if log and os.path.exists(log):
        thermo = read_thermo(log)
        figs = log_figures(thermo)
        if "dE_max" in figs:
            print(f"energy: max |E - E0|/|E0| = {figs['dE_max']:.2e}, at end {figs['dE_end']:.2e}")
        if "ekin_ratio" in figs:
            print(f"E_kin(end)/E_kin(0) = {figs['ekin_ratio']:.4f}")
        if "lz_ratio" in figs:
            print(f"L_z(end)/L_z(0) = {figs['lz_ratio']:.4f} (not conserved in a periodic box)")
        if "px_max" in figs:
            print(f"momentum: max |p_x|, |p_y| = {figs['px_max']:.1e}, {figs['py_max']:.1e}")
        if "alpha_mean_end" in figs:
            print(f"switch: mean alpha at end = {figs['alpha_mean_end']:.3e}, "
                  f"largest alpha at end = {figs['alpha_max_end']:.3e}")

    if args.png:
        label = "switch" if "alpha" in frame.columns and np.ptp(frame.columns["alpha"]) > 0 \
            else "SPH"
        plot_profiles([frame], [label], args.png, args.rmax,
                      title=f"{os.path.basename(args.dump)}: N = {len(frame.columns['x'])}, "
                            f"step {frame.timestep}, t = {t if t is not None else float('nan'):g}")
        print(f"profile plot: {args.png}")
    if args.log_png:
        series = [series_errors(args.series, args.rmax)] if args.series else None
        plot_log([thermo or {}], [os.path.basename(args.dump)], args.log_png, series)
        print(f"time-series plot: {args.log_png}")

    if args.bounds:
        return cli.assert_bounds(args.bounds, assert_values(err), error=parser.error,
                                 conditions={"particles in the measured region": err["n"] > 0})
    return 0


if __name__ == "__main__":
    sys.exit(main())
