#!/usr/bin/env python3
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
"""Sedov blast with global and with individual timesteps, side by side in one script.

Runs examples/sedov/in.sedov (background pressure 1e-6: the blast runs into gas whose own
timestep is long) three times at the same resolution: every particle at the smallest step
(``steps global``), individual steps with the timestep limiter (``steps individual``), and
individual steps without it (``limiter off``), all with the same Courant signal speed
(``--vsig``, fix sph/astro vsig; viscosity by default, as the fix) and the same deposit of
the blast energy (``--deposit``: in.sedov's kernel weights by default, or equal shares in the
central particle and its 12 nearest). Prints for each the shock
radius offset (binned density peak) and L1(rho) against the self-similar solution, the peak
density, the energy error, the particle-updates, the LAMMPS steps and the wall time; then the
individual runs' differences from the global one.

Usage (from anywhere; after source build/env.sh: build/venv's python3 and lmp on the PATH)::

    python3 examples/sedov/compare_steps.py [--n 16] [--np 1] [--limiter N]
        [--kicks pair|particle] [--vsig viscosity|pairs] [--deposit kernel|shell] [--outdir DIR]
        [--assert 'l1=0.02,rshock=0.02,nolimiter=0.1,updates=0.30']

``--assert`` fails (exit 1) unless: the limited individual run's L1(rho) and shock radius
differ from the global run's by at most ``l1`` and ``rshock`` (relative: |a-b|/|b|), the run
without the limiter goes visibly wrong: it misses the analytic shock radius by more than
``nolimiter`` (``--kicks particle``: the blast stalls in sleeping gas) or, with ``--kicks
pair``, also conserves energy worse than ``nolimiter`` or stops with an error (sleeping gas
next to the blast is pushed by its pairs but heated over its own long step), and the limited
run evaluates at most ``updates`` x the global run's particle-updates; ``energy`` (optional):
the limited individual run's relative total-energy error is at most that in magnitude;
``hot`` (optional): the blast energy went into at most that many particles.
"""

import argparse
import math
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
_DEPOSIT = re.compile(r"^Sedov: N = .* over (\d+) particles", re.M)


def variants(limiter, kicks, vsig):
    """global steps, individual steps with the limiter (None: the input's default), without;
    all three with the Courant signal speed vsig"""
    individual = ["-var", "steps", "individual", "-var", "kicks", kicks, "-var", "vsig", vsig]
    limited = list(individual)
    if limiter is not None:
        limited += ["-var", "limiter", str(limiter)]
    return [("global", ["-var", "steps", "global", "-var", "vsig", vsig]), ("individual", limited),
            ("no limiter", individual + ["-var", "limiter", "off"])]


def run(name, args, extra, may_fail=False):
    """one variant; may_fail: a run that stops with an error gives a row with its message"""
    work = os.path.join(args.outdir, name.replace(" ", "_"))
    os.makedirs(work, exist_ok=True)
    cmd = ["lmp", "-in", os.path.join(HERE, "in.sedov"), "-log", "log.lammps", "-screen",
           "none", "-var", "n", str(args.n), "-var", "out", "dump.sedov", "-var", "deposit",
           args.deposit] + extra
    if args.np > 1:
        cmd = ["mpirun", "--oversubscribe", "-np", str(args.np)] + cmd
    start = time.time()
    done = subprocess.run(cmd, cwd=work, check=not may_fail)
    wall = time.time() - start
    log_path = os.path.join(work, "log.lammps")
    if done.returncode != 0:
        with open(log_path, encoding="utf-8", errors="replace") as f:
            errors = [line.strip() for line in f if line.startswith("ERROR")]
        return {"name": name, "rshock": math.nan, "l1": math.nan, "peak": math.nan,
                "energy": math.inf, "updates": math.nan, "steps": 0, "wall": wall,
                "N": 0, "error": errors[-1] if errors else f"exit status {done.returncode}"}
    frame = read_last_frame(os.path.join(work, "dump.sedov"))
    res = sedov.sedov_errors(frame, frame.time if frame.time is not None else 0.1)
    log = parse_sph_log(log_path, loops="sum")
    with open(log_path, encoding="utf-8", errors="replace") as f:
        text = f.read()
    found = _UPDATES.findall(text)
    updates = float(found[-1]) if found else float(log["natoms"]) * log["steps"]
    hot = _DEPOSIT.findall(text)
    return {"name": name, "rshock": res["err_r_peak"], "l1": res["rho"],
            "peak": res["rho_peak"], "energy": log["energy"], "updates": updates,
            "steps": log["steps"], "wall": wall, "N": log["natoms"],
            "hot": float(hot[0]) if hot else math.nan}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=16, help="fcc cells per side (N = 4 n^3)")
    parser.add_argument("--np", type=int, default=1, help="MPI ranks")
    parser.add_argument("--limiter", type=int, default=None,
                        help="limiter levels of the individual run (default: the input's)")
    parser.add_argument("--kicks", choices=("particle", "pair"), default="pair",
                        help="fix sph/astro kicks of the individual runs (default pair, the "
                        "fix's default)")
    parser.add_argument("--vsig", choices=("viscosity", "pairs"), default="viscosity",
                        help="fix sph/astro vsig of all three runs (default viscosity, the "
                        "fix's default)")
    parser.add_argument("--deposit", choices=("kernel", "shell"), default="kernel",
                        help="in.sedov's deposit of the blast energy in all three runs "
                        "(default kernel, the input's)")
    parser.add_argument("--outdir", default="sedov_compare_steps")
    cli.add_assert_argument(parser, "fail (exit 1) unless l1, rshock, updates, energy <= "
                            "bound and nolimiter >= bound (see the docstring)")
    args = parser.parse_args(argv)
    rows = [run(name, args, extra, may_fail=name == "no limiter")
            for name, extra in variants(args.limiter, args.kicks, args.vsig)]
    print(f"Sedov, {rows[0]['N']} particles, {args.np} rank(s), t = 0.1, blast energy "
          f"deposited in {rows[0]['hot']:g} particles ({args.deposit})")
    print(f"{'steps':>11} {'R_s offset':>10} {'L1(rho)':>9} {'peak':>7} {'energy err':>11} "
          f"{'updates':>10} {'/particle':>9} {'LAMMPS steps':>12} {'wall s':>7}")
    for r in rows:
        print(f"{r['name']:>11} {100 * r['rshock']:+9.2f}% {r['l1']:9.4f} {r['peak']:7.3f} "
              f"{r['energy']:+11.3e} {r['updates']:10.4g} {r['updates'] / r['N'] if r['N'] else math.nan:9.1f} "
              f"{r['steps']:12d} {r['wall']:7.1f}")
        if "error" in r:
            print(f"{'':>11} stopped: {r['error']}")
    glob, ind, nolim = rows
    diff = {"l1": abs(ind["l1"] - glob["l1"]) / glob["l1"],
            "rshock": abs(ind["rshock"] - glob["rshock"]) / abs(glob["rshock"]),
            "updates": ind["updates"] / glob["updates"]}
    print(f"individual against global: L1(rho) {100 * diff['l1']:.2f} %, shock radius offset "
          f"{100 * diff['rshock']:.2f} % (relative), particle-updates x {diff['updates']:.3f}, "
          f"wall time x {ind['wall'] / glob['wall']:.3f}")
    print(f"without the limiter: shock radius {100 * nolim['rshock']:+.2f} % from the analytic "
          f"one, energy error {nolim['energy']:+.3e}"
          + (" (the run stopped with an error)" if "error" in nolim else ""))
    if args.bounds:
        # a run stopped by an error counts as gone wrong (inf); nan never passes
        # particle kicks: the blast stalls (R_s short); pair kicks: the sleeping gas is pushed
        # but not heated, and the energy goes wrong or u negative (a stopped run counts: inf)
        failure = abs(nolim["rshock"]) if args.kicks == "particle" else max(
            abs(nolim["rshock"]) if "error" not in nolim else 0.0, abs(nolim["energy"]))
        return cli.assert_bounds(args.bounds,
                                 {**diff, "nolimiter": failure, "energy": abs(ind["energy"]),
                                  "hot": rows[0]["hot"]},
                                 lower=("nolimiter",), error=parser.error)
    return 0


if __name__ == "__main__":
    sys.exit(main())
