#!/usr/bin/env python3
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
"""The tree's cost against N: wall time of one full gravity evaluation from 1e4 to 1e6 particles.

A Plummer sphere (a = M = 1, G = 1, cut at 10 a; Plummer 1911, sampled as Aarseth, Henon &
Wielen 1974) or a uniform ball (--scene cloud, radius 1) of N particles with softening length
0.01 (pair_style sph/astro/gravity ... h 0.01), kspace_style tree/sph/astro/gravity with the
given criterion (default relative 0.002), on --ranks MPI ranks: after two evaluations (the
relative criterion needs the first's accelerations) `run STEPS pre no post no` times STEPS full
evaluations (the tree's moments recomputed at each, its structure that of the set-up). Printed
per N: seconds per evaluation, particle-evaluations per second, LAMMPS' memory per rank
(including the tree's), bytes per particle; then the exponent p of a least-squares fit
t ~ N^p, and the exponent N log N has over the same range, 1 + ln(ln N2 / ln N1) / ln(N2 / N1),
for comparison (p below it: no faster than N log N). Written to build/output/gravity_scaling/.
Usage: python3 tools/gravity_scaling.py [--n 1e4,3e4,1e5,3e5,1e6] [--ranks 2] [--steps 5]
       [--scene plummer|cloud] [--opening "relative 0.002"] [--outdir DIR]
Needs lmp and the plugin: source build/env.sh first.
"""
import argparse
import os
import re
import subprocess

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

INPUT = """units lj
atom_style atomic
atom_modify map array sort 0 0.0
boundary m m m
read_data ${data}
pair_style sph/astro/gravity 1000.0 h 0.01
pair_coeff * *
kspace_style tree/sph/astro/gravity ${opening}
neighbor 0.001 bin
neigh_modify every 1000 delay 0 check no
thermo_style custom step pe
run 0 post no
run 0 post no
run ${steps} pre no post yes
"""


def positions(scene, n, seed=4711):
    rng = np.random.default_rng(seed)
    out = np.empty((0, 3))
    while len(out) < n:
        if scene == "plummer":
            r = 1.0 / np.sqrt(rng.uniform(0.0, 1.0, n) ** (-2.0 / 3.0) - 1.0)
            r = r[r < 10.0]
            cos_t = rng.uniform(-1.0, 1.0, r.size)
            phi = rng.uniform(0.0, 2.0 * np.pi, r.size)
            sin_t = np.sqrt(1.0 - cos_t**2)
            p = np.column_stack([r * sin_t * np.cos(phi), r * sin_t * np.sin(phi), r * cos_t])
        else:
            p = rng.uniform(-1.0, 1.0, (n, 3))
            p = p[np.sum(p**2, axis=1) < 1.0]
        out = np.vstack([out, p])
    return out[:n]


def write_data(path, pos):
    n = len(pos)
    ext = np.abs(pos).max() * 1.01
    with open(path, "w") as fh:
        fh.write(f"Plummer or uniform sphere\n\n{n} atoms\n1 atom types\n\n")
        for d in "xyz":
            fh.write(f"{-ext} {ext} {d}lo {d}hi\n")
        fh.write(f"\nMasses\n\n1 {1.0 / n!r}\n\nAtoms # atomic\n\n")
        ids = np.arange(1, n + 1)
        np.savetxt(fh, np.column_stack([ids, np.ones(n), pos]), fmt="%d %d %.16g %.16g %.16g")


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--n", default="1e4,3e4,1e5,3e5,1e6")
    p.add_argument("--ranks", type=int, default=2)
    p.add_argument("--steps", type=int, default=5)
    p.add_argument("--scene", default="plummer", choices=["plummer", "cloud"])
    p.add_argument("--opening", default="relative 0.002")
    p.add_argument("--outdir", default=os.path.join(ROOT, "build", "output", "gravity_scaling"))
    args = p.parse_args()
    os.makedirs(args.outdir, exist_ok=True)
    infile = os.path.join(args.outdir, "in.scaling")
    with open(infile, "w") as fh:
        fh.write(INPUT)
    rows = []
    for n in [int(float(v)) for v in args.n.split(",")]:
        data = os.path.join(args.outdir, f"data.{args.scene}.{n}")
        if not os.path.exists(data):
            write_data(data, positions(args.scene, n))
        log = os.path.join(args.outdir, f"log.{args.scene}.{n}")
        subprocess.run(["mpirun", "-np", str(args.ranks), "lmp", "-in", infile, "-log", log,
                        "-screen", "none", "-var", "data", data, "-var", "opening",
                        args.opening, "-var", "steps", str(args.steps)], check=True)
        text = open(log).read()
        loop = float(re.findall(r"Loop time of ([0-9.eE+-]+) on", text)[-1])
        mem = re.findall(r"Per MPI rank memory allocation \(min/avg/max\) = "
                         r"[0-9.]+ \| ([0-9.]+) \| [0-9.]+ Mbytes", text)
        per = loop / args.steps
        mem_rank = float(mem[-1]) if mem else float("nan")
        rows.append((n, per, n / per, mem_rank, mem_rank * args.ranks * 1048576.0 / n))
        print(f"N = {n:8d}: {per:8.3f} s per evaluation, {n / per:10.4g} particles/s, "
              f"{mem_rank:8.1f} MB per rank (LAMMPS' count), {rows[-1][4]:6.0f} B/particle",
              flush=True)
    ns = np.array([r[0] for r in rows], dtype=float)
    ts = np.array([r[1] for r in rows])
    slope = np.polyfit(np.log(ns), np.log(ts), 1)[0]
    nlogn = 1.0 + np.log(np.log(ns[-1]) / np.log(ns[0])) / np.log(ns[-1] / ns[0])
    lines = [f"{args.scene}, {args.ranks} MPI ranks, kspace_style tree/sph/astro/gravity "
             f"{args.opening}", "",
             "| N | s per evaluation | particle-evaluations per s | MB per rank | B per particle |",
             "|---|---|---|---|---|"]
    for n, per, rate, mem, bpp in rows:
        lines.append(f"| {n} | {per:.3f} | {rate:.4g} | {mem:.1f} | {bpp:.0f} |")
    lines += ["", f"fitted exponent p (t ~ N^p): {slope:.3f}; N log N over the same range: "
              f"{nlogn:.3f}; " + ("no faster than N log N" if slope <= nlogn + 0.02 else
                                  "FASTER than N log N")]
    text = "\n".join(lines) + "\n"
    print(text)
    with open(os.path.join(args.outdir, "table.md"), "w") as fh:
        fh.write(text)


if __name__ == "__main__":
    main()
