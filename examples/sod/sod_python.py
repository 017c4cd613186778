#!/usr/bin/env python3
"""Sod shock tube driven from Python through LAMMPS' own Python module.

Runs examples/sod/in.sod inside the Python process, then takes the particles' state
straight from LAMMPS' memory (numpy views of x, v and the SPH-ASTRO per-atom state
d_rho, d_u, and compute sph/astro/atom for the pressure) and compares it with the exact
Riemann solution.

    source build/env.sh
    /usr/bin/python3 examples/sod/sod_python.py [--nx 64] [--assert rho=0.02,vx=0.04]

The plugin is found through LAMMPS_PLUGIN_PATH (set by build/env.sh) or given with --plugin.
"""
import argparse
import os
import sys
import time

import numpy as np
from lammps import LMP_STYLE_ATOM, LMP_TYPE_ARRAY, lammps

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tools"))
from sphastro.sod import sod_errors  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--nx", type=int, default=64, help="left lattice cells per unit length")
    parser.add_argument("--ny", type=int, default=6, help="lattice cells across y and z")
    parser.add_argument("--plugin", default=None, help="path of sphastroplugin.so to load")
    parser.add_argument("--outdir", default=".", help="where LAMMPS writes its dump")
    parser.add_argument("--assert", dest="bounds", default=None,
                        help="exit 1 unless each L1 error is below its bound: rho=..,vx=..,P=..,u=..")
    args = parser.parse_args()

    os.makedirs(args.outdir, exist_ok=True)
    lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite",
                          "-var", "nx", str(args.nx), "-var", "ny", str(args.ny),
                          "-var", "out", os.path.join(args.outdir, "dump.sod_python")])
    if args.plugin:
        lmp.command(f"plugin load {args.plugin}")
    start = time.perf_counter()
    lmp.file(os.path.join(HERE, "in.sod"))
    wall = time.perf_counter() - start

    # the state, read from LAMMPS memory rather than from the dump
    nlocal = lmp.extract_global("nlocal")
    x = lmp.numpy.extract_atom("x")[:nlocal]
    v = lmp.numpy.extract_atom("v")[:nlocal]
    rho = lmp.numpy.extract_atom("d_rho")[:nlocal]
    u = lmp.numpy.extract_atom("d_u")[:nlocal]
    sph = lmp.numpy.extract_compute("sph", LMP_STYLE_ATOM, LMP_TYPE_ARRAY)[:nlocal]
    pressure = sph[:, 1]    # compute sph all sph/astro/atom rho pressure u h
    t = lmp.get_thermo("time")
    box = (lmp.extract_global("boxxlo"), lmp.extract_global("boxxhi"))
    steps = lmp.get_thermo("step")
    # numpy views point into LAMMPS' memory: copy before closing the instance
    columns = {"x": x[:, 0].copy(), "vx": v[:, 0].copy(), "rho": rho.copy(),
               "pressure": pressure.copy(), "u": u.copy()}
    lmp.close()

    err = sod_errors(columns, 5.0 / 3.0, t, x_periodic=box)
    print(f"Sod from Python: {nlocal} particles, {int(steps)} steps to t = {t:g}, "
          f"wall time {wall:.2f} s")
    print(f"L1(rho) = {err['rho']:.3e}")
    print(f"L1(vx) = {err['vx']:.3e}")
    print(f"L1(P) = {err['p']:.3e}")
    print(f"L1(u) = {err['u']:.3e}")
    if not np.isfinite([err['rho'], err['vx'], err['p'], err['u']]).all():
        return 1
    if args.bounds:
        names = {"rho": "rho", "vx": "vx", "P": "p", "u": "u"}
        failed = [k for k, b in (i.split("=") for i in args.bounds.split(","))
                  if not err[names[k]] <= float(b)]
        print("bounds " + args.bounds + (": FAILED " + ",".join(failed) if failed else ": ok"))
        return 1 if failed else 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
