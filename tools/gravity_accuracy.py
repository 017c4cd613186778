#!/usr/bin/env python3
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
"""Self-gravity accuracy against run time: PPPM (periodic) and MSM (open) kspace settings.

For each solver a random cloud of N equal-mass particles (periodic box of side 10 for
pppm/sph/astro/gravity; ball of radius 5 with boundary m m m for msm/sph/astro/gravity; G = 1,
softening length h = 0.5 for every particle, M4 kernel, pair cutoff 3) is evaluated with several
kspace accuracies. The reference is compute sph/astro/gravity/direct (Ewald summation at about
1e-10 for the periodic box, direct summation for the ball). Printed and written to
build/output/gravity_accuracy/: relative RMS force error |F - F_ref|_rms / |F_ref|_rms, relative
potential-energy error, the solver's grid, and the wall time of one force evaluation (pair +
kspace, the mean of `run STEPS` without integration, one MPI rank); PNG of error against time.
Usage: python3 tools/gravity_accuracy.py [--n 4000] [--steps 10] [--outdir DIR]
Needs LAMMPS' Python module and the plugin on LAMMPS_PLUGIN_PATH: source build/env.sh first.
"""
import argparse
import os
import re
import time

import numpy as np
from lammps import lammps, LMP_STYLE_ATOM, LMP_TYPE_ARRAY

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
CASES = [("pppm/sph/astro/gravity", True, [1e-2, 1e-3, 1e-4, 1e-5, 1e-6]),
         ("msm/sph/astro/gravity", False, [1e-2, 1e-3, 1e-4, 1e-5, 1e-6])]


def setup(lmp, periodic, n, logfile):
    lmp.commands_list([
        "units lj", "atom_style atomic", "atom_modify map array sort 0 0.0",
        "boundary " + ("p p p" if periodic else "m m m")])
    if periodic:
        lmp.commands_list(["region box block 0 10 0 10 0 10", "create_box 1 box",
                           f"create_atoms 1 random {n} 4711 NULL"])
    else:
        lmp.commands_list(["region box block -6 6 -6 6 -6 6", "create_box 1 box",
                           "region ball sphere 0 0 0 5 units box",
                           f"create_atoms 1 random {n} 4711 ball"])
    lmp.commands_list(["mass 1 1.0", "pair_style sph/astro/gravity 3.0 h 0.5", "pair_coeff * *",
                       "neighbor 0.1 bin", "neigh_modify one 5000 page 50000",
                       "thermo_style custom step pe", "thermo_modify norm no"])


def reference(periodic, n):
    lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    setup(lmp, periodic, n, None)
    if periodic:    # the pair needs a kspace for a periodic box; the reference ignores it
        lmp.command("kspace_style pppm/sph/astro/gravity 1e-3")
    lmp.commands_list(["compute ref all sph/astro/gravity/direct", "variable e equal c_ref",
                       "thermo_style custom step v_e", "run 0"])
    nlocal = lmp.extract_global("nlocal")
    t0 = time.perf_counter()
    lmp.command("run 0 post no")    # the reference once more, timed
    elapsed = time.perf_counter() - t0
    f = np.array(lmp.numpy.extract_compute("ref", LMP_STYLE_ATOM, LMP_TYPE_ARRAY)[:nlocal, :3])
    e = lmp.extract_variable("e")
    ids = np.array(lmp.numpy.extract_atom("id")[:nlocal])
    lmp.close()
    return ids, f, e, elapsed


def evaluate(style, periodic, accuracy, n, steps, logfile):
    lmp = lammps(cmdargs=["-log", logfile, "-screen", "none", "-nocite"])
    setup(lmp, periodic, n, logfile)
    lmp.commands_list([f"kspace_style {style} {accuracy:g}", "run 0"])
    nlocal = lmp.extract_global("nlocal")
    f = np.array(lmp.numpy.extract_atom("f")[:nlocal])
    ids = np.array(lmp.numpy.extract_atom("id")[:nlocal])
    e = lmp.get_thermo("pe")
    t0 = time.perf_counter()
    lmp.command(f"run {steps} pre no post no")
    per_step = (time.perf_counter() - t0) / steps
    lmp.close()
    log = open(logfile).read()
    grid = re.findall(r"grid = (\d+ \d+ \d+)", log)
    cut = re.findall(r"new cutoff = ([0-9.]+)", log)
    return ids, f, e, per_step, (grid[-1] if grid else "?"), (float(cut[-1]) if cut else 3.0)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--n", type=int, default=4000)
    p.add_argument("--steps", type=int, default=10)
    p.add_argument("--outdir", default=os.path.join(ROOT, "build", "output", "gravity_accuracy"))
    args = p.parse_args()
    os.makedirs(args.outdir, exist_ok=True)
    rows = []
    for style, periodic, accuracies in CASES:
        rid, fref, eref, tref = reference(periodic, args.n)
        order_ref = np.argsort(rid)
        for acc in accuracies:
            log = os.path.join(args.outdir, f"log.{style.split('/')[0]}.{acc:g}")
            ids, f, e, dt, grid, cut = evaluate(style, periodic, acc, args.n, args.steps, log)
            order = np.argsort(ids)
            d = f[order] - fref[order_ref]
            err = np.sqrt(np.sum(d**2) / np.sum(fref[order_ref] ** 2))
            rows.append((style, acc, err, abs(e - eref) / abs(eref), grid, cut, dt, tref))
            print(f"{style:24s} accuracy {acc:7.0e}: force error {err:.3e}, energy error "
                  f"{rows[-1][3]:.3e}, grid {grid}, cutoff {cut:.3g}, {dt * 1e3:8.2f} ms/step "
                  f"(reference {tref:.2f} s)", flush=True)
    table = ["| kspace style | accuracy | rel. RMS force error | rel. energy error | grid | "
             "pair cutoff | ms per force evaluation |", "|---|---|---|---|---|---|---|"]
    for style, acc, err, eerr, grid, cut, dt, _ in rows:
        table.append(f"| {style} | {acc:.0e} | {err:.2e} | {eerr:.1e} | {grid} | {cut:.3g} | "
                     f"{dt * 1e3:.1f} |")
    text = "\n".join(table) + "\n"
    print(text)
    with open(os.path.join(args.outdir, "table.md"), "w") as fh:
        fh.write(f"N = {args.n}, one MPI rank; reference: compute sph/astro/gravity/direct\n\n" + text)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    for style, _, _ in CASES:
        sel = [r for r in rows if r[0] == style]
        ax[0].loglog([r[1] for r in sel], [r[2] for r in sel], "o-", label=style)
        ax[1].loglog([r[6] * 1e3 for r in sel], [r[2] for r in sel], "o-", label=style)
    ax[0].loglog([1e-6, 1e-2], [1e-6, 1e-2], "k:", label="error = accuracy")
    ax[0].set_xlabel("kspace accuracy setting"); ax[0].set_ylabel("relative RMS force error")
    ax[1].set_xlabel("ms per force evaluation"); ax[1].set_ylabel("relative RMS force error")
    for a in ax:
        a.legend(fontsize=8)
    fig.suptitle(f"self-gravity accuracy, N = {args.n}, 1 rank")
    fig.tight_layout()
    png = os.path.join(args.outdir, "gravity_accuracy.png")
    fig.savefig(png, dpi=120)
    print(f"wrote {png} and table.md")


if __name__ == "__main__":
    main()
