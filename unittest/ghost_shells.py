#!/usr/bin/env python3
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
"""Ghost shells: ghosts narrow must give the particles of ghosts full, with fewer ghosts.

Runs examples/SCENE/in.SCENE with `-var ghosts full` and `-var ghosts narrow` on each rank
count and compares the final dumps field by field by atom ID. The narrow shells hold every
pair inside a kernel support, so each density and force sums the same pairs in the same order:
the dumps must agree bit for bit (--tol 0) when both runs built their neighbour lists at the
same steps; a shell made anew is a reneighbouring the full run does not make, after which the
pairs are summed in another order, so then the dumps must agree to --tol-rebuilt (round-off;
a pair missing from a shell moves a density by far more). The mean ghosts per rank (LAMMPS'
Nghost at the end of the run) must fall to at most --max-ratio of the full shell's, so a shell
that never narrows fails; with --min-remakes N the narrow run must also have made its shells
anew within the run at least N times because an h neared its shell (fix sph/astro/h's
end-of-run line).
Usage: ghost_shells.py WORKDIR [--ranks 1,2] [--scene sedov] [--tol 0] [--tol-rebuilt 1e-12]
       [--max-ratio 0.8] [--min-remakes 0] [lmp -var arguments ...]
"""
import argparse
import os
import re
import subprocess
import sys

import numpy as np

from sphastro.dump import read_last_frame

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))


def run(workdir, scene, ranks, ghosts, extra):
    tag = f"np{ranks}_{ghosts}"
    out = os.path.join(workdir, "dump." + tag)
    log = os.path.join(workdir, "log." + tag)
    cmd = ["mpirun", "-np", str(ranks), "lmp", "-in",
           os.path.join(ROOT, "examples", scene, "in." + scene), "-log", log,
           "-screen", "none", "-var", "out", out, "-var", "ghosts", ghosts] + extra
    subprocess.run(cmd, check=True, cwd=workdir)
    frame = read_last_frame(out)
    order = np.argsort(frame.columns["id"])
    cols = {k: np.asarray(v)[order] for k, v in frame.columns.items()}
    text = open(log).read()
    nghost = [float(m) for m in re.findall(r"^Nghost:\s+(\S+) ave", text, re.M)]
    shells = re.findall(r"^fix sph/astro/h ghosts narrow: .*$", text, re.M)
    builds = sum(int(m) for m in re.findall(r"^Neighbor list builds = (\d+)", text, re.M))
    return frame, cols, nghost[-1], shells[-1] if shells else "", builds


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("workdir")
    parser.add_argument("--ranks", default="1,2")
    parser.add_argument("--scene", default="sedov")
    parser.add_argument("--tol", type=float, default=0.0,
                        help="largest relative difference of a field (0: bit for bit)")
    parser.add_argument("--tol-rebuilt", type=float, default=1e-12,
                        help="the same when the narrow run built its neighbour lists at other "
                        "steps than the full run (its shells made anew)")
    parser.add_argument("--max-ratio", type=float, default=0.8,
                        help="largest ratio of the narrow shells' ghosts to the full shell's")
    parser.add_argument("--min-remakes", type=int, default=0,
                        help="fewest shells made anew because an h neared them (narrow run)")
    args, extra = parser.parse_known_args()
    os.makedirs(args.workdir, exist_ok=True)
    failed = False
    for ranks in [int(r) for r in args.ranks.split(",")]:
        ref_frame, ref, ref_ghosts, _, ref_builds = run(args.workdir, args.scene, ranks,
                                                         "full", extra)
        frame, cols, ghosts, shells, builds = run(args.workdir, args.scene, ranks, "narrow",
                                                  extra)
        tol = args.tol if builds == ref_builds else max(args.tol, args.tol_rebuilt)
        if frame.timestep != ref_frame.timestep or not np.array_equal(cols["id"], ref["id"]):
            print(f"np {ranks}: different step ({frame.timestep} vs {ref_frame.timestep}) "
                  "or atoms: FAILED")
            failed = True
            continue
        worst = 0.0
        for name, values in ref.items():
            if name == "id" or values.dtype.kind not in "fi":
                continue
            scale = max(float(np.max(np.abs(values))), 1e-300)
            worst = max(worst, float(np.max(np.abs(cols[name] - values))) / scale)
        ratio = ghosts / ref_ghosts
        found = re.search(r"(\d+) reneighbourings asked for by the shells", shells)
        remakes = int(found.group(1)) if found else -1
        ok = worst <= tol and ratio <= args.max_ratio and remakes >= args.min_remakes
        failed = failed or not ok
        print(f"np {ranks}: worst relative difference {worst:.3e} (bound {tol:g}; neighbour "
              f"list builds {builds} narrow, {ref_builds} full); ghosts "
              f"per rank {ghosts:.0f} narrow against {ref_ghosts:.0f} full = {ratio:.3f} "
              f"(bound {args.max_ratio:g}); {remakes} shells made anew (at least "
              f"{args.min_remakes}): {'ok' if ok else 'FAILED'}")
        print(f"  {shells}")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
