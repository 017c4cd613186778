#!/usr/bin/python3
"""Toy star (seed 001) set up, run and analysed from Python through LAMMPS' Python module.

The same scene as examples/toystar/in.toystar, written as LAMMPS commands issued from
Python: lambda comes from the Python reference (tools/sphastro/toystar.py) instead of the
input's own formula, the segment loop (re-typing the particles by h so that each type's
neighbour-list cutoff follows its h) is a Python loop, and the state is read straight from
LAMMPS' memory (numpy views of x, v and the per-atom SPH state d_rho, d_h) after the damped
relaxation and after the undamped continuation.

    source build/env.sh
    /usr/bin/python3 examples/toystar/toystar_python.py [--n 8] [--npoly 1] [--png toystar_py.png]
        [--assert 'l1=0.025,rfit=0.014,drift_l1=1e-3,drift_r=2e-3,ekin=1e-4,energy=2e-4']

``--assert`` bounds (upper bounds; exit 1 if one fails): ``l1`` (L1(rho)/rho_c of the relaxed
star), ``rfit`` (|relative error of R_fit|), ``l1free``, ``rfitfree`` (the same after the
continuation), ``drift_l1``, ``drift_r`` (their changes; drift_r relative to R), ``ekin``
(largest kinetic / thermal energy sampled during the continuation), ``energy`` (|relative
total-energy error| of the continuation). The figures are defined in examples/toystar/analyse.py.
The plugin is found through LAMMPS_PLUGIN_PATH (set by build/env.sh) or given with --plugin.
"""
import argparse
import math
import os
import sys
import time

import numpy as np
from lammps import LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR, lammps

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tools"))
from sphastro import toystar  # noqa: E402


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
    parser.add_argument("--nu", type=float, default=1.0, help="damping -nu v (seed 001)")
    parser.add_argument("--trelax", type=float, default=12.0)
    parser.add_argument("--tfree", type=float, default=6.0)
    parser.add_argument("--hfact", type=float, default=1.2)
    parser.add_argument("--segsteps", type=int, default=50)
    parser.add_argument("--plugin", default=None, help="path of sphastroplugin.so to load")
    parser.add_argument("--outdir", default=".", help="where LAMMPS writes its log")
    parser.add_argument("--png", default=None, help="plot rho(r) after both phases")
    parser.add_argument("--assert", dest="bounds", default=None)
    args = parser.parse_args()

    M, R, k, n = args.M, args.R, args.k, args.npoly
    lam = toystar.toystar_lambda(M, R, k, n)
    gamma = 1.0 + 1.0 / n
    a = 2.0 * R / args.n                    # fcc lattice constant
    ntypes, hstep, margin, skin = 6, 1.25, 1.3, 0.3

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
create_box      {ntypes} box
region          ball sphere 0.0 0.0 0.0 {R} units box
lattice         fcc {4.0 / a ** 3!r} origin 0.0 0.0 0.0
create_atoms    1 region ball
mass            * 1.0
reset_atoms     id sort yes
""")
    natoms = lmp.get_natoms()
    mass = M / natoms
    h0 = args.hfact * (mass / (M / (4.0 / 3.0 * math.pi * R ** 3))) ** (1.0 / 3.0)
    href = 0.7 * h0
    lmp.commands_string(f"""
mass            * {mass!r}
pair_style      sph/astro kernel m4 eos polytropic {k!r} {gamma!r} viscosity classic 1.0 2.0
pair_coeff      * *
fix             gas all sph/astro courant 0.3
fix             hvar all sph/astro/h iterate hfact {args.hfact} margin {margin}
set             group all d_h {1.3 * h0!r}
# seed 001: -lambda r and -nu v per unit mass; potential energy 1/2 lambda m r^2
variable        fx atom -{lam!r}*mass*x
variable        fy atom -{lam!r}*mass*y
variable        fz atom -{lam!r}*mass*z
variable        epot atom 0.5*{lam!r}*mass*(x*x+y*y+z*z)
fix             grav all addforce v_fx v_fy v_fz energy v_epot
fix_modify      grav energy yes
fix             damp all viscous {args.nu * mass!r}
neigh_modify    every 1 delay 0 check yes
compute         sum all sph/astro/global
thermo_style    custom step time dt c_sum[8] c_sum[9] c_sum[10] c_sum[11] f_hvar[4] cpu
thermo_modify   norm no
thermo          {args.segsteps}
timestep        1e-4
variable        kraw atom 1+floor(ln(d_h/{href!r})/ln({hstep}))
variable        hclass atom (v_kraw<1)+(v_kraw>=1)*(v_kraw<={ntypes})*v_kraw+(v_kraw>{ntypes})*{ntypes}
""")

    def run_until(tstop, ekin_compute=None):
        """Segments of segsteps steps, re-typed by h, until the time reaches tstop; returns
        the largest kinetic energy seen at the segment ends (compute ekin_compute)."""
        ekin_max = 0.0
        while lmp.get_thermo("time") < tstop:
            nlocal = lmp.extract_global("nlocal")
            hmin = float(lmp.numpy.extract_atom("d_h")[:nlocal].min())
            lmp.command("set group all type v_hclass")
            lmp.command(f"neighbor {skin * hmin!r} multi")
            lmp.command(f"run {args.segsteps}")
            if ekin_compute:
                ekin_max = max(ekin_max, global_value(lmp, ekin_compute, 8))
        return ekin_max

    run_until(args.trelax)
    relaxed, t_relaxed = state(lmp)
    eth = global_value(lmp, "sum", 9)
    ekin_relaxed = global_value(lmp, "sum", 8)
    # undamped continuation; compute free takes its energy reference E_0 now
    lmp.commands_string("""
unfix           damp
compute         free all sph/astro/global
thermo_style    custom step time dt c_free[8] c_free[11] c_free[12] f_hvar[4] cpu
thermo_modify   norm no
""")
    ekin_free = run_until(args.trelax + args.tfree, "free")
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
               "energy": abs(energy)}
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
    if args.png:
        toystar.plot_profile([(f"relaxed, t = {t_relaxed:.3g}", relaxed),
                              (f"free, t = {t_free:.3g}", free)], args.png, M, R, k, n,
                             title=f"toy star from Python, {natoms} particles")
        print(f"plot: {args.png}")
    if not all(np.isfinite(list(figures.values()))):
        print("non-finite figure")
        return 1
    if args.bounds:
        failed = []
        for item in args.bounds.split(","):
            name, bound = (s.strip() for s in item.split("="))
            if name not in figures:
                parser.error(f"--assert: unknown figure {name!r} ({', '.join(figures)})")
            ok = figures[name] <= float(bound)
            print(f"check {name} = {figures[name]:.4g} <= {float(bound):.4g}: "
                  f"{'ok' if ok else 'FAILED'}")
            if not ok:
                failed.append(name)
        return 1 if failed else 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
