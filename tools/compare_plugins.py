#!/usr/bin/env python3
# SPH-ASTRO - astrophysical SPH for LAMMPS
# This software is distributed under the GNU General Public License version 2 (the same
# licence as LAMMPS); see the LICENSE file.
"""Time two builds of the plugin on the same scenes, interleaved, in one run.

Usage (from the repository root, after ``source build/env.sh``)::

    python3 tools/compare_plugins.py OLD_PLUGIN_DIR NEW_PLUGIN_DIR [--repeat 3]
        [--scenes benchmark,sod,sodi,sedov16,sod_signal_cd] [--np 1] [--outdir DIR]

Each plugin directory holds a ``sphastroplugin.so`` (e.g. build/plugins of an older
checkout). Every scene runs ``--repeat`` times with each plugin, alternating A, B, A, B, ...
so that both see the same machine state (these machines' speed drifts within a day). Prints
per scene the fastest of the runs (LAMMPS' ``Loop time`` and the wall time) of each build,
their ratio B/A, the ratio of the medians, and the pair share of the loop; the minimum is the
estimate least disturbed by other work on the machine. The numbers belong together only as
ratios.
"""

import argparse
import os
import re
import statistics
import subprocess
import sys
import time

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir))

SCENES = {
    # uniform periodic box, fixed h, classic viscosity: the pair loop alone
    "benchmark": ("examples/benchmark/in.benchmark", ["-var", "ncell", "18", "-var", "steps", "100"]),
    # the flagship: Sod, variable h (iterate), M4, classic viscosity
    "sod": ("examples/sod/in.sod", []),
    # the same with individual timesteps (two bins: most particles active at most steps)
    "sodi": ("examples/sod/in.sod", ["-var", "steps", "individual"]),
    # Sod with the signal viscosity, the Cullen-Dehnen switch and conductivity
    "sod_signal_cd": ("examples/sod/in.sod", ["-var", "visc", "signal", "-var", "switch", "cd",
                                              "-var", "cond", "1.0"]),
    # Sod with fixed h (mean h_ij kernels)
    "sod_fixed_h": ("examples/sod/in.sod", ["-var", "hmode", "fixed", "-var", "hfact", "1.5"]),
    # Sedov blast, 16 384 particles, variable h over a wide range (ghost cutoff widened)
    "sedov16": ("examples/sedov/in.sedov", ["-var", "n", "16"]),
    # the same with individual timesteps (fix sph/astro steps individual), particle kicks
    "sedov16i": ("examples/sedov/in.sedov", ["-var", "n", "16", "-var", "steps", "individual",
                                             "-var", "kicks", "particle"]),
    # the same with pair kicks (fix sph/astro kicks pair)
    "sedov16ik": ("examples/sedov/in.sedov", ["-var", "n", "16", "-var", "steps", "individual",
                                              "-var", "kicks", "pair"]),
    # Sedov, 42 592 particles, individual timesteps with particle and with pair kicks
    "sedov22i": ("examples/sedov/in.sedov", ["-var", "n", "22", "-var", "steps", "individual",
                                             "-var", "kicks", "particle"]),
    "sedov22ik": ("examples/sedov/in.sedov", ["-var", "n", "22", "-var", "steps", "individual",
                                              "-var", "kicks", "pair"]),
    # Sedov, 171 500 particles, individual timesteps with pair kicks
    "sedov35ik": ("examples/sedov/in.sedov", ["-var", "n", "35", "-var", "steps", "individual",
                                              "-var", "kicks", "pair"]),
    # Evrard collapse, 3 604 particles to t 0.8: direct-summation self-gravity with zeta terms
    "evrard12": ("examples/evrard/in.evrard", ["-var", "n", "12", "-var", "tend", "0.8"]),
    # the same with individual timesteps (pair kicks)
    "evrard12i": ("examples/evrard/in.evrard", ["-var", "n", "12", "-var", "tend", "0.8",
                                                "-var", "steps", "individual", "-var", "kicks",
                                                "pair"]),
    # the two with MSM's long range (the zeta sums and the short range from the neighbour list)
    "evrard12m": ("examples/evrard/in.evrard", ["-var", "n", "12", "-var", "tend", "0.8",
                                                "-var", "gravity", "msm"]),
    "evrard12mi": ("examples/evrard/in.evrard", ["-var", "n", "12", "-var", "tend", "0.8",
                                                 "-var", "gravity", "msm", "-var", "steps",
                                                 "individual", "-var", "kicks", "pair"]),
}

_LOOP = re.compile(r"^Loop time of (\S+) on", re.M)
_PAIR = re.compile(r"^Pair\s*\|.*\|\s*(\S+)\s*$", re.M)


def run(scene, plugin_dir, np, outdir, tag):
    path, args = SCENES[scene]
    work = os.path.join(outdir, f"{scene}_{tag}")
    os.makedirs(work, exist_ok=True)
    env = dict(os.environ, LAMMPS_PLUGIN_PATH=plugin_dir)
    cmd = ["mpirun", "-np", str(np), "lmp", "-in", os.path.join(ROOT, path), "-log", "log.lammps",
           "-screen", "none"] + args
    start = time.time()
    subprocess.run(cmd, cwd=work, env=env, check=True, stdout=subprocess.DEVNULL)
    wall = time.time() - start
    log = open(os.path.join(work, "log.lammps")).read()
    loops = [float(x) for x in _LOOP.findall(log)]
    pairs = [float(x) for x in _PAIR.findall(log)]
    return sum(loops), wall, (statistics.mean(pairs) if pairs else float("nan"))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--scenes", default="benchmark,sod,sod_signal_cd,sod_fixed_h,sedov16")
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--outdir", default=os.path.join(ROOT, "build", "output", "compare_plugins"))
    a = ap.parse_args()
    for d in (a.old, a.new):
        if not os.path.exists(os.path.join(d, "sphastroplugin.so")):
            sys.exit(f"compare_plugins: no sphastroplugin.so in {d}")
    print(f"A = {a.old}\nB = {a.new}\n{a.repeat} runs each, interleaved, {a.np} MPI rank(s)")
    print(f"{'scene':<15} {'loop A s':>9} {'loop B s':>9} {'B/A':>6} {'wall A s':>9} "
          f"{'wall B s':>9} {'B/A':>6} {'median B/A':>10} {'pair% A':>8} {'pair% B':>8}")
    for scene in a.scenes.split(","):
        res = {"A": [], "B": []}
        for k in range(a.repeat):
            for tag, d in (("A", a.old), ("B", a.new)) if k % 2 == 0 else (("B", a.new), ("A", a.old)):
                res[tag].append(run(scene, os.path.abspath(d), a.np, a.outdir, tag))
        best = {t: [min(x[i] for x in res[t]) for i in range(2)] for t in res}
        med = {t: [statistics.median(x[i] for x in res[t]) for i in range(3)] for t in res}
        print(f"{scene:<15} {best['A'][0]:9.2f} {best['B'][0]:9.2f} "
              f"{best['B'][0] / best['A'][0]:6.3f} {best['A'][1]:9.2f} {best['B'][1]:9.2f} "
              f"{best['B'][1] / best['A'][1]:6.3f} {med['B'][0] / med['A'][0]:10.3f} "
              f"{med['A'][2]:8.1f} {med['B'][2]:8.1f}", flush=True)


if __name__ == "__main__":
    main()
