#!/usr/bin/env python3
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
"""Self-gravity accuracy against run time: the tree, MSM, PPPM and direct summation.

Scenes (G = 1, M4 kernel, one MPI rank):
  cloud    a random cloud of --n equal-mass particles: a ball of radius 5 (open boundaries:
           tree, MSM) and a periodic box of side 10 (PPPM); softening length 0.5
  evrard   the Evrard sphere's initial conditions of examples/evrard (fcc lattice cut to the
           unit sphere and stretched to rho ~ 1/r, --evrard-n cells across), softening length
           the SPH h of the example's start, hfact (m/rho)^(1/3)
  plummer  a Plummer sphere (Plummer 1911; sampled as Aarseth, Henon & Wielen 1974, cut at
           10 a) of --plummer-n particles, a = 1, M = 1, softening length 0.01
The reference is compute sph/astro/gravity/direct (direct summation; Ewald for the periodic
box). Per solver setting: the relative force error of each particle |F - F_ref| / |F_ref|,
its RMS and 99th percentile, the global |F - F_ref|_rms / |F_ref|_rms, the relative
potential-energy error, and the CPU time of one force evaluation (the mean of `run STEPS`
without integration: the tree keeps its structure and recomputes its moments, as between
re-neighbourings; CPU time, not wall time, so that other jobs on the machine disturb it less). Printed and written to build/output/gravity_accuracy/ (table.md, one PNG of
error against time per scene).
Usage: python3 tools/gravity_accuracy.py [--scenes cloud,evrard,plummer] [--n 4000]
       [--evrard-n 24] [--plummer-n 20000] [--thetas 0.3,0.4,0.5,0.6,0.7]
       [--alphas 0.0005,0.001,0.002,0.004] [--tree 'relative 1e-5 leaf 8 group 64' ...]
       [--steps 5] [--outdir DIR]
Needs LAMMPS' Python module and the plugin on LAMMPS_PLUGIN_PATH: source build/env.sh first.
"""
import argparse
import os
import re
import sys
import time

import numpy as np
from lammps import lammps, LMP_STYLE_ATOM, LMP_TYPE_ARRAY

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
sys.path.insert(0, os.path.join(ROOT, "python"))
from sphastro.evrard import create_sphere  # noqa: E402


def plummer_positions(n, seed=4711, rmax=10.0):
    """Plummer sphere, a = M = 1: r from the inverted mass profile, isotropic directions."""
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < n:
        mfrac = rng.uniform(0.0, 1.0, n)
        r = 1.0 / np.sqrt(mfrac ** (-2.0 / 3.0) - 1.0)
        r = r[r < rmax]
        cos_t = rng.uniform(-1.0, 1.0, r.size)
        phi = rng.uniform(0.0, 2.0 * np.pi, r.size)
        sin_t = np.sqrt(1.0 - cos_t**2)
        out.extend(np.column_stack([r * sin_t * np.cos(phi), r * sin_t * np.sin(phi),
                                    r * cos_t]))
    return np.array(out[:n])


def setup(lmp, scene, args, periodic=False):
    lmp.commands_list(["units lj", "atom_style atomic", "atom_modify map array sort 0 0.0",
                       "boundary " + ("p p p" if periodic else "m m m")])
    if scene == "cloud":
        if periodic:
            lmp.commands_list(["region box block 0 10 0 10 0 10", "create_box 1 box",
                               f"create_atoms 1 random {args.n} 4711 NULL"])
        else:
            lmp.commands_list(["region box block -6 6 -6 6 -6 6", "create_box 1 box",
                               "region ball sphere 0 0 0 5 units box",
                               f"create_atoms 1 random {args.n} 4711 ball"])
        lmp.commands_list(["mass 1 1.0", "pair_style sph/astro/gravity 3.0 h 0.5",
                           "pair_coeff * *"])
    elif scene == "evrard":
        create_sphere(lmp, args.evrard_n)
        lmp.commands_list([
            "sph/astro/state", "set group all d_h v_hinit",
            "pair_style sph/astro/gravity 1000.0", "pair_coeff * *"])
    elif scene == "plummer":
        pos = plummer_positions(args.plummer_n)
        ext = np.abs(pos).max() * 1.01
        lmp.commands_list([f"region box block {-ext} {ext} {-ext} {ext} {-ext} {ext}",
                           "create_box 1 box"])
        lmp.create_atoms(len(pos), None, [1] * len(pos), pos.ravel().tolist())
        lmp.commands_list([f"mass 1 {1.0 / len(pos)!r}",
                           "pair_style sph/astro/gravity 1000.0 h 0.01", "pair_coeff * *"])
    lmp.commands_list(["neighbor 0.1 bin", "neigh_modify one 10000 page 100000",
                       "thermo_style custom step pe", "thermo_modify norm no"])


def new_lammps(logfile):
    return lammps(cmdargs=["-log", logfile, "-screen", "none", "-nocite"])


def sorted_by_id(lmp, f):
    nlocal = lmp.extract_global("nlocal")
    ids = np.array(lmp.numpy.extract_atom("id")[:nlocal])
    return np.asarray(f)[np.argsort(ids)]


def reference(scene, args, periodic, logfile):
    lmp = new_lammps(logfile)
    setup(lmp, scene, args, periodic)
    if periodic:    # the pair needs a kspace for a periodic box; the reference ignores it
        lmp.command("kspace_style pppm/sph/astro/gravity 1e-3")
    lmp.commands_list(["compute ref all sph/astro/gravity/direct", "variable e equal c_ref",
                       "thermo_style custom step v_e", "run 0"])
    nlocal = lmp.extract_global("nlocal")
    f = sorted_by_id(lmp, lmp.numpy.extract_compute("ref", LMP_STYLE_ATOM,
                                                    LMP_TYPE_ARRAY)[:nlocal, :3])
    e = lmp.extract_variable("e")
    lmp.close()
    return f, e


def evaluate(scene, args, periodic, kspace, logfile):
    """forces and energy of one solver setting, and its wall time per force evaluation"""
    lmp = new_lammps(logfile)
    setup(lmp, scene, args, periodic)
    if kspace:
        lmp.command(f"kspace_style {kspace}")
    lmp.command("run 0")
    if kspace and " relative " in f" {kspace} ":    # (it needs the accelerations once)
        lmp.command("run 0")
    nlocal = lmp.extract_global("nlocal")
    f = sorted_by_id(lmp, np.array(lmp.numpy.extract_atom("f")[:nlocal]))
    e = lmp.get_thermo("pe")
    t0 = time.process_time()
    lmp.command(f"run {args.steps} pre no post no")
    per_step = (time.process_time() - t0) / args.steps
    lmp.close()
    log = open(logfile).read()
    grid = re.findall(r"grid = (\d+ \d+ \d+)", log)
    return f, e, per_step, (grid[-1] if grid else "")


def settings(scene, args, periodic):
    """(label, kspace_style arguments or None for direct summation)"""
    out = []
    if periodic:
        return [(f"pppm {a:g}", f"pppm/sph/astro/gravity {a:g}") for a in args.accuracies]
    if scene != "cloud":    # (the cloud's pair cutoff, 3, is that of MSM's split)
        out.append(("direct", None))
    out += [(f"tree geometric {t:g}", f"tree/sph/astro/gravity geometric {t:g}")
            for t in args.thetas]
    out += [(f"tree relative {a:g}", f"tree/sph/astro/gravity relative {a:g}")
            for a in args.alphas]
    out += [(f"tree {t}", f"tree/sph/astro/gravity {t}") for t in args.tree]
    if scene == "cloud":
        out += [(f"msm {a:g}", f"msm/sph/astro/gravity {a:g}") for a in args.accuracies]
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--scenes", default="cloud,evrard,plummer")
    p.add_argument("--n", type=int, default=4000, help="particles of the cloud")
    p.add_argument("--evrard-n", type=int, default=24, help="Evrard: fcc cells across")
    p.add_argument("--plummer-n", type=int, default=20000)
    p.add_argument("--thetas", default="0.3,0.4,0.5,0.6,0.7")
    p.add_argument("--alphas", default="0.0005,0.001,0.002,0.004")
    p.add_argument("--accuracies", default="1e-3,1e-4,1e-5")
    p.add_argument("--tree", action="append", default=[], metavar="ARGS",
                   help="further tree settings, e.g. 'relative 1e-5 leaf 8 group 64' "
                        "(repeatable)")
    p.add_argument("--steps", type=int, default=5)
    p.add_argument("--outdir", default=os.path.join(ROOT, "build", "output", "gravity_accuracy"))
    args = p.parse_args()
    args.thetas = [float(v) for v in args.thetas.split(",") if v]
    args.alphas = [float(v) for v in args.alphas.split(",") if v]
    args.accuracies = [float(v) for v in args.accuracies.split(",") if v]
    os.makedirs(args.outdir, exist_ok=True)
    header = ("| scene | N | solver | per-particle RMS | 99th pct | global RMS | energy | "
              "grid | CPU ms per evaluation |\n|---|---|---|---|---|---|---|---|---|")
    table = [header]
    curves = {}
    for scene in args.scenes.split(","):
        for periodic in ([False, True] if scene == "cloud" else [False]):
            name = scene + (" periodic" if periodic else "")
            tag = name.replace(" ", "_")
            fref, eref = reference(scene, args, periodic,
                                   os.path.join(args.outdir, f"log.{tag}.ref"))
            fnorm = np.linalg.norm(fref, axis=1)
            for label, kspace in settings(scene, args, periodic):
                log = os.path.join(args.outdir, f"log.{tag}.{label.replace(' ', '_')}")
                f, e, dt, grid = evaluate(scene, args, periodic, kspace, log)
                d = np.linalg.norm(f - fref, axis=1)
                rel = d / np.maximum(fnorm, 1e-300)
                row = (name, len(f), label, np.sqrt(np.mean(rel**2)), np.percentile(rel, 99),
                       np.sqrt(np.sum(d**2) / np.sum(fnorm**2)), abs(e - eref) / abs(eref),
                       grid, dt * 1e3)
                curves.setdefault(name, []).append(row)
                table.append("| {} | {} | {} | {:.2e} | {:.2e} | {:.2e} | {:.1e} | {} | {:.1f} |"
                             .format(*row))
                print(table[-1], flush=True)
    text = "\n".join(table) + "\n"
    with open(os.path.join(args.outdir, "table.md"), "w") as fh:
        fh.write("one MPI rank; reference: compute sph/astro/gravity/direct\n\n" + text)
    print(text)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(curves), figsize=(5 * len(curves), 4), squeeze=False)
    for ax, (name, rows) in zip(axes[0], curves.items()):
        for family in ("direct", "tree geometric", "tree relative", "msm", "pppm"):
            # (the --tree settings are drawn as points of the relative family's colour)
            sel = [r for r in rows if r[2].startswith(family)]
            if sel:
                ax.loglog([max(r[8], 1e-3) for r in sel], [max(r[3], 1e-16) for r in sel], "o-",
                          label=family)
        ax.set_title(f"{name}, N = {rows[0][1]}")
        ax.set_xlabel("CPU ms per force evaluation")
        ax.set_ylabel("per-particle RMS relative force error")
        ax.legend(fontsize=8)
    fig.tight_layout()
    png = os.path.join(args.outdir, "gravity_accuracy.png")
    fig.savefig(png, dpi=110)
    print(f"wrote {png} and table.md")


if __name__ == "__main__":
    main()
