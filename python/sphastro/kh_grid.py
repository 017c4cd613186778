#!/usr/bin/env python3
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
"""Non-linear grid reference for the Kelvin-Helmholtz scene: the test of McNally, Lyra & Passy
(2012, ApJS 201, 18) solved with a second-order Godunov finite-volume code, and its mode
amplitude M(t) (their eqs. 6-9) every 0.01 up to t = 2.

The solver is examples/kelvin_helmholtz/kh_grid.cpp (compiled here with g++ -O3): 2D compressible
Euler, gamma 5/3, periodic unit box, MUSCL-Hancock with MC-limited primitive slopes and the
HLLC Riemann solver (Toro 2009, Riemann Solvers and Numerical Methods for Fluid Dynamics,
sec. 14.4 and 10.4), Strang-split directions, CFL 0.4; the initial state (their eqs. 1-5) is
sampled at the cell centres, so M(0) = 0.01 exactly. M uses the SPH analysis' weights
(in.kelvin_helmholtz) with the cell area in place of m/rho.

The script runs the resolutions given (default 128, 256, 512), prints the convergence
(max |M_N - M_2N| / M_2N over [0, tend] and at t = 1, 1.5, 2), the difference to the linear
reference (kh_linear.py) at t = 0.5 and 1, and writes the finest run's table.

Usage::

    python3 -m sphastro.kh_grid [--n 128,256,512] [--tend 2] [--out kh_grid_reference.txt]
        [--cache DIR]   (keeps kh_grid_N.txt of each run there and reuses them)
        [--threads 1]   (OpenMP threads of the solver; the lines of a sweep are independent,
                         so the result does not depend on the thread count)
"""

import argparse
import hashlib
import os
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np

from .runs import repo_root


def source(root=None):
    """examples/kelvin_helmholtz/kh_grid.cpp of the SPH-ASTRO tree (root, else $SPH_ASTRO_ROOT)."""
    return os.path.join(repo_root(root), "examples", "kelvin_helmholtz", "kh_grid.cpp")


def binary(workdir=None, root=None):
    """Path of the compiled kh_grid.cpp (compiled once per source version)."""
    src = source(root)
    with open(src, "rb") as f:
        tag = hashlib.sha1(f.read()).hexdigest()[:12]
    workdir = workdir or os.path.join(tempfile.gettempdir(), f"sphastro-kh-grid-{os.getuid()}")
    os.makedirs(workdir, exist_ok=True)
    exe = os.path.join(workdir, f"kh_grid-{tag}")
    if not os.path.exists(exe):
        cxx = os.environ.get("CXX") or shutil.which("g++") or "c++"
        tmp = exe + f".{os.getpid()}"
        subprocess.run([cxx, "-O3", "-std=c++11", "-fopenmp", "-o", tmp, src], check=True)
        os.replace(tmp, exe)
    return exe


def run(n, tend=2.0, dt_out=0.01, cfl=0.4, cache=None, threads=1, root=None):
    """(t, M) of one N x N run; read from cache/kh_grid_N.txt when it holds the same run."""
    path = os.path.join(cache, f"kh_grid_{n}.txt") if cache else None
    if path and os.path.exists(path):
        data = np.loadtxt(path, ndmin=2)
        if len(data) == int(round(tend / dt_out)) + 1 and abs(data[-1, 0] - tend) < 1e-9:
            return data[:, 0], data[:, 1], float("nan")
    start = time.time()
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    out = subprocess.run([binary(root=root), str(n), repr(tend), repr(dt_out), repr(cfl)], check=True,
                         capture_output=True, text=True, env=env).stdout
    wall = time.time() - start
    data = np.loadtxt(out.splitlines(), ndmin=2)
    if path:
        os.makedirs(cache, exist_ok=True)
        np.savetxt(path, data, fmt="%.6f %.10e")
    return data[:, 0], data[:, 1], wall


def load(path):
    """(t, M) of a table written by this script (kh_grid_reference.txt)."""
    data = np.loadtxt(path, ndmin=2)
    return data[:, 0], data[:, 1]


def differences(m_coarse, m_fine, t):
    """max |M_N - M_2N| / M_2N over all t and at t = 1, 1.5, 2 (the relative gap)."""
    rel = np.abs(m_coarse - m_fine) / m_fine
    out = {"max": float(rel.max()), "tmax": float(t[np.argmax(rel)])}
    for tt in (1.0, 1.5, 2.0):
        if tt <= t[-1] + 1e-9:
            out[tt] = float(rel[np.argmin(np.abs(t - tt))])
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--n", default="128,256,512", help="cells a side, comma-separated")
    parser.add_argument("--tend", type=float, default=2.0)
    parser.add_argument("--dt-out", type=float, default=0.01)
    parser.add_argument("--cfl", type=float, default=0.4)
    parser.add_argument("--out", default=None, help="write the finest run's t M table here")
    parser.add_argument("--cache", default=None, help="keep/reuse kh_grid_N.txt in this folder")
    parser.add_argument("--threads", type=int, default=1, help="OpenMP threads (default 1)")
    args = parser.parse_args(argv)
    sizes = sorted(int(s) for s in args.n.split(","))

    runs = {}
    for n in sizes:
        t, m, wall = run(n, args.tend, args.dt_out, args.cfl, args.cache, args.threads)
        runs[n] = (t, m)
        tag = f"{wall:.1f} s" if wall == wall else "from the cache"
        print(f"N {n:5d}: M(0) = {m[0]:.6f}  M(0.5) = {np.interp(0.5, t, m):.5f}  "
              f"M(1) = {np.interp(1.0, t, m):.5f}  M(1.5) = {np.interp(1.5, t, m):.5f}  "
              f"M(2) = {np.interp(2.0, t, m):.5f}  ({tag})")
    gaps = {}
    for a, b in zip(sizes[:-1], sizes[1:]):
        t = runs[b][0]
        d = differences(runs[a][1], runs[b][1], t)
        gaps[b] = (a, d)
        at = "  ".join(f"t = {k:g}: {v:.4f}" for k, v in d.items() if not isinstance(k, str))
        print(f"|M_{a} - M_{b}| / M_{b}: max {d['max']:.4f} (t = {d['tmax']:.2f})  {at}")

    from . import kh_linear
    tl, ml = kh_linear.load_or_compute(None, ny=256, tend=min(args.tend, 2.0), dt_out=args.dt_out)
    tf, mf = runs[sizes[-1]]
    for tt in (0.5, 1.0):
        if tt <= tf[-1] + 1e-9:
            g, lin = np.interp(tt, tf, mf), np.interp(tt, tl, ml)
            print(f"t = {tt:g}: grid N {sizes[-1]} M = {g:.5f}, linear {lin:.5f}, "
                  f"grid / linear - 1 = {g / lin - 1.0:+.4f}")

    if args.out:
        n = sizes[-1]
        lines = ["Kelvin-Helmholtz of McNally, Lyra & Passy (2012): mode amplitude M (eqs. 6-9)",
                 f"from kh_grid.cpp (MUSCL-Hancock, MC limiter, HLLC, Strang split, CFL {args.cfl:g}),"
                 f" {n}^2 cells, cell-centre sampled initial state",
                 "command: python3 -m sphastro.kh_grid --n "
                 f"{args.n} --tend {args.tend:g} --out examples/kelvin_helmholtz/kh_grid_reference.txt"]
        if n in gaps:
            a, d = gaps[n]
            lines.append(f"|M_{a} - M_{n}| / M_{n}: max {d['max']:.4f} over t in [0, {args.tend:g}], "
                         + ", ".join(f"{v:.4f} at t = {k:g}" for k, v in d.items()
                                     if not isinstance(k, str)))
        lines.append("columns: t M")
        np.savetxt(args.out, np.column_stack(runs[n]), fmt="%.2f %.6e", header="\n".join(lines))
        print(f"table: {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
