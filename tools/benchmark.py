#!/usr/bin/env python3
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
"""SPH-ASTRO throughput and memory benchmark on a uniform periodic 3D box.

Usage (from the repository root)::

    python3 tools/benchmark.py [--sizes 1e4,1e5,1e6] [--np 1] [--steps 20]
        [--outdir build/output/benchmark] [--var name=value ...]

Runs examples/benchmark/in.benchmark once per size: N equal-mass particles on an fcc lattice
(N = 4 ncell^3, ncell chosen to come closest to the requested size), rho = 1, u = 1, gamma 5/3,
random displacements and velocities, h = 1.2 (m/rho)^(1/3) (about 58 neighbours inside the M4
support 2h), fixed dt = 0.2 h / c, ``--steps`` steps after the set-up.  ``lmp`` must be on PATH
(``source build/env.sh``); otherwise build/env.sh is sourced.  Prints, per size:

* N, steps, loop_s: LAMMPS' ``Loop time`` of the timed steps (set-up excluded);
* Mps/s and Mps/s/core: million particle-steps per second (per MPI rank);
* us/ps: microseconds per particle-step (loop_s / (N steps)); flat in N for linear scaling;
  us*core/ps multiplies it by the ranks;
* pair%, neigh%, comm%: shares of the loop time from LAMMPS' timing breakdown (pair
  sph/astro makes its own neighbour lists: their time is part of pair%);
* nlist: neighbours per particle in the pair style's list: 2 x the half-list entries per
  particle of pair sph/astro's own lists (its end-of-run line "pair sph/astro neighbour
  search: ..."), else 2 x LAMMPS' ``Ave neighs/atom`` of a half list (nan if neither);
  nkern: mean neighbours inside the kernel support 2h (pair's count);
* RSS_MB: peak resident memory summed over the ranks (``/usr/bin/time -f %M`` around each rank;
  fallback ``getrusage(RUSAGE_CHILDREN)``), B/part: RSS / N, dB/part: marginal bytes per particle
  between consecutive sizes (removes the fixed ~30 MB of the executable and libraries);
* lmp_MB: LAMMPS' own ``Per MPI rank memory allocation`` (avg per rank x ranks).

The table is also written to OUTDIR/benchmark_table.txt, logs to OUTDIR/N<size>/.
"""

import argparse
import os
import re
import resource
import shutil
import subprocess
import sys
import time

from sphastro.runs import provenance, lammps_environment

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir))
INPUT = os.path.join(ROOT, "examples", "benchmark", "in.benchmark")

_LOOP = re.compile(r"^Loop time of (\S+) on (\d+) procs for (\d+) steps with (\d+) atoms", re.M)
_MEM = re.compile(r"^Per MPI rank memory allocation \(min/avg/max\) = (\S+) \| (\S+) \| (\S+)",
                  re.M)
_NEIGH = re.compile(r"^Ave neighs/atom = (\S+)", re.M)
_SEARCH = re.compile(r"^pair sph/astro neighbour search:.*?per particle: (\S+) half-list entries",
                     re.M)
_SECTION = re.compile(r"^(Pair|Neigh|Comm|Output|Modify|Other)\s*\|.*\|\s*(\S+)\s*$", re.M)
_NEWTON_OFF = re.compile(r"^\s*newton\s+off", re.M)






def ncell_for(n):
    """fcc cells per side whose N = 4 ncell^3 is closest to n (in log)."""
    c = max(1, round((n / 4.0) ** (1.0 / 3.0)))
    return min((c - 1, c, c + 1), key=lambda k: abs(((4 * k ** 3) / n) - 1.0) if k > 0 else 1e9)


def parse_log(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        text = f.read()
    loops = _LOOP.findall(text)
    if not loops:
        raise RuntimeError(f"{path}: no 'Loop time' line (did the run fail?)")
    loop_s, procs, steps, natoms = loops[-1]
    mem = _MEM.findall(text)
    neigh = _NEIGH.findall(text)
    search = _SEARCH.findall(text)
    sections = {name: float(pct) for name, pct in _SECTION.findall(text)}
    # thermo: the c_nn column (mean neighbours inside the support) of the last thermo line
    nkern = float("nan")
    lines = text.splitlines()
    for k, line in enumerate(lines):
        if line.split()[:1] == ["Step"] and "c_nn" in line.split():
            col = line.split().index("c_nn")
            rows = []
            for row in lines[k + 1:]:
                if row.startswith("Loop time"):
                    break
                rows.append(row.split())
            values = [float(r[col]) for r in rows if len(r) > col and r[0].isdigit()]
            if values:
                nkern = sum(values) / len(values)
    half = not _NEWTON_OFF.search(text)
    return {
        "loop_s": float(loop_s), "procs": int(procs), "steps": int(steps), "N": int(natoms),
        "mem_avg_mb": float(mem[-1][1]) if mem else float("nan"),
        "mem_max_mb": float(mem[-1][2]) if mem else float("nan"),
        # pair sph/astro searches its neighbours itself (LAMMPS' count is then 0)
        "nlist": 2.0 * float(search[-1]) if search
        else (2.0 if half else 1.0) * float(neigh[-1]) if neigh and float(neigh[-1]) > 0
        else float("nan"),
        "nkern": nkern,
        "sections": sections,
    }


def run_size(n, args, env, have_time):
    ncell = ncell_for(n)
    workdir = os.path.join(args.outdir, f"N{4 * ncell ** 3}")
    os.makedirs(workdir, exist_ok=True)
    log = os.path.join(workdir, "log.lammps")
    # LAMMPS reads its input while running: run a copy, safe from edits and kept as a record
    copy = os.path.join(workdir, os.path.basename(INPUT))
    shutil.copyfile(INPUT, copy)
    lmp_args = ["-in", copy, "-log", log, "-screen", "none",
                "-var", "ncell", str(ncell), "-var", "steps", str(args.steps)]
    for item in args.var:
        name, value = item.split("=", 1)
        lmp_args += ["-var", name, value]
    for f in os.listdir(workdir):
        if f.startswith("rss."):
            os.remove(os.path.join(workdir, f))
    if have_time:
        # each rank under GNU time, peak RSS (kB) to rss.<rank>
        wrapper = ['sh', '-c', 'exec /usr/bin/time -f %M -o "rss.${OMPI_COMM_WORLD_RANK:-'
                   '${PMI_RANK:-0}}" "$0" "$@"', args.lmp] + lmp_args
    else:
        wrapper = [args.lmp] + lmp_args
    cmd = wrapper if args.np == 1 else ["mpirun", "-np", str(args.np)] + wrapper
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    start = time.perf_counter()
    proc = subprocess.run(cmd, cwd=workdir, env=env, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    if proc.returncode != 0:
        tail = proc.stdout.decode(errors="replace")[-2000:]
        raise RuntimeError(f"{' '.join(cmd)} failed (exit {proc.returncode}); see {log}\n{tail}")
    info = parse_log(log)
    info["wall_s"] = wall
    info["log"] = log
    rss_files = [f for f in os.listdir(workdir) if f.startswith("rss.")]
    if have_time and rss_files:
        kb = 0
        for f in rss_files:
            with open(os.path.join(workdir, f), encoding="utf-8") as fh:
                kb += int(fh.read().split()[-1])
        info["rss_mb"] = kb / 1024.0
        info["rss_how"] = f"/usr/bin/time, summed over {len(rss_files)} rank(s)"
    else:
        # max over all children so far (a single process, not a sum over ranks); valid when
        # the sizes grow, as here
        info["rss_mb"] = after / 1024.0 if after > before or before == 0 else float("nan")
        info["rss_how"] = "getrusage(RUSAGE_CHILDREN) ru_maxrss (largest single process)"
    return info


def format_table(rows, args):
    cols = ["N", "steps", "loop_s", "Mps/s", "Mps/s/core", "us/ps", "us*core/ps", "pair%",
            "neigh%", "comm%", "nlist", "nkern", "RSS_MB", "B/part", "dB/part", "lmp_MB"]
    widths = [max(len(c), 8) for c in cols]
    widths[0] = 9
    out = [f"# SPH-ASTRO benchmark: uniform periodic fcc box, rho=1 u=1 gamma=5/3, M4, "
           f"h=1.2(m/rho)^(1/3), fixed dt=0.2h/c, {args.np} MPI rank(s), {args.steps} steps"
           + (f", -var {' '.join(args.var)}" if args.var else ""),
           "# loop_s: LAMMPS Loop time (set-up excluded); Mps/s: 1e6 particle-steps/s; us/ps: "
           "microseconds per particle-step; nlist: list neighbours (2x half list, 2h+skin);"
           " nkern: neighbours inside 2h; RSS_MB: peak RSS summed over ranks; dB/part: "
           "marginal RSS per added particle; lmp_MB: LAMMPS' memory estimate x ranks",
           "  ".join(c.rjust(w) for c, w in zip(cols, widths))]
    prev = None
    for r in rows:
        ps = r["N"] * r["steps"]
        rate = ps / r["loop_s"]
        sec = r["sections"]
        rss_b = r["rss_mb"] * 1024.0 ** 2
        marginal = float("nan")
        if prev is not None and r["N"] > prev["N"]:
            marginal = (rss_b - prev["rss_mb"] * 1024.0 ** 2) / (r["N"] - prev["N"])
        vals = [str(r["N"]), str(r["steps"]), f"{r['loop_s']:.3f}", f"{rate / 1e6:.3f}",
                f"{rate / 1e6 / r['procs']:.3f}", f"{1e6 / rate:.3f}",
                f"{1e6 / rate * r['procs']:.3f}", f"{sec.get('Pair', float('nan')):.1f}",
                f"{sec.get('Neigh', float('nan')):.1f}", f"{sec.get('Comm', float('nan')):.1f}",
                f"{r['nlist']:.1f}", f"{r['nkern']:.1f}", f"{r['rss_mb']:.1f}",
                f"{rss_b / r['N']:.0f}", "-" if marginal != marginal else f"{marginal:.0f}",
                f"{r['mem_avg_mb'] * r['procs']:.1f}"]
        out.append("  ".join(v.rjust(w) for v, w in zip(vals, widths)))
        prev = r
    if rows:
        out.append(f"# peak RSS from {rows[0]['rss_how']}")
        out.append(f"# {provenance(rows[0]['log'])}")
    if len(rows) >= 2:
        import math
        a, b = rows[0], rows[-1]
        ca = a["loop_s"] / (a["N"] * a["steps"])
        cb = b["loop_s"] / (b["N"] * b["steps"])
        slope = math.log((b["loop_s"] / b["steps"]) / (a["loop_s"] / a["steps"])) / \
            math.log(b["N"] / a["N"])
        out.append(f"# time per step ~ N^{slope:.3f} between N={a['N']} and N={b['N']} "
                   f"(1 = linear); cost per particle-step changes by x{cb / ca:.2f}")
    return "\n".join(out) + "\n"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sizes", default="1e4,1e5,1e6",
                        help="comma-separated particle numbers (rounded to 4 ncell^3)")
    parser.add_argument("--np", type=int, default=1, help="MPI ranks (default 1)")
    parser.add_argument("--steps", type=int, default=20, help="timed steps (default 20)")
    parser.add_argument("--outdir", default=os.path.join(ROOT, "build", "output", "benchmark"))
    parser.add_argument("--var", action="append", default=[], metavar="NAME=VALUE",
                        help="extra LAMMPS variable for in.benchmark, e.g. hfact=1.5 "
                             "(repeatable)")
    parser.add_argument("--lmp", default="lmp", help="LAMMPS executable (default lmp)")
    args = parser.parse_args(argv)
    if args.steps < 1:
        parser.error("--steps must be >= 1")
    args.outdir = os.path.abspath(args.outdir)
    os.makedirs(args.outdir, exist_ok=True)
    env = lammps_environment()
    have_time = os.access("/usr/bin/time", os.X_OK)

    sizes = sorted(int(float(s)) for s in args.sizes.split(",") if s.strip())
    rows = []
    for n in sizes:
        print(f"[benchmark] N ~ {n:g} (ncell {ncell_for(n)}, N = {4 * ncell_for(n) ** 3}), "
              f"{args.steps} steps on {args.np} rank(s) ...", end=" ", flush=True)
        info = run_size(n, args, env, have_time)
        print(f"loop {info['loop_s']:.2f} s, wall {info['wall_s']:.2f} s", flush=True)
        rows.append(info)
    table = format_table(rows, args)
    path = os.path.join(args.outdir, "benchmark_table.txt")
    with open(path, "w", encoding="utf-8") as f:
        f.write(table)
    print()
    print(table, end="")
    print(f"table: {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
