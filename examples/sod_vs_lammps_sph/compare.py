#!/usr/bin/env python3
"""Compare SPH-ASTRO with LAMMPS' SPH package on the particles of the 3d shock tube shock3d.lmp.

Usage (from anywhere; python3 of build/venv, on PATH after source build/env.sh)::

    python3 examples/sod_vs_lammps_sph/compare.py [--np 1] [--outdir DIR]
        [--check | --check-accuracy] [--var NAME=VALUE ...]   (variables of in.sph_astro)
        [--run-lammps-sph] [--write-reference] [--reference FILE]

Runs ``in.sph_astro`` (SPH-ASTRO on the particles of LAMMPS'
``examples/PACKAGES/sph/shock_tube/shock3d.lmp``) as ``lmp -in ... -log ... -screen none``
inside DIR (default build/output/sod_vs_lammps_sph), timing the wall time of the lmp call.
The result of LAMMPS' own SPH package on ``in.lammps_sph`` (the physics of shock3d.lmp), which
changes only with LAMMPS' version, is read from the stored reference
``lammps_sph_reference.txt`` beside this script (its L1 errors, wall time and final profile;
it records the LAMMPS version it came from). ``--run-lammps-sph`` runs the SPH package again
instead (before SPH-ASTRO, back to back), ``--write-reference`` does so and rewrites the stored
file (``--reference FILE``: another file). ``--check`` implies ``--run-lammps-sph``: wall times
are only comparable back to back.

Then compares the final states (t = 20) with the exact Riemann solution (gamma 1.4, left
(rho, v, P) = (1, 0, 1), right (0.25, 0, 0.25), discontinuity at x0 = 0.5, halfway between
the particle layers x = 0 and x = 1) over -50 <= x <= 50, the range of LAMMPS'
exact_solution.dat: per-particle L1 errors of rho, vx and P, a table, the SPH-ASTRO /
SPH-package ratios of L1(rho) and wall time, and a PNG of the profiles
(DIR/sod_vs_lammps_sph.png).

The environment (lmp on PATH, the plugin path) comes from $SPH_ASTRO_BUILD/env.sh, or
build/env.sh of this repository, when that file exists; otherwise from the caller.

Exit status: 0; 2 if a LAMMPS run failed (non-zero status or no dump) or the stored reference
is missing or was written for another in.lammps_sph; with --check, 1 unless SPH-ASTRO's
L1(rho) <= 0.5 x the SPH package's AND its wall time <= 0.5 x the SPH package's;
with --check-accuracy, 1 unless the L1(rho) half holds.
"""

import argparse
import datetime
import hashlib
import math
import os
import re
import shutil
import subprocess
import sys
import time

import numpy as np

from sphastro import riemann
from sphastro.dump import read_last_frame

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, os.pardir, os.pardir))

GAMMA = 1.4
LEFT = (1.0, 0.0, 1.0)
RIGHT = (0.25, 0.0, 0.25)
X0 = 0.5          # interface between the last left layer (x = 0) and the first right one (x = 1)
TEND = 20.0
WINDOW = (-50.0, 50.0)
BAR = 0.5         # acceptance: SPH-ASTRO L1(rho) and wall time <= BAR x the SPH package's

RUNS = (
    # key, label, input, dump, log
    ("lammps_sph", "LAMMPS SPH", "in.lammps_sph", "dump.lammps_sph", "log.lammps_sph"),
    ("sph_astro", "SPH-ASTRO", "in.sph_astro", "dump.sph_astro", "log.sph_astro"),
)

# the stored result of LAMMPS' SPH package (--write-reference rewrites it)
REFERENCE = os.path.join(HERE, "lammps_sph_reference.txt")
PROFILE_WINDOW = (WINDOW[0] - 2.0, WINDOW[1] + 2.0)   # stored profile: the plot's x range
META_RE = re.compile(r"^# ([a-z0-9_]+) = (.*)$")
VERSION_RE = re.compile(r"^LAMMPS \((.+)\)\s*$", re.M)

LOOP_RE = re.compile(r"^Loop time of (\S+) on (\d+) procs for (\d+) steps with (\d+) atoms",
                     re.M)


def load_environment():
    """The environment of build/env.sh (lmp, plugin path), or the caller's if there is none."""
    build = os.environ.get("SPH_ASTRO_BUILD", os.path.join(ROOT, "build"))
    env_sh = os.path.join(build, "env.sh")
    if not os.path.isfile(env_sh):
        return dict(os.environ), None
    out = subprocess.run(["bash", "-c", 'source "$1" && env -0', "bash", env_sh],
                         check=True, stdout=subprocess.PIPE).stdout
    env = dict(item.split("=", 1) for item in out.decode().split("\0") if "=" in item)
    return env, env_sh


def run_lammps(key, label, infile, dump, log, np_ranks, outdir, env, extra_vars=()):
    """Run one input in outdir; return a dict with status, wall time and the log's loop data.
    extra_vars: (name, value) pairs passed as -var name value."""
    for stale in (dump, log):
        if os.path.exists(os.path.join(outdir, stale)):
            os.remove(os.path.join(outdir, stale))
    cmd = ["lmp", "-in", os.path.join(HERE, infile), "-log", log, "-screen", "none",
           "-var", "out", dump]
    for name, value in extra_vars:
        cmd += ["-var", name, value]
    if np_ranks > 1:
        cmd = ["mpirun", "-np", str(np_ranks)] + cmd
    load = os.getloadavg()[0]
    print(f"running {label}: {' '.join(cmd)}  (load average {load:.2f})", flush=True)
    start = time.perf_counter()
    proc = subprocess.run(cmd, cwd=outdir, env=env, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT)
    wall = time.perf_counter() - start
    result = {"key": key, "label": label, "wall": wall, "rc": proc.returncode,
              "dump": os.path.join(outdir, dump), "log": os.path.join(outdir, log),
              "output": proc.stdout.decode(errors="replace"), "load": load}
    text = ""
    if os.path.exists(result["log"]):
        with open(result["log"], errors="replace") as f:
            text = f.read()
    version = VERSION_RE.search(text)
    result["version"] = version.group(1) if version else "unknown"
    loops = LOOP_RE.findall(text)
    if loops:
        loop, procs, steps, atoms = loops[-1]
        result.update(loop=float(loop), procs=int(procs), steps=int(steps), atoms=int(atoms))
    result["ok"] = proc.returncode == 0 and os.path.exists(result["dump"]) and bool(loops)
    if not result["ok"]:
        print(f"  {label} FAILED (exit status {proc.returncode}); last lines of output/log:")
        tail = (text or result["output"]).rstrip().splitlines()[-15:]
        for line in tail:
            print("    " + line)
        for line in result["output"].rstrip().splitlines()[-5:]:
            if line not in tail:
                print("    " + line)
    else:
        print(f"  {label}: {wall:.2f} s wall, {result['steps']} steps, loop time "
              f"{result['loop']:.2f} s", flush=True)
    return result


def particle_data(key, path):
    """x, rho, vx, P from a final dump (P of the SPH package: 0.4 rho e / m)."""
    frame = read_last_frame(path)
    c = frame.columns
    x, rho, vx = c["x"], c["rho"], c["vx"]
    if key == "lammps_sph":
        p = (GAMMA - 1.0) * rho * c["e"] / c["mass"]
        if "pressure" in c and not np.allclose(p, c["pressure"], rtol=1e-4, atol=1e-6):
            print("  warning: the dumped pressure differs from 0.4 rho e / m")
    else:
        p = c["pressure"]
    return {"x": x, "rho": rho, "vx": vx, "p": p, "time": frame.time,
            "timestep": frame.timestep}


def l1_errors(data, x0=X0):
    """Mean |q - q_exact| of rho, vx, P over the particles in WINDOW (data["count"], when
    present, is the number of particles each row stands for: the stored profile)."""
    x = data["x"]
    sel = (x >= WINDOW[0]) & (x <= WINDOW[1])
    count = data.get("count", np.ones_like(x))[sel]
    exact = riemann.sample(x[sel], TEND, LEFT, RIGHT, GAMMA, x0)
    err = {k: float(np.sum(count * np.abs(data[k][sel] - exact[q])) / np.sum(count))
           for k, q in (("rho", "rho"), ("vx", "vx"), ("p", "p"))}
    err["n"] = int(np.sum(count))
    err["nan"] = int(sum(np.count_nonzero(~np.isfinite(data[k])) for k in ("x", "rho", "vx", "p")))
    return err


def sha256(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def write_reference(path, run, data, err, err0, np_ranks):
    """Store the SPH package's result: run data, L1 errors (full precision, from the dump) and
    the final profile over PROFILE_WINDOW (x to 1e-4, rho, vx, P to 1e-6), each distinct row
    once with the number of particles that share it (planar layers of 64 particles collapse)."""
    x = data["x"]
    sel = np.nonzero((x >= PROFILE_WINDOW[0]) & (x <= PROFILE_WINDOW[1]))[0]
    rows = {}
    for i in sel[np.argsort(x[sel], kind="stable")]:
        fields = [f"{data[k][i]:.{d}f}" for k, d in (("x", 4), ("rho", 6), ("vx", 6), ("p", 6))]
        row = " ".join("0.000000" if f == "-0.000000" else f for f in fields)
        rows[row] = rows.get(row, 0) + 1
    meta = {
        "lammps_version": run["version"],
        "input": "in.lammps_sph",
        "input_sha256": sha256(os.path.join(HERE, "in.lammps_sph")),
        "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
        "np": np_ranks, "atoms": run["atoms"], "steps": run["steps"], "time": data["time"],
        "wall": f"{run['wall']:.2f}", "loop": f"{run['loop']:.2f}",
        "load": f"{run['load']:.2f}", "n": err["n"],
        "l1_rho": repr(err["rho"]), "l1_vx": repr(err["vx"]), "l1_p": repr(err["p"]),
        "l1_rho_x0_0": repr(err0["rho"]), "l1_vx_x0_0": repr(err0["vx"]),
        "l1_p_x0_0": repr(err0["p"]),
    }
    lines = [
        "# SPH-ASTRO - astrophysical SPH for LAMMPS. This software is distributed under the GNU",
        "# General Public License version 2 (the same licence as LAMMPS); see the LICENSE file.",
        "#",
        "# LAMMPS' SPH package on in.lammps_sph (the physics of its",
        "# examples/PACKAGES/sph/shock_tube/shock3d.lmp) at t = 20: the stored reference of",
        "# compare.py. It changes only with LAMMPS' version or in.lammps_sph; rewrite it with",
        "#   python3 examples/sod_vs_lammps_sph/compare.py --write-reference",
        "# (runs the SPH package, 25-50 s on one core). wall and loop are seconds on the",
        "# machine that wrote the file (load = its load average at the start); L1 = mean",
        f"# |q - q_exact| over the n particles with {WINDOW[0]:g} <= x <= {WINDOW[1]:g},"
        f" x0 = {X0:g} (_x0_0: x0 = 0), from the dump.",
    ]
    lines += [f"# {k} = {v}" for k, v in meta.items()]
    lines += [
        f"# final profile, {PROFILE_WINDOW[0]:g} <= x <= {PROFILE_WINDOW[1]:g}, sorted by x (x to"
        " 1e-4, rho, vx, P to 1e-6); count = particles with this row",
        "# x rho vx p count",
    ]
    lines += [f"{row} {count}" for row, count in rows.items()]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    print(f"wrote the reference {path} ({len(rows)} profile rows, {os.path.getsize(path)} bytes)")


def read_reference(path):
    """The stored SPH package run: (run, data, err, err0), or None with a message."""
    if not os.path.isfile(path):
        print(f"error: no stored reference {path}: run compare.py --write-reference")
        return None
    meta = {}
    with open(path) as f:
        for line in f:
            m = META_RE.match(line.rstrip("\n"))
            if m:
                meta[m.group(1)] = m.group(2)
    table = np.loadtxt(path, ndmin=2)
    data = {k: table[:, i] for i, k in enumerate(("x", "rho", "vx", "p", "count"))}
    data.update(time=float(meta["time"]), timestep=None)
    if meta.get("input_sha256") != sha256(os.path.join(HERE, meta.get("input", "in.lammps_sph"))):
        print(f"error: in.lammps_sph changed since {path} was written: rewrite it with "
              "compare.py --write-reference (or use --run-lammps-sph)")
        return None
    run = {"key": "lammps_sph", "label": "LAMMPS SPH", "stored": True, "ok": True,
           "version": meta["lammps_version"], "date": meta["date"], "np": int(meta["np"]),
           "atoms": int(meta["atoms"]), "steps": int(meta["steps"]),
           "wall": float(meta["wall"]), "loop": float(meta["loop"]), "load": float(meta["load"])}
    err = {"rho": float(meta["l1_rho"]), "vx": float(meta["l1_vx"]), "p": float(meta["l1_p"]),
           "n": int(meta["n"]), "nan": 0}
    err0 = {"rho": float(meta["l1_rho_x0_0"]), "vx": float(meta["l1_vx_x0_0"]),
            "p": float(meta["l1_p_x0_0"]), "n": int(meta["n"]), "nan": 0}
    # the profile must reproduce the stored errors (it is rounded)
    again = l1_errors(data)
    if again["n"] != err["n"] or any(abs(again[k] - err[k]) > 1e-4 * err[k]
                                      for k in ("rho", "vx", "p")):
        print(f"error: the profile of {path} does not reproduce its L1 errors "
              f"({again['rho']:.4e} {again['vx']:.4e} {again['p']:.4e}, n {again['n']})")
        return None
    print(f"LAMMPS SPH: stored reference {path}\n  (LAMMPS {run['version']}, written "
          f"{run['date']}, {run['np']} rank(s), wall {run['wall']:.2f} s at load "
          f"{run['load']:.2f}; --run-lammps-sph runs it again)")
    return run, data, err, err0


def check_reference_file(env):
    """Compare LAMMPS' exact_solution.dat (columns x rho v P) with sphastro.riemann."""
    src = env.get("LAMMPS_SOURCE_DIR", "")
    path = os.path.join(src, "examples", "PACKAGES", "sph", "shock_tube", "exact_solution.dat")
    if not src or not os.path.isfile(path):
        print("exact_solution.dat of LAMMPS not found (LAMMPS_SOURCE_DIR unset?): not checked")
        return
    ref = np.loadtxt(path)
    print(f"LAMMPS exact_solution.dat ({len(ref)} points, x {ref[0, 0]:g} .. {ref[-1, 0]:g}) "
          "against sphastro.riemann (gamma 1.4, t 20):")
    for x0 in (0.0, X0):
        ex = riemann.sample(ref[:, 0], TEND, LEFT, RIGHT, GAMMA, x0)
        dev = max(float(np.max(np.abs(ex[q] - ref[:, k])))
                  for k, q in ((1, "rho"), (2, "vx"), (3, "p")))
        print(f"  x0 = {x0:g}: max |difference| of rho, v, P = {dev:.2e}")
    print("  (the file puts the discontinuity at x0 = 0; the particles put it at x0 = 0.5,"
          " used here)")


def plot(datas, path):
    from matplotlib.figure import Figure

    xs = np.linspace(WINDOW[0], WINDOW[1], 4001)
    exact = riemann.sample(xs, TEND, LEFT, RIGHT, GAMMA, X0)
    fig = Figure(figsize=(9, 10))
    axes = fig.subplots(3, 1, sharex=True)
    styles = {"lammps_sph": dict(color="tab:orange", marker="s", ms=3.0),
              "sph_astro": dict(color="tab:blue", marker="o", ms=2.0)}
    for ax, key, label in zip(axes, ("rho", "vx", "p"), (r"$\rho$", r"$v_x$", r"$P$")):
        for run, data in datas:
            x = data["x"]
            sel = (x >= WINDOW[0] - 2) & (x <= WINDOW[1] + 2)
            label = run["label"] + (" (stored)" if run.get("stored") else "")
            ax.plot(x[sel], data[key][sel], linestyle="none", label=label,
                    rasterized=True, **styles[run["key"]])
        ax.plot(xs, exact[key], "-", lw=1.0, color="black", label="exact")
        ax.set_ylabel(label)
        ax.set_xlim(*WINDOW)
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("x")
    axes[0].legend(loc="upper right")
    fig.suptitle("3d shock tube (shock3d.lmp particles), t = 20, gamma = 1.4")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    return path


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--np", type=int, default=1, help="MPI ranks per run (default 1)")
    parser.add_argument("--outdir", default=os.path.join(ROOT, "build", "output",
                                                         "sod_vs_lammps_sph"),
                        help="scratch directory for logs, dumps and the plot")
    parser.add_argument("--check", action="store_true",
                        help=f"exit 1 unless SPH-ASTRO's L1(rho) and wall time are <= {BAR} x "
                             "the SPH package's")
    parser.add_argument("--check-accuracy", action="store_true",
                        help=f"exit 1 unless SPH-ASTRO's L1(rho) is <= {BAR} x the SPH package's "
                             "(the accuracy half of --check, for ctest: no wall-time bound)")
    parser.add_argument("--var", action="append", default=[], metavar="NAME=VALUE",
                        help="LAMMPS variable of the SPH-ASTRO run (in.sph_astro: hmode, hfact, "
                             "kernel, switch, visc, cond, ...), repeatable")
    parser.add_argument("--run-lammps-sph", action="store_true",
                        help="run LAMMPS' SPH package again instead of reading its stored result "
                             "(implied by --check and --write-reference)")
    parser.add_argument("--write-reference", action="store_true",
                        help="run LAMMPS' SPH package and rewrite the stored reference with its "
                             "result (after a LAMMPS update or a change of in.lammps_sph)")
    parser.add_argument("--reference", default=REFERENCE, metavar="FILE",
                        help="the stored reference (default: lammps_sph_reference.txt beside "
                             "this script)")
    args = parser.parse_args(argv)
    if args.np < 1:
        parser.error("--np must be >= 1")
    if args.check or args.write_reference:
        args.run_lammps_sph = True
    astro_vars = []
    for item in args.var:
        if "=" not in item:
            parser.error(f"--var expects NAME=VALUE, got {item!r}")
        astro_vars.append(tuple(item.split("=", 1)))

    env, env_sh = load_environment()
    if env_sh:
        print(f"environment from {env_sh}")
    if shutil.which("lmp", path=env.get("PATH")) is None:
        print("error: lmp not found on PATH (source build/env.sh)")
        return 2
    outdir = os.path.abspath(args.outdir)
    os.makedirs(outdir, exist_ok=True)

    stored = None
    if not args.run_lammps_sph:
        stored = read_reference(os.path.abspath(args.reference))
        if stored is None:
            return 2
        print()
    runs = [run_lammps(*spec, args.np, outdir, env, astro_vars if spec[0] == "sph_astro" else ())
            for spec in RUNS if args.run_lammps_sph or spec[0] != "lammps_sph"]
    failed = [r["label"] for r in runs if not r["ok"]]

    print()
    check_reference_file(env)
    print()

    rows, datas = {}, []
    if stored is not None:
        run, data, err, err0 = stored
        rows["lammps_sph"] = (run, err, err0)
        datas.append((run, data))
    for run in runs:
        if not run["ok"]:
            continue
        data = particle_data(run["key"], run["dump"])
        if data["time"] is not None and abs(data["time"] - TEND) > 1e-6 * TEND:
            print(f"warning: {run['label']} dump is at t = {data['time']}, not {TEND}")
        err = l1_errors(data)
        if err["nan"]:
            print(f"warning: {run['label']} dump holds {err['nan']} non-finite values")
        rows[run["key"]] = (run, err, l1_errors(data, 0.0))
        datas.append((run, data))
        if run["key"] == "lammps_sph" and args.write_reference:
            path = os.path.abspath(args.reference)
            write_reference(path, run, data, err, rows[run["key"]][2], args.np)
            if read_reference(path) is None:
                return 2
            print()
    datas.sort(key=lambda item: [spec[0] for spec in RUNS].index(item[0]["key"]))
    if stored is not None and "sph_astro" in rows:
        version = rows["sph_astro"][0]["version"]
        if version != stored[0]["version"]:
            print(f"warning: the stored reference comes from LAMMPS {stored[0]['version']}, "
                  f"this run from LAMMPS {version}: rewrite it with --write-reference\n")

    header = (f"{'code':<12} {'particles':>9} {'steps':>6} {'wall s':>7} {'loop s':>7} "
              f"{'particle-steps/s':>16} {'L1 rho':>9} {'L1 vx':>9} {'L1 P':>9}")
    print(f"np = {args.np}; L1 = mean over the {', '.join(str(r[1]['n']) for r in rows.values())}"
          f" particles with {WINDOW[0]:g} <= x <= {WINDOW[1]:g} at t = {TEND:g}, x0 = {X0:g}")
    print(header)
    print("-" * len(header))
    for run, err, _ in rows.values():
        rate = run["atoms"] * run["steps"] / run["wall"]
        label = run["label"] + (" *" if run.get("stored") else "")
        print(f"{label:<12} {run['atoms']:>9d} {run['steps']:>6d} {run['wall']:>7.2f} "
              f"{run['loop']:>7.2f} {rate:>16.3e} {err['rho']:>9.3e} {err['vx']:>9.3e} "
              f"{err['p']:>9.3e}")
    for run, _, err0 in rows.values():
        print(f"  ({run['label']} against the exact solution with x0 = 0, the convention of "
              f"exact_solution.dat: L1 rho {err0['rho']:.3e}, vx {err0['vx']:.3e}, "
              f"P {err0['p']:.3e})")
    if stored is not None:
        print(f"  * stored reference (LAMMPS {stored[0]['version']}, {stored[0]['date']}): "
              "its wall time is not from this run")

    status = 0
    if "lammps_sph" in rows and "sph_astro" in rows:
        ref_run, ref_err, _ = rows["lammps_sph"]
        new_run, new_err, _ = rows["sph_astro"]
        l1_ratio = new_err["rho"] / ref_err["rho"] if ref_err["rho"] > 0 else math.inf
        wall_ratio = new_run["wall"] / ref_run["wall"]
        print()
        print(f"L1(rho) ratio SPH-ASTRO / SPH package = {l1_ratio:.3f}")
        print(f"wall time ratio SPH-ASTRO / SPH package = {wall_ratio:.3f}"
              f"  (loop time ratio {new_run['loop'] / ref_run['loop']:.3f})"
              + ("; against the stored time, not back to back" if stored is not None else ""))
        png = plot(datas, os.path.join(outdir, "sod_vs_lammps_sph.png"))
        print(f"profile plot: {png}")
        if args.check or args.check_accuracy:
            ok_l1 = l1_ratio <= BAR          # False for NaN
            print(f"check L1(rho) ratio {l1_ratio:.3f} <= {BAR}: {'ok' if ok_l1 else 'FAILED'}")
            ok_wall = True
            if args.check:
                ok_wall = wall_ratio <= BAR
                print(f"check wall time ratio {wall_ratio:.3f} <= {BAR}: "
                      f"{'ok' if ok_wall else 'FAILED'}")
            if not (ok_l1 and ok_wall):
                status = 1
    elif args.check or args.check_accuracy:
        status = 1
    if failed:
        print(f"failed run(s): {', '.join(failed)}; logs in {outdir}")
        return 2
    return status


if __name__ == "__main__":
    sys.exit(main())
