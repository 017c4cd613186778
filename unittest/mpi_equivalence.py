#!/usr/bin/env python3
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
"""MPI equivalence: the same scene on 1, 2, 3 and 4 ranks must give the same particles.

Runs examples/sod/in.sod (short: t = 0.05; or another scene, --scene) with `mpirun -np N lmp`, reads the final dumps
and compares every field by atom ID with the 1-rank run. Summation order differs between
decompositions, so the runs agree to round-off growth, not bit for bit: the bound is a
relative difference of 1e-9 of each field's scale.
With --repeat the last rank count runs a second time and must give the same numbers bit for
bit (a solver whose results depend on the decomposition, as the gravity tree's do within its
force error, still repeats itself exactly).
Usage: mpi_equivalence.py WORKDIR [--ranks 1,2,3,4] [--tol 1e-9] [--scene sod | --input FILE]
       [--repeat] [lmp -var arguments ...]
"""
import argparse
import os
import subprocess
import sys

import numpy as np

from sphastro.dump import read_last_frame

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))


def run(workdir, np_ranks, extra, scene="sod", tag=""):
    out = os.path.join(workdir, f"dump.np{np_ranks}{tag}")
    # a scene of examples/ or an input file (a path)
    script = scene if os.sep in scene else os.path.join(ROOT, "examples", scene, "in." + scene)
    cmd = ["mpirun", "-np", str(np_ranks), "lmp", "-in", script, "-log",
           os.path.join(workdir, f"log.np{np_ranks}{tag}"), "-screen", "none",
           "-var", "out", out] + extra
    subprocess.run(cmd, check=True, cwd=workdir)
    frame = read_last_frame(out)
    order = np.argsort(frame.columns["id"])
    return frame, {k: np.asarray(v)[order] for k, v in frame.columns.items()}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("workdir")
    parser.add_argument("--ranks", default="1,2,3,4")
    parser.add_argument("--tol", type=float, default=1e-9)
    parser.add_argument("--scene", default="sod", help="examples/SCENE/in.SCENE (its dump has "
                        "x y z vx vy vz rho pressure u)")
    parser.add_argument("--input", help="an input file instead of a scene (its dump has the same "
                        "columns)")
    parser.add_argument("--repeat", action="store_true",
                        help="the last rank count again: bit for bit the same")
    args, extra = parser.parse_known_args()
    if not extra:
        extra = ["-var", "nx", "32", "-var", "ny", "4", "-var", "tend", "0.05"]
    os.makedirs(args.workdir, exist_ok=True)
    if args.input:
        args.scene = os.path.abspath(args.input)
    ranks = [int(r) for r in args.ranks.split(",")]
    ref_frame, ref = run(args.workdir, ranks[0], extra, args.scene)
    fields = ["x", "y", "z", "vx", "vy", "vz", "rho", "pressure", "u"]
    failed = False
    for n in ranks[1:]:
        frame, cols = run(args.workdir, n, extra, args.scene)
        if frame.timestep != ref_frame.timestep or not np.array_equal(cols["id"], ref["id"]):
            print(f"np {n}: different step ({frame.timestep} vs {ref_frame.timestep}) or atoms")
            failed = True
            continue
        worst = 0.0
        for f in fields:
            scale = max(np.max(np.abs(ref[f])), 1e-300)
            diff = np.max(np.abs(cols[f] - ref[f])) / scale
            worst = max(worst, diff)
            status = "ok" if diff <= args.tol else "FAILED"
            if diff > args.tol:
                failed = True
            print(f"np {n} vs np {ranks[0]}: max relative difference of {f:8s} = {diff:.3e} {status}")
        print(f"np {n}: step {frame.timestep}, worst relative difference {worst:.3e}")
    if args.repeat:
        n = ranks[-1]
        _, first = run(args.workdir, n, extra, args.scene) if n == ranks[0] else (None, cols)
        _, again = run(args.workdir, n, extra, args.scene, ".repeat")
        same = all(np.array_equal(again[f], first[f]) for f in fields)
        failed = failed or not same
        print(f"np {n} run again: " + ("bit for bit the same" if same else "DIFFERENT (FAILED)"))
    print("MPI equivalence " + ("FAILED" if failed else "passed"))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
