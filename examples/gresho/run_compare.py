#!/usr/bin/env python3
"""Gresho-Chan vortex with constant artificial viscosity and with the Morris-Monaghan switch.

Usage (from anywhere; python3 of build/venv, on PATH after source build/env.sh)::

    python3 examples/gresho/run_compare.py [--n 64] [--np 1]
        [--kernel m4] [--hfact 1.2] [--amin 0.1] [--ell 0.2] [--alpha 1.0] [--beta 2.0]
        [--every 0.1]
        [--outdir build/output/gresho] [--var NAME=VALUE ...]
        [--assert-ratio 0.5] [--assert-constant l1=0.2] [--assert-switch l1=0.1]

Runs examples/gresho/in.gresho twice at lattice resolution n (n particles across the unit box):
``visc constant`` (alpha, beta fixed) and ``visc switch`` (fix sph/astro/switch
morris-monaghan AMIN ALPHA ELL, every particle starting at alpha_min). Prints, for both, the
particle number, steps, wall time (around the lmp call) and the L1 error of v_phi at t = tend
against the steady vortex over r < 0.5, then the ratio L1(switch) / L1(constant). Writes to
OUTDIR: the logs and dumps (log.constant, dump.constant, ...), ``gresho_nN.png`` with both
v_phi, P and alpha profiles, ``gresho_nN_time.png`` with the energy error, E_kin, L_z, mean
alpha and (with --every > 0) L1(v_phi) against time.

The assertions exit with status 1 when they fail: --assert-ratio R needs
L1(switch) <= R L1(constant); --assert-constant / --assert-switch take analyse.py's
--assert bounds (l1 = v_phi, vr, P, rho). ``lmp`` comes from PATH, else from build/env.sh.
"""

import argparse
import os
import re
import subprocess
import sys
import time

from sphastro import cli, gresho
from sphastro.dump import read_last_frame
from sphastro.runs import lammps_environment

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, os.pardir, os.pardir))

_LOOP = re.compile(r"^Loop time of (\S+) on (\d+) procs for (\d+) steps with (\d+) atoms", re.M)




def run_variant(name, lmp_vars, args, env):
    """Run in.gresho once; return a dict with wall time, steps, N, errors, log figures."""
    dump = os.path.join(args.outdir, f"dump.{name}")
    log = os.path.join(args.outdir, f"log.{name}")
    cmd = ([args.lmp] if args.np == 1 else ["mpirun", "-np", str(args.np), args.lmp])
    cmd += ["-in", os.path.join(HERE, "in.gresho"), "-log", log, "-screen", "none",
            "-var", "n", str(args.n), "-var", "out", dump, "-var", "every", str(args.every)]
    for k, v in lmp_vars.items():
        cmd += ["-var", k, str(v)]
    print(f"[{name}] {' '.join(cmd)}", flush=True)
    start = time.perf_counter()
    proc = subprocess.run(cmd, cwd=args.outdir, env=env, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT)
    wall = time.perf_counter() - start
    if proc.returncode != 0:
        sys.exit(f"{name}: lmp failed (exit {proc.returncode}); see {log}\n"
                 f"{proc.stdout.decode(errors='replace')[-2000:]}")
    with open(log, encoding="utf-8", errors="replace") as f:
        loops = _LOOP.findall(f.read())
    frame = read_last_frame(dump)
    res = {"name": name, "wall": wall, "loop": sum(float(x[0]) for x in loops),
           "steps": sum(int(x[2]) for x in loops), "natoms": int(loops[-1][3]),
           "frame": frame, "err": gresho.gresho_errors(frame, args.rmax),
           "thermo": gresho.read_thermo(log), "dump": dump,
           "series": None}
    res["log"] = gresho.log_figures(res["thermo"])
    if args.every > 0 and os.path.exists(dump + ".series"):
        res["series"] = gresho.series_errors(dump + ".series", args.rmax)
    return res


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--n", type=int, default=64, help="particles across x (default 64)")
    parser.add_argument("--np", type=int, default=1, help="MPI ranks per run (default 1)")
    parser.add_argument("--alpha", type=float, default=1.0,
                        help="constant alpha, and alpha_max of the switch (default 1)")
    parser.add_argument("--beta", type=float, default=2.0, help="beta at alpha (default 2)")
    parser.add_argument("--amin", type=float, default=0.1, help="switch alpha_min (default 0.1)")
    parser.add_argument("--ell", type=float, default=0.2, help="switch decay L (default 0.2)")
    parser.add_argument("--switch", default="morris-monaghan",
                        choices=("morris-monaghan", "cullen-dehnen"),
                        help="fix sph/astro/switch form (default morris-monaghan)")
    parser.add_argument("--kernel", default="m4",
                        help="kernel: m4, m6, wendland/c2, wendland/c4 (default m4)")
    parser.add_argument("--hfact", type=float, default=1.2,
                        help="h = hfact (m/rho)^(1/2) (default 1.2: ~18 neighbours with m4; "
                             "wendland/c4 with 2.0: ~50)")
    parser.add_argument("--tend", type=float, default=1.0, help="end time (default 1)")
    parser.add_argument("--every", type=float, default=0.1,
                        help="dump interval in time for L1(t) (0: final dump only; default 0.1)")
    parser.add_argument("--rmax", type=float, default=0.5, help="measure r < rmax (default 0.5)")
    parser.add_argument("--outdir", default=os.path.join(ROOT, "build", "output", "gresho"))
    parser.add_argument("--var", action="append", default=[], metavar="NAME=VALUE",
                        help="further in.gresho variable for both runs (repeatable)")
    parser.add_argument("--lmp", default="lmp", help="LAMMPS executable (default lmp)")
    parser.add_argument("--assert-ratio", type=float, default=None,
                        help="fail unless L1(switch) <= R * L1(constant)")
    parser.add_argument("--assert-constant", default=None,
                        help="analyse.py --assert bounds for the constant-alpha run")
    parser.add_argument("--assert-switch", default=None,
                        help="analyse.py --assert bounds for the switch run")
    args = parser.parse_args(argv)
    args.outdir = os.path.abspath(args.outdir)
    os.makedirs(args.outdir, exist_ok=True)

    common = {"tend": args.tend, "alpha": args.alpha, "beta": args.beta,
              "kernel": args.kernel, "hfact": args.hfact}
    for item in args.var:
        if "=" not in item:
            parser.error(f"--var: expected NAME=VALUE, got {item!r}")
        k, v = item.split("=", 1)
        common[k.strip()] = v.strip()
    env = lammps_environment()
    runs = [run_variant("constant", {**common, "visc": "constant"}, args, env),
            run_variant("switch", {**common, "visc": "switch", "amin": args.amin,
                                   "ell": args.ell, "swform": args.switch}, args, env)]
    labels = [f"constant alpha = {args.alpha:g}",
              f"{args.switch} alpha {args.amin:g}-{args.alpha:g}, L = {args.ell:g}"]

    print()
    print(f"Gresho-Chan vortex, 2D, gamma 5/3, t = {args.tend:g}, n = {args.n}, kernel "
          f"{common['kernel']}, hfact {common['hfact']}, {args.np} MPI rank(s); "
          f"L1 of v_phi per particle over r < {args.rmax:g}")
    head = (f"{'variant':<10} {'N':>7} {'steps':>6} {'wall_s':>8} {'L1(vphi)':>10} "
            f"{'L1(vr)':>10} {'L1(P)':>10} {'Ekin/Ekin0':>10} {'|dE/E0|':>9} {'<alpha>':>9}")
    print(head)
    for r, label in zip(runs, labels):
        e, lg = r["err"], r["log"]
        alpha_mean = e.get("alpha_mean", float("nan"))
        print(f"{r['name']:<10} {r['natoms']:>7} {r['steps']:>6} {r['wall']:>8.2f} "
              f"{e['vphi']:>10.3e} {e['vr']:>10.3e} {e['p']:>10.3e} "
              f"{lg.get('ekin_ratio', float('nan')):>10.4f} {lg.get('dE_max', float('nan')):>9.2e} "
              f"{alpha_mean:>9.3f}")
    l1c, l1s = runs[0]["err"]["vphi"], runs[1]["err"]["vphi"]
    ratio = l1s / l1c if l1c > 0 else float("nan")
    print(f"L1(vphi) constant alpha = {l1c:.4e}")
    print(f"L1(vphi) switch = {l1s:.4e}")
    print(f"ratio switch/constant = {ratio:.3f}")
    print(f"wall time constant = {runs[0]['wall']:.2f} s, switch = {runs[1]['wall']:.2f} s")

    png = os.path.join(args.outdir, f"gresho_n{args.n}.png")
    gresho.plot_profiles([r["frame"] for r in runs], labels, png, args.rmax,
                          title=f"Gresho-Chan vortex, N = {runs[0]['natoms']}, {common['kernel']} "
                                f"hfact {common['hfact']}, t = {args.tend:g}: "
                                f"L1(switch)/L1(constant) = {ratio:.3f}")
    png_t = os.path.join(args.outdir, f"gresho_n{args.n}_time.png")
    gresho.plot_log([r["thermo"] for r in runs], labels, png_t,
                     [r["series"] for r in runs] if args.every > 0 else None)
    print(f"profiles: {png}\ntime series: {png_t}")

    failed = []
    if args.assert_ratio is not None:
        failed += cli.check_bounds(f"ratio={args.assert_ratio!r}", {"ratio": ratio},
                                   error=parser.error)
    for r, bounds in ((runs[0], args.assert_constant), (runs[1], args.assert_switch)):
        if bounds:
            print(f"{r['name']}:")
            failed += [f"{r['name']} {name}" for name in cli.check_bounds(
                bounds, gresho.assert_values(r["err"]), error=parser.error,
                conditions={"particles in the measured region": r["err"]["n"] > 0})]
    if args.assert_ratio is None and not args.assert_constant and not args.assert_switch:
        return 0
    return cli.report(failed)


if __name__ == "__main__":
    sys.exit(main())
