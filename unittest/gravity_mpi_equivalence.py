#!/usr/bin/env python3
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
"""MPI equivalence of self-gravity: the uniform-sphere scene on 1, 2 and 3 ranks.

Runs examples/gravity_sphere/in.gravity_sphere (short: n = 8, no reference compute) with
`mpirun -np N lmp` for each solver (direct summation; pair + MSM; the tree; pair + PPPM or
the tree with PPPM with the ball in a periodic box), reads the dumps and
compares forces and per-atom potential energies particle by particle (matched by position)
with the 1-rank run. Summation
order differs between decompositions, so the bound is relative round-off (default 1e-10 of
each field's largest magnitude). An entry of --ranks is a rank count (LAMMPS chooses the
processor grid) or a grid PXxPYxPZ (`processors PX PY PZ`, PX*PY*PZ ranks).
Usage: gravity_mpi_equivalence.py WORKDIR [--ranks 1,2,3,3x1x1] [--tol 1e-10]
       [--solvers direct,msm,pppm,tree,treepm] [lmp -var arguments ...]
"""
import argparse
import os
import subprocess
import sys

import numpy as np

from sphastro.dump import read_last_frame

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))


def run(workdir, ranks, solver, extra=()):
    """ranks: a rank count ("3") or a processor grid ("3x1x1")"""
    grid = ranks.split("x")
    nranks = int(np.prod([int(g) for g in grid]))
    pgrid = " ".join(grid) if len(grid) == 3 else "* * *"
    out = os.path.join(workdir, f"dump.{solver}.np{ranks}")
    cmd = ["mpirun", "-np", str(nranks), "lmp", "-in",
           os.path.join(ROOT, "examples", "gravity_sphere", "in.gravity_sphere"),
           "-log", os.path.join(workdir, f"log.{solver}.np{ranks}"), "-screen", "none",
           "-var", "n", "8", "-var", "ref", "no", "-var", "solver", solver, "-var", "out", out,
           "-var", "pgrid", pgrid] + list(extra)
    subprocess.run(cmd, check=True, cwd=workdir)
    cols = read_last_frame(out).columns
    # create_atoms numbers the lattice sites per rank, so IDs differ between decompositions:
    # match the particles by position (lattice sites, run 0: they do not move)
    key = [np.round(np.asarray(cols[c]), 9) for c in ("z", "y", "x")]
    order = np.lexsort(key)
    return {k: np.asarray(v)[order] for k, v in cols.items()}


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("workdir")
    p.add_argument("--ranks", default="1,2,3")
    p.add_argument("--tol", type=float, default=1e-10)
    p.add_argument("--solvers", default="direct,msm")
    args, extra = p.parse_known_args()
    args.workdir = os.path.abspath(args.workdir)
    os.makedirs(args.workdir, exist_ok=True)
    ranks = args.ranks.split(",")
    failed = False
    for solver in args.solvers.split(","):
        ref = run(args.workdir, ranks[0], solver, extra)
        for n in ranks[1:]:
            cols = run(args.workdir, n, solver, extra)
            if not all(np.allclose(cols[c], ref[c], rtol=0, atol=1e-12) for c in "xyz"):
                print(f"{solver} np {n}: different particle positions")
                failed = True
                continue
            for f in ("fx", "fy", "fz", "c_pe"):
                diff = np.max(np.abs(cols[f] - ref[f])) / max(np.max(np.abs(ref[f])), 1e-300)
                ok = diff <= args.tol
                failed |= not ok
                print(f"{solver} np {n} vs np {ranks[0]}: max relative difference of {f:5s} = "
                      f"{diff:.3e} {'ok' if ok else 'FAILED'}")
    print("gravity MPI equivalence " + ("FAILED" if failed else "passed"))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
