#!/usr/bin/env python3
"""Compare the spreading of a Gaussian u bump (examples/conduction/in.conduction) with the
exact solution of the diffusion equation.

Usage (python3 of build/venv, on PATH after source build/env.sh)::

    python3 examples/conduction/analyse.py DUMPFILE [--kappa 1] [--rho 1]
        [--u0 1] [--log log.lammps] [--png out.png]
        [--assert 'growth=0.05,amp=0.05,energy=1e-12']

The dump is a LAMMPS text ``dump custom`` with the columns x, rho (c_sph[1]) and u (c_sph[2])
and ``dump_modify time yes``; every frame is used. For each frame the width of the bump is
measured from its second moment about its centre of mass,

    sigma^2 = sum_i m (u_i - u0) (x_i - xbar)^2 / sum_i m (u_i - u0),

(equal masses; u0 is the background, default 1) and its amplitude as the largest u - u0.
The exact solution of du/dt = D d2u/dx2 with D = kappa / rho for a Gaussian start is a
Gaussian of the same area with sigma^2(t) = sigma0^2 + 2 D t and amplitude
A0 sigma0 / sigma(t). Printed:

* ``growth``: the relative error of the measured growth sigma^2(t) - sigma0^2 against 2 D t
  at the last frame, and the effective diffusivity (slope of sigma^2(t) over all frames / 2);
* ``amp``: the relative error of the amplitude at the last frame against A0 sigma0/sigma(t)
  (A0 and sigma0 are the measured ones of the first frame);
* ``energy``: the relative change of sum_i m (u_i - u0) between the first and last frames
  (conduction conserves it pair by pair).

``--assert`` fails (exit 1) unless every listed |figure| is within its bound.
"""

import argparse
import sys

import numpy as np

from sphastro import cli
from sphastro.dump import read_frames


def moments(frame, u0):
    cols = frame.columns
    x = cols["x"]
    u = cols["c_sph[2]"]
    du = u - u0
    area = du.sum()
    xbar = (du * x).sum() / area
    sigma2 = (du * (x - xbar) ** 2).sum() / area
    return area, sigma2, du.max(), cols["c_sph[1]"].mean()


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("dump")
    parser.add_argument("--kappa", type=float, default=1.0, help="conduction KAPPA (default 1)")
    parser.add_argument("--rho", type=float, default=None,
                        help="density for D = kappa / rho (default: mean rho of the dump)")
    parser.add_argument("--u0", type=float, default=1.0, help="background u (default 1)")
    parser.add_argument("--png", default=None, help="write sigma^2(t) and amplitude to a PNG")
    cli.add_assert_argument(parser, "fail (exit 1) unless every listed |figure| is within its "
                            "bound: growth, amp, energy")
    args = parser.parse_args(argv)

    times, s2, amps, areas = [], [], [], []
    rho_mean = None
    for frame in read_frames(args.dump):
        area, sigma2, amp, rho = moments(frame, args.u0)
        times.append(frame.time)
        s2.append(sigma2)
        amps.append(amp)
        areas.append(area)
        rho_mean = rho
    if len(times) < 2:
        sys.exit("analyse.py: need at least two frames with ITEM: TIME")
    t = np.array(times) - times[0]
    s2 = np.array(s2)
    rho = args.rho if args.rho is not None else rho_mean
    D = args.kappa / rho
    exact_growth = 2.0 * D * t[-1]
    growth_err = (s2[-1] - s2[0]) / exact_growth - 1.0
    slope = np.polyfit(t, s2, 1)[0]
    amp_exact = amps[0] * np.sqrt(s2[0] / (s2[0] + exact_growth))
    amp_err = amps[-1] / amp_exact - 1.0
    energy_err = areas[-1] / areas[0] - 1.0

    print(f"frames = {len(t)}, t = {t[-1]:.6g}, rho = {rho:.6g}, D = kappa/rho = {D:.6g}")
    print(f"sigma0^2 = {s2[0]:.6g}, sigma^2(t) = {s2[-1]:.6g}, exact {s2[0] + exact_growth:.6g}")
    print(f"growth error = {growth_err:.4e}  (measured sigma^2 growth / 2 D t - 1)")
    print(f"effective D = {slope / 2.0:.6g} (fit of sigma^2(t) / 2; ratio {slope / 2.0 / D:.4f})")
    print(f"amplitude = {amps[-1]:.6g}, exact {amp_exact:.6g}, amp error = {amp_err:.4e}")
    print(f"energy error = {energy_err:.3e}  (sum m (u - u0), last vs first frame)")

    if args.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(1, 2, figsize=(9, 3.5))
        ax[0].plot(t, s2, "o", label="SPH")
        ax[0].plot(t, s2[0] + 2 * D * t, "-", label=r"$\sigma_0^2 + 2Dt$")
        ax[0].set_xlabel("t")
        ax[0].set_ylabel(r"$\sigma^2$")
        ax[0].legend()
        ax[1].plot(t, amps, "o", label="SPH")
        ax[1].plot(t, amps[0] * np.sqrt(s2[0] / (s2[0] + 2 * D * t)), "-", label="exact")
        ax[1].set_xlabel("t")
        ax[1].set_ylabel("amplitude")
        ax[1].legend()
        fig.tight_layout()
        fig.savefig(args.png, dpi=100)

    if args.bounds:
        figures = {"growth": abs(growth_err), "amp": abs(amp_err), "energy": abs(energy_err)}
        return cli.assert_bounds(args.bounds, figures, error=parser.error)
    return 0


if __name__ == "__main__":
    sys.exit(main())
