#!/usr/bin/env python3
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
"""Cost of SPH-ASTRO on a uniform box and on astrophysical scenes, side by side in one script
(and SWIFT's Sedov runs, when a SWIFT build is given), as a table.

Usage (from the repository root; ``source build/env.sh`` first or it is sourced for you)::

    python3 tools/benchmark_scenes.py [--np 2] [--rows box1e4,box1e5,...]
        [--swift-bin PATH --swift-dir DIR] [--outdir build/output/benchmark_scenes]
        [--individual-var NAME=VALUE ...]

Rows (``--rows``, default all): ``box1e4``, ``box1e5``, ``box1e6`` (examples/benchmark, a
uniform periodic box, fixed h and dt, 40/20/5 steps), ``box1e5i`` (the same box as the scenes
run: the h iteration with grad-h terms, skin 0.5 h), ``sedov16``, ``sedov22``, ``sedov35``
(examples/sedov to t = 0.1), ``noh24`` (examples/noh to t = 0.6), ``evrard`` (examples/evrard,
n 16, MSM gravity, to t = 0.8), ``evrard16d``, ``evrard16t``, ``evrard24d``, ``evrard24t``
(Evrard to t = 0.8 with direct summation or the tree), ``evrard24n`` and ``evrard24tm`` (n 24
to t = 0.1 without gravity and with the tree: the memory gravity adds), ``evrard40t3`` (n 40,
135 000 particles, the tree, to t = 3; only when asked for; ``evrard40t3b`` the same with
fix balance, ``-var balance yes``), the same scenes with individual timesteps (``sedov16i``,
``sedov22i``, ``sedov35i``, ``noh24i``, ``evrardi``: ``-var steps individual`` with the inputs'
default pair kicks; their updates are the particle-updates fix sph/astro counts; for the
Evrard gravity rows ``evrard16di``, ``evrard16ti``, ``evrard24ti``, ``evrard24ni``,
``evrard24tmi``, ``evrard40t3i``, ``evrard40t3bi``); the same with
particle kicks, ``-var kicks particle``: ``sedov16ik``, ``sedov22ik``, ``sedov35ik``,
``noh24ik``, ``evrardik``; ``sedov16i1``, ``sedov22i1``, ``sedov35i1`` with ``-var limiter 1``
(the default is 2 levels with pair kicks); ``sedov16p``, ``sedov22p``,
``sedov35p`` and, with individual steps, ``sedov16ip``, ``sedov22ip``, ``sedov35ip``: the
Courant signal speed over the neighbours,
``-var vsig pairs``; ``sedov16c``, ``sedov22c``, ``sedov35c`` and, with individual steps,
``sedov16ic``, ``sedov22ic``, ``sedov35ic``: SWIFT's Courant criterion, ``-var vsig pairs
-var courant 0.4``); ``sedov16s``, ``sedov22s``, ``sedov35s`` and, with individual steps,
``sedov16is``, ``sedov22is``, ``sedov35is``: the blast energy in equal shares in the central
particle and its 12 nearest, ``-var deposit shell``), and ``swift35`` and ``swift56``:
SWIFT's Sedov at 42 875 and 175 616 particles (``--swift-bin``: the swift executable, built
with SPHENIX and the cubic spline as its repository describes; ``--swift-dir``: a folder
with ``swift_sedov.yml`` and ``swift_sedov_ic.py ``; 2 threads, ``--hydro --limiter``).
SWIFT is never part of this repository or of its tests; its rows are skipped when it is
absent. ``--individual-var kicks=particle`` runs the rows with individual steps with ``-var
kicks particle`` instead.

Each SPH-ASTRO row runs ``mpirun -np NP /usr/bin/time -f %M lmp ...`` and prints

* N, ranks, wall (s, the whole process), loop (s, LAMMPS' loop times summed over the input's
  runs), steps, updates (N x steps, or with individual steps the particles evaluated, millions);
* Mps/s/core: million particle-steps per second per core; us.core/ps: core-microseconds per
  particle-step; x box: that cost over the uniform box of ~1e5 particles (same kernel and
  hfact: about 58 neighbours inside the M4 support);
* half, rows, kern: entries per particle of the half list and of the gather rows of the h
  iteration, and neighbours inside the kernel support (the pair's end-of-run line);
  ghosts: ghost atoms per particle;
* RSS MB: peak resident memory summed over the ranks; B/part: (RSS - the ranks' RSS for a
  32-particle box on as many ranks, the fixed cost of the lmp processes) / N;
* grav/hyd: LAMMPS' Kspace seconds over its Pair seconds (the tree's gravity against the hydro
  for the same particle-updates); dE: the Evrard runs' relative energy error at the end.

SWIFT rows give wall, steps (its step count), updates (particle updates, summed over steps),
particle updates per second per thread, and its peak RSS. The table goes to stdout and to
OUTDIR/benchmark_scenes.txt; logs to OUTDIR/<row>/.
"""

import argparse
import os
import re
import shutil
import subprocess
import sys
import time

from sphastro.runs import lammps_environment, provenance

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir))

EX = os.path.join(ROOT, "examples")
SCENES = {
    "fixed": ("benchmark/in.benchmark", {"ncell": 2, "steps": 1}),
    "box1e4": ("benchmark/in.benchmark", {"ncell": 14, "steps": 40}),
    "box1e5": ("benchmark/in.benchmark", {"ncell": 29, "steps": 20}),
    "box1e6": ("benchmark/in.benchmark", {"ncell": 63, "steps": 5}),
    # the box as the scenes run it: h iteration and grad-h terms, Sedov's skin of 0.5 h
    "box1e5i": ("benchmark/in.benchmark", {"ncell": 29, "steps": 60, "hmode": "iterate",
                                           "skinfrac": 0.5}),
    "sedov16": ("sedov/in.sedov", {"n": 16, "thermoevery": 100}),
    "sedov22": ("sedov/in.sedov", {"n": 22, "thermoevery": 100}),
    "sedov35": ("sedov/in.sedov", {"n": 35, "thermoevery": 100}),
    "noh24": ("noh/in.noh", {"n": 24, "thermoevery": 100}),
    "evrard": ("evrard/in.evrard", {"n": 16, "gravity": "msm", "tend": 0.8,
                                    "thermoevery": 100}),
    # self-gravity solvers on the Evrard collapse to t = 0.8: direct summation (d), the tree
    # (t), the hydro without gravity (n, for the cost and memory gravity adds); + "i":
    # individual steps
    "evrard16d": ("evrard/in.evrard", {"n": 16, "gravity": "direct", "tend": 0.8,
                                       "thermoevery": 50}),
    "evrard16t": ("evrard/in.evrard", {"n": 16, "gravity": "tree", "tend": 0.8,
                                       "thermoevery": 50}),
    "evrard24d": ("evrard/in.evrard", {"n": 24, "gravity": "direct", "tend": 0.8,
                                       "thermoevery": 50}),
    "evrard24t": ("evrard/in.evrard", {"n": 24, "gravity": "tree", "tend": 0.8,
                                       "thermoevery": 50}),
    "evrard24n": ("evrard/in.evrard", {"n": 24, "gravity": "none", "tend": 0.1,
                                       "thermoevery": 50}),
    "evrard24tm": ("evrard/in.evrard", {"n": 24, "gravity": "tree", "tend": 0.1,
                                        "thermoevery": 50}),
    # the Evrard collapse with the tree at 135 000 particles to t = 3 (about 30 minutes); "b":
    # with fix balance, each particle weighted by its work (-var balance yes)
    "evrard40t3": ("evrard/in.evrard", {"n": 40, "gravity": "tree", "tend": 3.0,
                                        "thermoevery": 100}),
    "evrard40t3b": ("evrard/in.evrard", {"n": 40, "gravity": "tree", "tend": 3.0,
                                         "thermoevery": 100, "balance": "yes"}),
}
for _name in ("evrard16d", "evrard16t", "evrard24t", "evrard24n", "evrard24tm", "evrard40t3",
              "evrard40t3b"):
    _script, _vars = SCENES[_name]
    SCENES[_name + "i"] = (_script, dict(_vars, steps="individual"))
# the scenes with individual timesteps (fix sph/astro steps individual, its default pair kicks):
# row name + "i"; with particle kicks (kicks particle): + "ik"
for _name in ("sedov16", "sedov22", "sedov35", "noh24", "evrard"):
    _script, _vars = SCENES[_name]
    SCENES[_name + "i"] = (_script, dict(_vars, steps="individual"))
    SCENES[_name + "ik"] = (_script, dict(_vars, steps="individual", kicks="particle"))
# Sedov with individual steps and a limiter of 1 level (factor 2; the default is 2 levels,
# factor 4, SWIFT's): row name + "i1"
for _name in ("sedov16", "sedov22", "sedov35"):
    _script, _vars = SCENES[_name]
    SCENES[_name + "i1"] = (_script, dict(_vars, steps="individual", limiter=1))
# Sedov with the Courant signal speed taken over the neighbours (vsig pairs): global steps
# row name + "p", individual steps + "ip"; with SWIFT's Courant criterion (vsig pairs courant
# 0.4: dt = 0.4 h / max_j v_sig,ij, which is SWIFT's CFL 0.1 with its h = H / 1.825742 for the
# cubic spline of support H = 2h): global steps row name + "c", individual steps + "ic"
for _name in ("sedov16", "sedov22", "sedov35"):
    _script, _vars = SCENES[_name]
    SCENES[_name + "p"] = (_script, dict(_vars, vsig="pairs"))
    SCENES[_name + "ip"] = (_script, dict(_vars, vsig="pairs", steps="individual"))
    SCENES[_name + "c"] = (_script, dict(_vars, vsig="pairs", courant=0.4))
    SCENES[_name + "ic"] = (_script, dict(_vars, vsig="pairs", courant=0.4, steps="individual"))
# Sedov with E in equal shares in the central particle and its 12 nearest (deposit shell, as
# SWIFT's example puts it in its 15 central particles): global steps row name + "s",
# individual steps + "is"
for _name in ("sedov16", "sedov22", "sedov35"):
    _script, _vars = SCENES[_name]
    SCENES[_name + "s"] = (_script, dict(_vars, deposit="shell"))
    SCENES[_name + "is"] = (_script, dict(_vars, deposit="shell", steps="individual"))
SWIFT_ROWS = {"swift35": 35, "swift56": 56}
ORDER = ["box1e4", "box1e5", "box1e6", "box1e5i"] + [
    s + v for s in ("sedov16", "sedov22", "sedov35")
    for v in ("", "p", "i", "ik", "ip", "i1", "c", "ic", "s", "is")] + [
    "noh24", "noh24i", "noh24ik", "evrard", "evrardi", "evrardik", "evrard16d", "evrard16t",
    "evrard16ti", "evrard16di", "evrard24d", "evrard24t", "evrard24ti", "evrard24ni",
    "evrard24tmi", "swift35", "swift56"]
# (evrard40t3i and evrard40t3bi, about 30 minutes each on 2 ranks, only when asked for)

_LOOP = re.compile(r"^Loop time of (\S+) on (\d+) procs for (\d+) steps with (\d+) atoms", re.M)
# (with individual steps the line gives entries per row made, of reach rows: no half list)
_SEARCH = re.compile(r"pair sph/astro neighbour search: .*?per (?:particle|row made): (\S+) "
                     r"(half-list|reach-row) entries.*?, (\S+) gather-row entries[,;] "
                     r"(?:per particle: )?(\S+) neighbours inside the kernel support, (\S+) "
                     r"ghost atoms", re.S)
_RSS = re.compile(r"RSS_KB (\d+)")
_UPDATES = re.compile(r"fix sph/astro steps individual: (\S+) particle-updates")
_SECTION = re.compile(r"^(Pair|Kspace)\s+\|\s+\S+\s+\|\s+(\S+)", re.M)
_ENERGY = re.compile(r"relative energy error (\S+)")


def run_lammps(name, np_ranks, outdir, env, individual_vars=()):
    script, variables = SCENES[name]
    if variables.get("steps") == "individual":
        variables = dict(variables, **dict(individual_vars))
    work = os.path.join(outdir, name)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    # (each rank appends its line to one file: one short write each, so lines do not interleave
    # as the ranks' stderr can)
    cmd = ["mpirun", "--oversubscribe", "-np", str(np_ranks), "/usr/bin/time", "-a", "-o",
           "rss_kb.txt", "-f", "SPHASTRO_RSS_KB %M", "lmp", "-in", os.path.join(EX, script),
           "-log", "log.lammps", "-screen", "none"]
    if np_ranks == 1:
        cmd = cmd[4:]
    for key, value in variables.items():
        cmd += ["-var", key, str(value)]
    start = time.time()
    proc = subprocess.run(cmd, cwd=work, env=env, capture_output=True, text=True)
    wall = time.time() - start
    with open(os.path.join(work, "stderr.txt"), "w") as f:
        f.write(proc.stderr)
    if proc.returncode != 0:
        raise RuntimeError(f"{name}: lmp failed (exit {proc.returncode}); see {work}")
    with open(os.path.join(work, "log.lammps"), encoding="utf-8", errors="replace") as f:
        log = f.read()
    loops = _LOOP.findall(log)
    with open(os.path.join(work, "rss_kb.txt")) as f:
        rss = [int(v) for v in _RSS.findall(f.read())]
    row = {"name": name, "ranks": np_ranks, "wall": wall,
           "loop": sum(float(l[0]) for l in loops), "steps": sum(int(l[2]) for l in loops),
           "N": int(loops[-1][3]) if loops else 0, "rss_mb": sum(rss) / 1024.0}
    # particle updates: the atoms of each run times its steps (run 0 adds none)
    row["updates"] = sum(int(l[2]) * int(l[3]) for l in loops)
    individual = _UPDATES.findall(log)    # individual steps: the updates the fix counted
    if individual:
        row["updates"] = sum(float(v) for v in individual)
    # the seconds of LAMMPS' Pair and Kspace sections (the hydro and the gravity kspace)
    sections = dict(_SECTION.findall(log))
    row["pair_s"] = float(sections.get("Pair", "nan"))
    row["kspace_s"] = float(sections.get("Kspace", "nan"))
    energy = _ENERGY.findall(log)
    row["energy"] = float(energy[-1]) if energy else float("nan")
    found = _SEARCH.findall(log)
    row["half"], row["rows"], row["kern"], row["ghosts"] = [float("nan")] * 4
    if found:
        entries, kind, rows, kern, ghosts = found[-1]
        row["half"] = float(entries) if kind == "half-list" else float("nan")
        row["rows"], row["kern"], row["ghosts"] = float(rows), float(kern), float(ghosts)
    return row


def run_swift(name, n, outdir, swift_bin, swift_dir):
    work = os.path.abspath(os.path.join(outdir, name))
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    ic = os.path.join(work, f"sedov_n{n}.hdf5")
    subprocess.run([sys.executable, os.path.join(swift_dir, "swift_sedov_ic.py"), str(n), ic],
                   cwd=work, check=True, capture_output=True)
    cmd = ["/usr/bin/time", "-f", "SPHASTRO_RSS_KB %M", swift_bin, "--hydro", "--limiter",
           "--threads=2", "-P", f"InitialConditions:file_name:{ic}",
           os.path.join(swift_dir, "swift_sedov.yml")]
    start = time.time()
    proc = subprocess.run(cmd, cwd=work, capture_output=True, text=True)
    wall = time.time() - start
    with open(os.path.join(work, "stdout.txt"), "w") as f:
        f.write(proc.stdout)
    if proc.returncode != 0:
        raise RuntimeError(f"{name}: swift failed (exit {proc.returncode}); see {work}")
    steps = updates = 0
    with open(os.path.join(work, "timesteps.txt")) as f:
        for line in f:
            cols = line.split()
            if line.startswith("#") or len(cols) < 8:
                continue
            steps = int(cols[0])
            if steps > 0:
                updates += int(cols[7])
    rss = [int(v) for v in _RSS.findall(proc.stderr)]
    return {"name": name, "ranks": 2, "wall": wall, "loop": wall, "steps": steps, "N": n ** 3,
            "updates": updates, "rss_mb": sum(rss) / 1024.0, "half": float("nan"),
            "rows": float("nan"), "kern": float("nan"), "ghosts": float("nan"), "swift": True,
            "pair_s": float("nan"), "kspace_s": float("nan"), "energy": float("nan")}


def table(rows, fixed_mb):
    box = next((r for r in rows if r["name"] == "box1e5i"),
               next((r for r in rows if r["name"] == "box1e5"), None))
    box_cost = box["loop"] * box["ranks"] / box["updates"] * 1e6 if box else None
    head = (f"{'row':<9} {'N':>9} {'ranks':>5} {'wall s':>8} {'loop s':>8} {'steps':>6} "
            f"{'upd M':>7} {'Mps/s/c':>8} {'us.c/ps':>8} {'x box':>6} {'half':>6} {'rows':>6} "
            f"{'kern':>6} {'ghosts':>6} {'RSS MB':>8} {'B/part':>7} {'grav/hyd':>8} "
            f"{'dE':>9}")
    out = [head, "-" * len(head)]
    for r in rows:
        cost = r["loop"] * r["ranks"] / max(r["updates"], 1) * 1e6
        mps = r["updates"] / (r["loop"] * r["ranks"]) / 1e6
        ratio = f"{cost / box_cost:6.2f}" if box_cost and not r.get("swift") else f"{'':>6}"
        per = (r["rss_mb"] - fixed_mb) * 1048576.0 / r["N"] if not r.get(
            "swift") else r["rss_mb"] * 1048576.0 / r["N"]
        out.append(f"{r['name']:<9} {r['N']:>9} {r['ranks']:>5} {r['wall']:>8.1f} "
                   f"{r['loop']:>8.1f} {r['steps']:>6} {r['updates'] / 1e6:>7.2f} {mps:>8.3f} "
                   f"{cost:>8.2f} {ratio} {r['half']:>6.1f} {r['rows']:>6.1f} {r['kern']:>6.1f} "
                   f"{r['ghosts']:>6.2f} {r['rss_mb']:>8.1f} {per:>7.0f} "
                   f"{r['kspace_s'] / r['pair_s']:>8.2f} {r['energy']:>9.2e}")
    out.append(f"fixed cost of the lmp processes (32-particle box): {fixed_mb:.1f} MB; "
               "SWIFT rows: B/part is its whole RSS per particle, 'ranks' its threads; "
               "grav/hyd: LAMMPS' Kspace over Pair seconds (the gravity kspace against the "
               "hydro, for the same particle-updates); dE: the Evrard run's final relative "
               "energy error")
    return "\n".join(out)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--np", type=int, default=2, help="MPI ranks (default 2)")
    parser.add_argument("--rows", default=",".join(ORDER))
    parser.add_argument("--swift-bin", default=os.environ.get("SPH_ASTRO_SWIFT_BIN", ""))
    parser.add_argument("--swift-dir", default=os.environ.get("SPH_ASTRO_SWIFT_DIR", ""))
    parser.add_argument("--outdir", default=os.path.join(ROOT, "build", "output",
                                                         "benchmark_scenes"))
    parser.add_argument("--individual-var", action="append", default=[], metavar="NAME=VALUE",
                        help="-var NAME VALUE for the rows with individual steps (e.g. "
                             "kicks=particle); repeatable")
    args = parser.parse_args()
    individual_vars = []
    for item in args.individual_var:
        name, sep, value = item.partition("=")
        if not sep or not name:
            parser.error(f"--individual-var '{item}' is not NAME=VALUE")
        individual_vars.append((name, value))
    env = lammps_environment()
    os.makedirs(args.outdir, exist_ok=True)
    wanted = [r for r in args.rows.split(",") if r]
    for r in wanted:
        if r not in SCENES and r not in SWIFT_ROWS:
            parser.error(f"unknown row '{r}'; allowed: {', '.join(ORDER)}, evrard40t3i, "
                         "evrard40t3bi")
    fixed = run_lammps("fixed", args.np, args.outdir, env)
    rows = []
    for name in wanted:
        if name in SWIFT_ROWS:
            if not (os.path.isfile(args.swift_bin) and os.path.isdir(args.swift_dir)):
                print(f"{name}: skipped (no --swift-bin/--swift-dir)", flush=True)
                continue
            row = run_swift(name, SWIFT_ROWS[name], args.outdir, args.swift_bin, args.swift_dir)
        else:
            row = run_lammps(name, args.np, args.outdir, env, individual_vars)
        rows.append(row)
        print(f"{name}: N {row['N']}, wall {row['wall']:.1f} s, {row['steps']} steps, "
              f"RSS {row['rss_mb']:.0f} MB", flush=True)
    text = provenance(os.path.join(args.outdir, "fixed", "log.lammps")) + "\n" + table(
        rows, fixed["rss_mb"])
    print(text)
    with open(os.path.join(args.outdir, "benchmark_scenes.txt"), "w") as f:
        f.write(text + "\n")


if __name__ == "__main__":
    main()
