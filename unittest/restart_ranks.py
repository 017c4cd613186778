#!/usr/bin/env python3
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
"""Restart on the same and on other rank counts: a run continued from a restart file equals the
uninterrupted run.

Runs unittest/in.restart_ranks two ways: straight (2 x steps on the first rank count, writing a
restart file at step steps, where LAMMPS also re-neighbours) and continue (read_restart of that
file, the fixes defined again, steps more) on each rank count. With --exact the
continuation on the writer's rank count must equal the straight run bit for bit, the simulation
time included (the dump's TIME); on the others every field and the time must agree to
round-off: a relative
difference of --tol of the field's scale. (With variable h the package's neighbour lists of the
restart step serve the iterated h, where the uninterrupted run's served the predicted h of the
step before the iteration; when an h later outgrows one and not the other, the two runs add
the same pairs in another order.)
Usage: restart_ranks.py WORKDIR [--ranks 1,2,3,4] [--tol 1e-12] [--exact] [lmp -var arguments ...]
"""
import argparse
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
FIELDS = ["x", "y", "z", "vx", "vy", "vz", "u", "h"]


def lmp(workdir, ranks, mode, extra, out=None):
    cmd = ["mpirun", "--oversubscribe", "-np", str(ranks), "lmp", "-in",
           os.path.join(HERE, "in.restart_ranks"), "-log",
           os.path.join(workdir, f"log.{mode}.np{ranks}"), "-screen", "none",
           "-var", "mode", mode, "-var", "restart", os.path.join(workdir, "restart_ranks")]
    if out:
        cmd += ["-var", "out", out]
    subprocess.run(cmd + extra, check=True, cwd=workdir)


def read_dump(path):
    """the atoms sorted by ID, and the simulation time (the dump's TIME item, as written)"""
    with open(path) as f:
        lines = f.read().splitlines()
    start = next(k for k, line in enumerate(lines) if line.startswith("ITEM: ATOMS"))
    time = next(lines[k + 1].strip() for k, line in enumerate(lines)
                if line.startswith("ITEM: TIME"))
    data = np.loadtxt(lines[start + 1:], ndmin=2)
    return data[np.argsort(data[:, 0])], time


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("workdir")
    parser.add_argument("--ranks", default="1,2,3,4")
    parser.add_argument("--tol", type=float, default=1e-12)
    parser.add_argument("--exact", action="store_true",
                        help="bit for bit on the writer's rank count")
    args, extra = parser.parse_known_args()
    os.makedirs(args.workdir, exist_ok=True)
    ranks = [int(r) for r in args.ranks.split(",")]
    straight = os.path.join(args.workdir, "dump.straight")
    lmp(args.workdir, ranks[0], "straight", extra, straight)
    ref, time_ref = read_dump(straight)
    scale = np.maximum(np.abs(ref[:, 1:]).max(axis=0), 1e-300)
    failed = False
    for n in ranks:
        out = os.path.join(args.workdir, f"dump.continue.np{n}")
        lmp(args.workdir, n, "continue", extra, out)
        cont, time = read_dump(out)
        if not np.array_equal(cont[:, 0], ref[:, 0]):
            print(f"np {n}: other atoms than the straight run")
            failed = True
            continue
        diff = (np.abs(cont[:, 1:] - ref[:, 1:]) / scale).max(axis=0)
        worst = ", ".join(f"{f} {d:.1e}" for f, d in zip(FIELDS, diff))
        bound = 0.0 if (args.exact and n == ranks[0]) else args.tol
        # the simulation time: as written (17 digits) on the writer's rank count, else to round-off
        time_diff = abs(float(time) - float(time_ref)) / max(abs(float(time_ref)), 1e-300)
        time_ok = time == time_ref if bound == 0.0 else time_diff <= args.tol
        ok = bool(np.all(diff <= bound)) and time_ok
        failed |= not ok
        what = "bit for bit" if bound == 0.0 else f"within {bound:g}"
        print(f"np {n} continued from np {ranks[0]}: {'ok' if ok else 'FAILED'} ({what}; "
              f"largest relative differences {worst}; time {time} against {time_ref})")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
