#!/usr/bin/env python3
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
"""Sedov blast with global and with individual timesteps, side by side in one script.

Runs examples/sedov/in.sedov (background pressure 1e-6: the blast runs into gas whose own
timestep is long) three times at the same resolution: every particle at the smallest step
(``steps global``), individual steps with the timestep limiter (``steps individual``), and
individual steps without it (``limiter off``). Prints for each the shock radius offset (binned
density peak) and L1(rho) against the self-similar solution, the peak density, the energy
error, the particle-updates, the LAMMPS steps and the wall time; then the individual runs'
differences from the global one.

Usage (from anywhere; after source build/env.sh: build/venv's python3 and lmp on the PATH)::

    python3 examples/sedov/compare_steps.py [--n 16] [--np 1] [--outdir DIR]
        [--assert 'l1=0.02,rshock=0.02,nolimiter=0.1,updates=0.30']

``--assert`` fails (exit 1) unless: the limited individual run's L1(rho) and shock radius
differ from the global run's by at most ``l1`` and ``rshock`` (relative: |a-b|/|b|), the run
without the limiter misses the analytic shock radius or conserves energy worse than
``nolimiter`` (relative; it must go visibly wrong: the sleeping gas is pushed by the blast's
pairs but heated only over its own long step), and the limited run evaluates at most ``updates`` x the global run's
particle-updates.
"""

import argparse
import os
import re
import subprocess
import sys
import time

from sphastro import cli, sedov
from sphastro.dump import read_last_frame
from sphastro.runs import parse_sph_log

HERE = os.path.dirname(os.path.abspath(__file__))

_UPDATES = re.compile(r"fix sph/astro steps individual: (\S+) particle-updates")
VARIANTS = [("global", ["-var", "steps", "global"]),
            ("individual", ["-var", "steps", "individual"]),
            ("no limiter", ["-var", "steps", "individual", "-var", "limiter", "off"])]


def run(name, args, extra):
    work = os.path.join(args.outdir, name.replace(" ", "_"))
    os.makedirs(work, exist_ok=True)
    cmd = ["lmp", "-in", os.path.join(HERE, "in.sedov"), "-log", "log.lammps", "-screen",
           "none", "-var", "n", str(args.n), "-var", "out", "dump.sedov"] + extra
    if args.np > 1:
        cmd = ["mpirun", "--oversubscribe", "-np", str(args.np)] + cmd
    start = time.time()
    subprocess.run(cmd, cwd=work, check=True)
    wall = time.time() - start
    frame = read_last_frame(os.path.join(work, "dump.sedov"))
    res = sedov.sedov_errors(frame, frame.time if frame.time is not None else 0.1)
    log_path = os.path.join(work, "log.lammps")
    log = parse_sph_log(log_path, loops="sum")
    with open(log_path, encoding="utf-8", errors="replace") as f:
        found = _UPDATES.findall(f.read())
    updates = float(found[-1]) if found else float(log["natoms"]) * log["steps"]
    return {"name": name, "rshock": res["err_r_peak"], "l1": res["rho"],
            "peak": res["rho_peak"], "energy": log["energy"], "updates": updates,
            "steps": log["steps"], "wall": wall, "N": log["natoms"]}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=16, help="fcc cells per side (N = 4 n^3)")
    parser.add_argument("--np", type=int, default=1, help="MPI ranks")
    parser.add_argument("--outdir", default="sedov_compare_steps")
    cli.add_assert_argument(parser, "fail (exit 1) unless l1, rshock, updates <= bound and "
                            "nolimiter >= bound (see the docstring)")
    args = parser.parse_args(argv)
    rows = [run(name, args, extra) for name, extra in VARIANTS]
    print(f"Sedov, {rows[0]['N']} particles, {args.np} rank(s), t = 0.1")
    print(f"{'steps':>11} {'R_s offset':>10} {'L1(rho)':>9} {'peak':>7} {'energy err':>11} "
          f"{'updates':>10} {'/particle':>9} {'LAMMPS steps':>12} {'wall s':>7}")
    for r in rows:
        print(f"{r['name']:>11} {100 * r['rshock']:+9.2f}% {r['l1']:9.4f} {r['peak']:7.3f} "
              f"{r['energy']:+11.3e} {r['updates']:10.4g} {r['updates'] / r['N']:9.1f} "
              f"{r['steps']:12d} {r['wall']:7.1f}")
    glob, ind, nolim = rows
    diff = {"l1": abs(ind["l1"] - glob["l1"]) / glob["l1"],
            "rshock": abs(ind["rshock"] - glob["rshock"]) / abs(glob["rshock"]),
            "updates": ind["updates"] / glob["updates"]}
    print(f"individual against global: L1(rho) {100 * diff['l1']:.2f} %, shock radius offset "
          f"{100 * diff['rshock']:.2f} % (relative), particle-updates x {diff['updates']:.3f}, "
          f"wall time x {ind['wall'] / glob['wall']:.3f}")
    print(f"without the limiter: shock radius {100 * nolim['rshock']:+.2f} % from the analytic "
          f"one, energy error {nolim['energy']:+.3e}")
    if args.bounds:
        failure = max(abs(nolim["rshock"]), abs(nolim["energy"]))
        return cli.assert_bounds(args.bounds, {**diff, "nolimiter": failure},
                                 lower=("nolimiter",), error=parser.error)
    return 0


if __name__ == "__main__":
    sys.exit(main())
