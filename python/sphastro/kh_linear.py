#!/usr/bin/env python3
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
"""Linear reference for the Kelvin-Helmholtz scene: the seeded mode of McNally, Lyra & Passy
(2012, ApJS 201, 18) evolved with the Euler equations linearised about their base state.

The base state (their eqs. 1-4; examples/kelvin_helmholtz/README.md) is a steady solution of
the Euler equations: uniform P0 = 5/2, rho0(y), U(y) along x, no v_y. A perturbation
q'(y, t) exp(i k x) with k = 4 pi obeys (ideal gas, gamma = 5/3; P0 uniform, so the
v'.grad P0 term vanishes)::

    d rho'/dt = -i k U rho' - rho0_y v' - rho0 (i k u' + v'_y)
    d u'/dt   = -i k U u' - U_y v' - i k p' / rho0
    d v'/dt   = -i k U v' - p'_y / rho0
    d p'/dt   = -i k U p' - gamma P0 (i k u' + v'_y)

(the linearised compressible Euler equations about a parallel shear flow, e.g. Chandrasekhar
1961, Hydrodynamic and Hydromagnetic Stability; Berlok & Pfrommer 2019, MNRAS 485, 908). The seed v_y = 0.01 sin(4 pi x)
is v' = -0.01 i, the other fields 0. The y direction is periodic on [0, 1] and is solved with
Fourier derivatives (NY points), the time with the classical 4th-order Runge-Kutta scheme.

The mode amplitude is McNally et al.'s (their eqs. 6-9): with the weight
w(y) = exp(-4 pi |y - 1/4|) for y < 1/2 and exp(-4 pi |(1 - y) - 1/4|) for y >= 1/2,
s = sum v_y sin(4 pi x) w, c = sum v_y cos(4 pi x) w, d = sum w, M = 2 sqrt((s/d)^2 + (c/d)^2).
For a single Fourier mode v_y = Re(v'(y) exp(i k x)) the x sums give
M = |integral v' w dy| / integral w dy, which is 0.01 at t = 0.

This is the exact (inviscid) evolution while the perturbation stays small; it is not the
non-linear solution once the billows roll up (M of order 0.1 and more).

Usage::

    python3 -m sphastro.kh_linear [--ny 1024] [--tend 2] [--out kh_linear.txt]

writes the columns t, M (every --dt-out) and prints the late-time growth rate
d ln M / dt.
"""

import argparse
import sys

import numpy as np

GAMMA = 5.0 / 3.0
P0 = 2.5
RHO1, RHO2 = 1.0, 2.0
U1, U2 = 0.5, -0.5
L = 0.025
K = 4.0 * np.pi
V0 = 0.01


def base_state(y):
    """rho0(y), U(y) of McNally et al. (2012), eqs. 1-4 (y in [0, 1))."""
    y = np.asarray(y, dtype=float)
    rhom, um = 0.5 * (RHO1 - RHO2), 0.5 * (U1 - U2)
    e1 = np.exp((y - 0.25) / L)
    e2 = np.exp((0.25 - y) / L)
    e3 = np.exp((y - 0.75) / L)
    e4 = np.exp((0.75 - y) / L)
    rho = np.select([y < 0.25, y < 0.5, y < 0.75],
                    [RHO1 - rhom * e1, RHO2 + rhom * e2, RHO2 + rhom * e3],
                    RHO1 - rhom * e4)
    u = np.select([y < 0.25, y < 0.5, y < 0.75],
                  [U1 - um * e1, U2 + um * e2, U2 + um * e3],
                  U1 - um * e4)
    return rho, u


def weight(y):
    """McNally et al.'s (2012) mode weight: exp(-4 pi |y - 1/4|), mirrored for y >= 1/2."""
    y = np.asarray(y, dtype=float)
    return np.where(y < 0.5, np.exp(-4.0 * np.pi * np.abs(y - 0.25)),
                    np.exp(-4.0 * np.pi * np.abs((1.0 - y) - 0.25)))


def evolve(ny=1024, tend=2.0, dt_out=0.01, courant=0.5):
    """Integrate the linearised equations; return (times, M)."""
    y = (np.arange(ny) + 0.5) / ny
    rho0, U = base_state(y)
    ky = 2.0 * np.pi * np.fft.fftfreq(ny, d=1.0 / ny)

    def ddy(f):
        return np.fft.ifft(1j * ky * np.fft.fft(f))

    rho0_y = ddy(rho0).real
    U_y = ddy(U).real
    w = weight(y)
    wsum = w.sum()

    def rhs(q):
        r, u, v, p = q
        div = 1j * K * u + ddy(v)
        adv = -1j * K * U
        return np.array([adv * r - rho0_y * v - rho0 * div,
                         adv * u - U_y * v - 1j * K * p / rho0,
                         adv * v - ddy(p) / rho0,
                         adv * p - GAMMA * P0 * div])

    q = np.zeros((4, ny), dtype=complex)
    q[2] = -1j * V0
    cmax = np.sqrt(GAMMA * P0 / rho0.min())
    # RK4 is stable for |lambda dt| < 2.8 on the imaginary axis; the largest |lambda| is about
    # k |U| + c sqrt(k^2 + ky_max^2)
    lam = K * np.abs(U).max() + cmax * np.hypot(K, np.abs(ky).max())
    nsub = max(1, int(np.ceil(dt_out / (courant * 2.8 / lam))))
    dt = dt_out / nsub
    times, amps = [0.0], [abs(np.sum(q[2] * w)) / wsum]
    nout = int(round(tend / dt_out))
    for n in range(nout):
        for _ in range(nsub):
            k1 = rhs(q)
            k2 = rhs(q + 0.5 * dt * k1)
            k3 = rhs(q + 0.5 * dt * k2)
            k4 = rhs(q + dt * k3)
            q = q + dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
        times.append((n + 1) * dt_out)
        amps.append(abs(np.sum(q[2] * w)) / wsum)
    return np.array(times), np.array(amps)


def load_or_compute(path=None, ny=1024, tend=2.0, dt_out=0.01):
    """(t, M) from a file written by this script, or computed now when path is None/missing."""
    import os
    if path and os.path.exists(path):
        data = np.loadtxt(path)
        return data[:, 0], data[:, 1]
    t, m = evolve(ny, tend, dt_out)
    if path:
        np.savetxt(path, np.column_stack([t, m]), fmt="%.6f %.8e",
                   header=f"McNally et al. 2012 seed, linearised Euler, ny {ny}: t M")
    return t, m


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--ny", type=int, default=1024, help="Fourier points in y (1024)")
    parser.add_argument("--tend", type=float, default=2.0)
    parser.add_argument("--dt-out", type=float, default=0.01)
    parser.add_argument("--out", default=None, help="write the columns t M to this file")
    args = parser.parse_args(argv)
    t, m = evolve(args.ny, args.tend, args.dt_out)
    if args.out:
        np.savetxt(args.out, np.column_stack([t, m]), fmt="%.6f %.8e",
                   header=f"McNally et al. 2012 seed, linearised Euler, ny {args.ny}: t M")
    for tt in (0.25, 0.5, 0.75, 1.0, 1.5, 2.0):
        if tt <= t[-1] + 1e-9:
            print(f"t = {tt:4.2f}  M = {np.interp(tt, t, m):.5e}")
    sel = t >= 0.5 * t[-1]
    rate = np.polyfit(t[sel], np.log(m[sel]), 1)[0]
    print(f"growth rate d ln M/dt over t in [{0.5 * t[-1]:g}, {t[-1]:g}] = {rate:.4f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
