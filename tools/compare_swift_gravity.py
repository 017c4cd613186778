#!/usr/bin/env python3
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
"""Self-gravity side by side with SWIFT: kspace_style tree/sph/astro/gravity against SWIFT's FMM.

SWIFT (Schaller et al. 2024, MNRAS 530, 2378: a fast multipole method, multipoles to 4th order
by default, with an adaptive opening criterion of tolerance epsilon_fmm) is built outside this
repository; this script writes its initial-condition and parameter files into OUTDIR, runs it
and SPH-ASTRO one after the other on the same machine and prints markdown tables. No SWIFT
file or output belongs in the repository.

Part A: one full gravity evaluation of the Evrard sphere (Evrard 1988; M = R = G = 1).
  States: "ic", the initial conditions of examples/evrard/in.evrard at -var n 24 (28 928
  particles: fcc lattice cut to the unit sphere and stretched to rho ~ 1/r; h = 1.2 (m/rho)^(1/3),
  built through LAMMPS' Python module with the input's own commands), and "t0.6", the state of
  `mpirun -np NP lmp -in examples/evrard/in.evrard -var n 24 -var tend 0.6 -var steps individual
  -var thermoevery 50` (run once into OUTDIR/evrard_t0.6, reused while its dump exists; h from
  fix sph/astro/h there).
  SPH-ASTRO: gravity alone, pair_style sph/astro/gravity 1000.0 G 1.0 with kspace_style
  tree/sph/astro/gravity relative ALPHA (default 0.002: the relative criterion of Springel 2005;
  quadrupole tree), softening length of each particle = the state's SPH h (M4 kernel-softened
  potential, Price & Monaghan 2007, support 2h), `mpirun -np NP`. `run 0` twice (the relative
  criterion needs the accelerations of a first evaluation), then `run EVALS pre no` without an
  integrator (positions fixed): time per evaluation = LAMMPS' loop time / EVALS ("least": the
  smallest of EVALS single `run 1 pre no post no`; Kspace: LAMMPS' breakdown of the timed run).
  Error: per particle |F - F_ref| / |F_ref| against compute sph/astro/gravity/direct (its
  O(N^2) sum with the same softening), RMS, 99th percentile, maximum.
  SWIFT: the same particles as dark matter (PartType1, `swift --self-gravity --threads=NT -v 1`),
  open boundaries (periodic 0) in a cube of side --swift-box (default 100 as in its example;
  SWIFT ran 15-20 % faster in it than in a cube of side 4) centred on the sphere, the gravity
  settings of its examples/HydroTests/EvrardCollapse_3D/evrard.yml (MAC adaptive, epsilon_fmm
  0.001 unless --epsilon-fmm, theta_cr 0.7, eta 0.025; use_tree_below_softening at its default
  0: pairs closer than the softening support are summed directly) and a fixed Plummer-equivalent
  softening eps (SWIFT's Wendland C2 softening kernel, support 3 eps, phi(0) = -1/eps):
  eps = the state's mean h; eps = mean h / 1.4, which gives the potential at r = 0 of the M4
  softening of the mean h (phi(0) = -1.4/h); and its example's 0.001. A run of 16 steps of a
  tiny dt (1e-4/16) with every particle active at every step. Time per evaluation: the mean
  wall-clock time of its steps from step 2 on (its step table; it rebuilds its tree at every
  step, as its rebuild_frequency 0.01 asks when all particles are active; "least": the fastest
  step), with the wall time of its task execution (engine_launch) and the CPU time of its
  gravity tasks summed over threads (scheduler_report_task_times). Error (--swift-checks: SWIFT
  configured with --enable-gravity-force-checks=1, which sums every particle's acceleration
  exactly with its own softening and writes gravity_checks_*.dat): step 1, in the same
  per-particle form, with its counters per particle (the source particles reached directly,
  P2P, and through accepted multipoles, M2P and M2L; not a count of operations).
  Timing in --repeats rounds, every setting once per round; the least mean per evaluation is kept
  (other jobs on a shared machine slow single runs).

Part B: the Evrard collapse to t = 0.8 side by side. SPH-ASTRO: `mpirun -np NP lmp -in
  examples/evrard/in.evrard -var n {16,24} -var tend 0.8 -var steps individual -var
  thermoevery 50` (8 628 and 28 928 particles; the tree by default). SWIFT: the set-up of its
  example EvrardCollapse_3D (its makeIC.py: r = R sqrt(U), isotropic, box 100 R, h = 2R/N^(1/3),
  u = 0.05; generated here with a fixed seed and SPH-ASTRO's N) with its published evrard.yml
  (CFL 0.1, dt_max 1e-3, softening 0.001; read from the SWIFT tree, only file_name, time_end and
  the softening replaced), `--hydro --self-gravity --limiter --threads=NT`, and once more with
  the softening raised to the mean h of SPH-ASTRO's initial conditions of the same N (--matched:
  also with that softening, CFL 0.3 and dt_max 0.05, the Courant number and top step of
  SPH-ASTRO's run; the two codes define their Courant conditions differently). Reported:
  wall time around each run and the code's own (LAMMPS' loop time; SWIFT's clock at "main:
  done"), steps, particle updates, relative energy error (E - E0)/|E0| at the end (SWIFT: its
  statistics.txt, kinetic + internal + potential; SPH-ASTRO: compute sph/astro/global).

Usage: python3 tools/compare_swift_gravity.py --swift /path/to/swift
       [--swift-checks /path/to/swift_with_checks] [--outdir build/output/compare_swift_gravity]
       [--part A|B|all] [--states ic,t0.6] [--relative 0.002] [--epsilon-fmm 0.001]
       [--repeats 3] [--matched] [--np 2] [--threads 2] [--evals 10] [--sizes 16,24]
       [--swift-box 100]
Needs LAMMPS' Python module, lmp and the plugin (source build/env.sh first; the plugin's
directory, LAMMPS_PLUGIN_PATH, must not be rebuilt meanwhile: a warning says so), h5py, and SWIFT
built without MPI (e.g. ./configure --with-hydro=sphenix --with-kernel=cubic-spline
--disable-mpi). Everything runs under `nice`. Tables printed and written to OUTDIR/table.md.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import time

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
sys.path.insert(0, os.path.join(ROOT, "python"))
from sphastro.evrard import create_sphere  # noqa: E402
from sphastro.runs import lammps_environment, provenance  # noqa: E402

HFACT = 1.2
M4_PHI0 = 1.4        # M4 kernel-softened potential at r = 0: -1.4 G m / h
_LOOP = re.compile(r"^Loop time of (\S+) on (\d+) procs for (\d+) steps with (\d+) atoms", re.M)
_KSPACE = re.compile(r"^Kspace\s*\|\s*\S+\s*\|\s*(\S+)\s*\|\s*\S+\s*\|\s*\S+\s*\|\s*(\S+)",
                     re.M)


# ------------------------------------------------------------------ states

def evrard_ic(n):
    """The initial conditions of examples/evrard/in.evrard at -var n N (its lattice, stretch
    and h lines), built in LAMMPS through its Python module: id, x, m, h sorted by id."""
    from lammps import lammps
    lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    lmp.commands_list(["units lj", "atom_style atomic", "atom_modify map array sort 0 0.0",
                       "boundary s s s"])
    m = 1.0 / create_sphere(lmp, n, HFACT)
    nlocal = lmp.extract_global("nlocal")
    ids = np.array(lmp.numpy.extract_atom("id")[:nlocal])
    x = np.array(lmp.numpy.extract_atom("x")[:nlocal])
    h = np.array(lmp.extract_variable("hinit", "all", 1))[:nlocal]
    lmp.close()
    o = np.argsort(ids)
    return {"id": ids[o], "x": x[o], "m": np.full(nlocal, m), "h": h[o], "time": 0.0}


def read_dump(path):
    """a LAMMPS text dump (one snapshot) as a dict of columns and its time (if written)"""
    with open(path) as f:
        lines = f.readlines()
    t = None
    for i, line in enumerate(lines):
        if line.strip() == "ITEM: TIME":
            t = float(lines[i + 1])
        if line.startswith("ITEM: ATOMS"):
            cols = line.split()[2:]
            data = np.loadtxt(lines[i + 1:], ndmin=2)
            out = {c: data[:, k] for k, c in enumerate(cols)}
            out["time"] = t
            return out
    raise ValueError(f"{path}: no ITEM: ATOMS")


def run(cmd, cwd, stdout_path, env=None):
    """run cmd under nice in cwd, stdout and stderr to stdout_path; wall seconds"""
    os.makedirs(cwd, exist_ok=True)
    t0 = time.perf_counter()
    with open(stdout_path, "w") as out:
        rc = subprocess.run(["nice"] + cmd, cwd=cwd, stdout=out, stderr=subprocess.STDOUT,
                            env=env).returncode
    wall = time.perf_counter() - t0
    if rc != 0:
        tail = open(stdout_path, errors="replace").read()[-3000:]
        sys.exit(f"error: {' '.join(cmd)} (in {cwd}) failed with {rc}:\n{tail}")
    return wall


def lmp_cmd(args, *rest):
    return (["mpirun", "-np", str(args.np)] if args.np > 1 else []) + ["lmp"] + list(rest)


def evrard_t06(args, env):
    """the state of in.evrard -var n 24 at t = 0.6 (run once, reused while its dump exists)"""
    d = os.path.join(args.outdir, "evrard_t0.6")
    dump = os.path.join(d, "dump.evrard_t0.6")
    if os.path.exists(dump) and abs((read_dump(dump)["time"] or 0.0) - 0.6) < 1e-9:
        print(f"state t0.6: reusing {dump}", flush=True)
    else:
        print("state t0.6: running in.evrard -var n 24 to t = 0.6 ...", flush=True)
        wall = run(lmp_cmd(args, "-in", os.path.join(ROOT, "examples", "evrard", "in.evrard"),
                           "-var", "n", "24", "-var", "tend", "0.6", "-var", "steps",
                           "individual", "-var", "thermoevery", "50", "-var", "out",
                           "dump.evrard_t0.6", "-log", "log.evrard_t0.6", "-screen", "none"),
                   d, os.path.join(d, "stdout"), env)
        print(f"state t0.6: {wall:.1f} s", flush=True)
    c = read_dump(dump)
    o = np.argsort(c["id"])
    n = len(o)
    return {"id": c["id"][o].astype(np.int64), "x": np.column_stack([c["x"], c["y"], c["z"]])[o],
            "m": np.full(n, 1.0 / n), "h": c["h"][o], "time": c["time"]}


# ------------------------------------------------------------------ SPH-ASTRO, part A

def write_lammps_state(state, d):
    """data file (positions, one mass) and atomfile of h for the gravity-only inputs"""
    m = np.unique(state["m"])
    if m.size != 1:
        sys.exit("error: the state's masses are not all equal (one atom type holds them)")
    x, n = state["x"], len(state["id"])
    lo, hi = x.min(axis=0) - 0.05, x.max(axis=0) + 0.05
    with open(os.path.join(d, "state.data"), "w") as f:
        f.write(f"Evrard state t = {state['time']}\n\n{n} atoms\n1 atom types\n\n")
        for k, ax in enumerate("xyz"):
            f.write(f"{lo[k]!r} {hi[k]!r} {ax}lo {ax}hi\n")
        f.write(f"\nMasses\n\n1 {m[0]!r}\n\nAtoms # atomic\n\n")
        for i in range(n):
            f.write(f"{state['id'][i]} 1 {x[i, 0]!r} {x[i, 1]!r} {x[i, 2]!r}\n")
    with open(os.path.join(d, "state.h"), "w") as f:
        f.write(f"# SPH smoothing length h\n{n}\n")
        for i in range(n):
            f.write(f"{state['id'][i]} {state['h'][i]!r}\n")


LMP_HEAD = """units           lj
atom_style      atomic
atom_modify     map array sort 0 0.0
boundary        m m m
processors      * * 1
sph/astro/state
read_data       state.data
variable        h atomfile state.h
set             group all d_h v_h                 # softening length = the SPH h
pair_style      sph/astro/gravity 1000.0 G 1.0
pair_coeff      * *
neighbor        0.1 bin
neigh_modify    one 10000 page 100000
thermo_style    custom step
"""


def sph_reference(args, env, d):
    with open(os.path.join(d, "in.reference"), "w") as f:
        f.write(LMP_HEAD + "compute         ref all sph/astro/gravity/direct\n"
                "dump            f all custom 1 ref.dump id c_ref[1] c_ref[2] c_ref[3]\n"
                "dump_modify     f sort id format float %.17g\n"
                "run             0\n")
    run(lmp_cmd(args, "-in", "in.reference", "-log", "log.reference", "-screen", "none"), d,
        os.path.join(d, "stdout.reference"), env)
    c = read_dump(os.path.join(d, "ref.dump"))
    return np.column_stack([c["c_ref[1]"], c["c_ref[2]"], c["c_ref[3]"]])


def sph_gravity(args, env, d, alpha, fref, rnd):
    """one timed SPH-ASTRO run: mean and least time per evaluation; the errors in round 0"""
    tag = f"tree_relative_{alpha:g}"
    with open(os.path.join(d, f"in.{tag}"), "w") as f:
        f.write(LMP_HEAD + f"kspace_style    tree/sph/astro/gravity relative {alpha:g}\n"
                "run             0\n"
                "run             0                 # the relative criterion: accelerations of a "
                "first evaluation\n"
                f"run             {args.evals} pre no post yes  # post: the timing breakdown\n"
                + "run             1 pre no post no\n" * args.evals +
                f"dump            f all custom 1 {tag}.dump id fx fy fz\n"
                "dump_modify     f sort id format float %.17g\n"
                "run             0\n")
    log_name = f"log.{tag}.{rnd}"
    run(lmp_cmd(args, "-in", f"in.{tag}", "-log", log_name, "-screen", "none"), d,
        os.path.join(d, f"stdout.{tag}.{rnd}"), env)
    log = open(os.path.join(d, log_name)).read()
    loops = _LOOP.findall(log)
    timed = [lp for lp in loops if int(lp[2]) == args.evals][0]
    out = {"t": float(timed[0]) / args.evals,
           "tmin": min(float(lp[0]) for lp in loops if int(lp[2]) == 1)}
    # the breakdown of the timed run (post yes), after its loop time
    ks = _KSPACE.findall(log[log.index(f"for {args.evals} steps with"):])
    out["gpart"] = (f"Kspace {1e3 * float(ks[0][0]) / args.evals:.1f} avg/rank ({ks[0][1]} %)"
                    if ks else "")
    if rnd == 0:
        c = read_dump(os.path.join(d, f"{tag}.dump"))
        f = np.column_stack([c["fx"], c["fy"], c["fz"]])
        rel = np.linalg.norm(f - fref, axis=1) / np.linalg.norm(fref, axis=1)
        out.update(code="SPH-ASTRO", setting=f"tree relative {alpha:g}, {args.np} ranks",
                   soft="M4, per-particle h", rms=np.sqrt(np.mean(rel**2)),
                   p99=np.percentile(rel, 99), max=rel.max(), inter="",
                   prov=provenance(os.path.join(d, log_name)))
    return out

# ------------------------------------------------------------------ SWIFT

SWIFT_UNITS = """InternalUnitSystem:
  UnitMass_in_cgs:     1
  UnitLength_in_cgs:   1
  UnitVelocity_in_cgs: 1
  UnitCurrent_in_cgs:  1
  UnitTemp_in_cgs:     1
"""


def write_swift_ic(path, x, m, ptype, box, h=None, u=None):
    """SWIFT/GADGET HDF5 initial conditions: one particle type, velocities 0"""
    import h5py
    n = len(m)
    counts = [0] * 6
    counts[ptype] = n
    with h5py.File(path, "w") as f:
        g = f.create_group("Header")
        g.attrs["BoxSize"] = [box] * 3
        g.attrs["NumPart_Total"] = counts
        g.attrs["NumPart_Total_HighWord"] = [0] * 6
        g.attrs["NumPart_ThisFile"] = counts
        g.attrs["Time"] = 0.0
        g.attrs["NumFilesPerSnapshot"] = 1
        g.attrs["MassTable"] = [0.0] * 6
        g.attrs["Flag_Entropy_ICs"] = 0
        g.attrs["Dimension"] = 3
        un = f.create_group("Units")
        for k in ("length", "mass", "time", "current", "temperature"):
            key = {"length": "Unit length in cgs (U_L)", "mass": "Unit mass in cgs (U_M)",
                   "time": "Unit time in cgs (U_t)", "current": "Unit current in cgs (U_I)",
                   "temperature": "Unit temperature in cgs (U_T)"}[k]
            un.attrs[key] = 1.0
        p = f.create_group(f"PartType{ptype}")
        p.create_dataset("Coordinates", data=x, dtype="d")
        p.create_dataset("Velocities", data=np.zeros((n, 3)), dtype="f")
        p.create_dataset("Masses", data=m, dtype="f")
        p.create_dataset("ParticleIDs", data=np.arange(1, n + 1, dtype=np.uint64))
        if h is not None:
            p.create_dataset("SmoothingLength", data=h, dtype="f")
        if u is not None:
            p.create_dataset("InternalEnergy", data=u, dtype="f")


def swift_gravity_yml(path, ic, eps, efmm, t_end, dt_max):
    with open(path, "w") as f:
        f.write(SWIFT_UNITS + f"""TimeIntegration:
  time_begin: 0.
  time_end:   {t_end!r}
  dt_min:     1e-12
  dt_max:     {dt_max!r}
Snapshots:
  basename:   snap
  time_first: 100.
  delta_time: 100.
Statistics:
  delta_time: 100.
Gravity:                      # as examples/HydroTests/EvrardCollapse_3D/evrard.yml
  eta:          0.025
  MAC:          adaptive
  theta_cr:     0.7
  epsilon_fmm:  {efmm!r}
  max_physical_DM_softening: {eps!r}   # Plummer-equivalent; Wendland C2 support 3 eps
InitialConditions:
  file_name:  {ic}
  periodic:   0
PhysicalConstants:
  G: 1.
""")


# SWIFT's step table: Step Time a z dt bin_min bin_max Updates g-Updates s sink b Wall Props Dead
_SWIFT_STEP = re.compile(r"^\s+(\d+)\s+(\S+)\s+\S+\s+\S+\s+(\S+)\s+\d+\s+\d+\s+(\d+)\s+(\d+)\s+\d+"
                         r"\s+\d+\s+\d+\s+(\S+)\s+\d+\s+\S+\s*$", re.M)
_SWIFT_GRAV = re.compile(r"scheduler_report_task_times: \*\*\*\s+gravity:\s+(\S+) ms")
_SWIFT_LAUNCH = re.compile(r"engine_launch: \(tasks\) took (\S+) ms")


def swift_steps(text):
    return [(int(s), float(t), float(dt), int(u), int(g), float(w))
            for s, t, dt, u, g, w in _SWIFT_STEP.findall(text)]


def swift_errors(d, step):
    """per-particle relative error of SWIFT's accelerations against its exact sums at step"""
    sw = [f for f in os.listdir(d) if f.startswith(f"gravity_checks_swift_step{step:04d}")]
    a = np.loadtxt(os.path.join(d, sw[0]))
    b = np.loadtxt(os.path.join(d, f"gravity_checks_exact_step{step:04d}.dat"))
    a, b = a[np.argsort(a[:, 0])], b[np.argsort(b[:, 0])]
    if a.shape[0] != b.shape[0] or not np.array_equal(a[:, 0], b[:, 0]):
        sys.exit(f"error: {d}: SWIFT and exact check files of step {step} hold other particles")
    rel = np.linalg.norm(a[:, 4:7] - b[:, 4:7], axis=1) / np.linalg.norm(b[:, 4:7], axis=1)
    inter = a[:, 21:24].mean(axis=0)       # n_p2p, n_m2p, n_m2l per particle
    return rel, inter, sw[0]


T_END, NSTEPS = 1e-4, 16     # part A: SWIFT's tiny run; every particle active at every step


def swift_setup(args, d, state, eps, efmm):
    os.makedirs(d, exist_ok=True)
    box = args.swift_box
    ic = os.path.join(d, "ic.hdf5")
    write_swift_ic(ic, state["x"] + 0.5 * box, state["m"], 1, box)
    # (dt_max a little above t_end/nsteps: SWIFT rounds it down to a power-of-two fraction)
    swift_gravity_yml(os.path.join(d, "gravity.yml"), ic, eps, efmm, T_END,
                      1.01 * T_END / NSTEPS)
    swift_gravity_yml(os.path.join(d, "checks.yml"), ic, eps, efmm, T_END, 1.01 * T_END / 2)


def swift_timing(args, d, n, rnd):
    """one timed SWIFT run: mean and least wall time of its steps from step 2 on"""
    td = os.path.join(d, f"timing.{rnd}")
    shutil.rmtree(td, ignore_errors=True)
    run([args.swift, "--self-gravity", f"--threads={args.threads}", "-v", "1",
         os.path.join(d, "gravity.yml")], td, os.path.join(td, "stdout"))
    text = open(os.path.join(td, "stdout")).read()
    steps = [s for s in swift_steps(text) if s[0] >= 2]
    if not steps or any(s[4] != n for s in steps):
        print(f"warning: {td}: not every particle active at every step", flush=True)
    # one task report and one launch for the initial accelerations, then one per step
    grav = [float(g) for g in _SWIFT_GRAV.findall(text)][3:]
    launch = [float(g) for g in _SWIFT_LAUNCH.findall(text)][3:]
    if abs(len(grav) - len(steps)) > 1 or abs(len(launch) - len(steps)) > 1:
        print(f"warning: {td}: {len(grav)} task reports, {len(launch)} launches for "
              f"{len(steps)} steps", flush=True)
    return {"t": np.mean([s[5] for s in steps]) / 1e3, "tmin": min(s[5] for s in steps) / 1e3,
            "gpart": f"tasks {np.mean(launch):.1f} wall, gravity tasks {np.mean(grav):.1f} CPU",
            "prov": "SWIFT " + re.search(r"Config\. options: '([^']*)'", text).group(1)}


def swift_checks(args, d, n):
    """SWIFT's accelerations against its exact sums at step 1 (force-check build)"""
    cd = os.path.join(d, "checks")
    shutil.rmtree(cd, ignore_errors=True)     # SWIFT reuses an old exact file if present
    run([args.swift_checks, "--self-gravity", f"--threads={args.threads}",
         os.path.join(d, "checks.yml")], cd, os.path.join(cd, "stdout"))
    rel, inter, name = swift_errors(cd, 1)
    if len(rel) != n:
        print(f"warning: {cd}: {len(rel)} of {n} particles checked", flush=True)
    return {"rms": np.sqrt(np.mean(rel**2)), "p99": np.percentile(rel, 99), "max": rel.max(),
            "inter": f"{inter[0]:.0f} P2P + {inter[1]:.0f} M2P + {inter[2]:.0f} M2L"}

# ------------------------------------------------------------------ part A

def part_a(args, env):
    rows = []
    nan = float("nan")
    for name in args.states:
        state = evrard_ic(24) if name == "ic" else evrard_t06(args, env)
        n = len(state["id"])
        hmean = float(np.mean(state["h"]))
        print(f"part A, state {name}: N = {n}, t = {state['time']}, h mean {hmean:.5f} "
              f"median {np.median(state['h']):.5f} min {state['h'].min():.5f} "
              f"max {state['h'].max():.5f}", flush=True)
        d = os.path.join(args.outdir, f"A_{name}")
        sd = os.path.join(d, "sph")
        os.makedirs(sd, exist_ok=True)
        write_lammps_state(state, sd)
        fref = sph_reference(args, env, sd)
        # the rows: SPH-ASTRO per criterion, SWIFT per softening and tolerance
        jobs = [("sph", alpha, {"state": name, "n": n, "ts": [], "tmins": []})
                for alpha in args.relative]
        for eps, label in [(hmean, "mean h"), (hmean / M4_PHI0, "mean h / 1.4"),
                           (0.001, "example's")]:
            for efmm in args.epsilon_fmm:
                sw = os.path.join(d, f"swift_eps{eps:.5g}_fmm{efmm:g}")
                swift_setup(args, sw, state, eps, efmm)
                row = {"state": name, "n": n, "ts": [], "tmins": [], "code": "SWIFT",
                       "setting": f"FMM adaptive {efmm:g}, {args.threads} threads",
                       "soft": f"eps {eps:.4g} ({label})", "t": nan, "tmin": nan, "gpart": "",
                       "rms": nan, "p99": nan, "max": nan, "inter": ""}
                if args.swift_checks:
                    row.update(swift_checks(args, sw, n))
                jobs.append(("swift", sw, row))
        # timing rounds: every setting once per round, one after the other
        for rnd in range(args.repeats):
            for kind, what, row in jobs:
                if kind == "sph":
                    res = sph_gravity(args, env, sd, what, fref, rnd)
                elif args.swift:
                    res = swift_timing(args, what, n, rnd)
                else:
                    continue
                row["ts"].append(res.pop("t"))
                row["tmins"].append(res.pop("tmin"))
                if row["ts"][-1] == min(row["ts"]):      # the parts of the fastest round
                    row.update(res)
                else:
                    row.update({k: v for k, v in res.items() if k not in row})
        for kind, what, row in jobs:
            if row["ts"]:
                row["t"], row["tmin"] = min(row["ts"]), min(row["tmins"])
            rows.append(row)
            print(fmt_a(row), flush=True)
    return rows

HEAD_A = ("| state | N | code | setting | softening | ms per evaluation (wall; best round) | "
          "rounds | least | parts, ms | "
          "per-particle RMS | 99th pct | max | interactions per particle |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|")


def fmt_a(r):
    return (f"| {r['state']} | {r['n']} | {r['code']} | {r['setting']} | {r['soft']} | "
            f"{1e3 * r['t']:.1f} | {' '.join(f'{1e3 * t:.0f}' for t in r.get('ts', []))} | "
            f"{1e3 * r['tmin']:.1f} | {r['gpart']} | {r['rms']:.2e} | "
            f"{r['p99']:.2e} | {r['max']:.2e} | {r['inter']} |")


# ------------------------------------------------------------------ part B

def swift_evrard_ic(path, n, seed=4711):
    """SWIFT's EvrardCollapse_3D makeIC.py set-up, seeded: r = R sqrt(U), isotropic, box 100 R,
    sphere at its centre, h = 2 R / N^(1/3), u = 0.05, gas (PartType0)"""
    rng = np.random.default_rng(seed)
    r = np.sqrt(rng.random(n))
    phi = 2.0 * np.pi * rng.random(n)
    cos_t = 2.0 * rng.random(n) - 1.0
    sin_t = np.sqrt(1.0 - cos_t**2)
    x = np.column_stack([r * sin_t * np.cos(phi), r * sin_t * np.sin(phi), r * cos_t]) + 50.0
    write_swift_ic(path, x, np.full(n, 1.0 / n), 0, 100.0, h=np.full(n, 2.0 / n ** (1 / 3)),
                   u=np.full(n, 0.05))


def swift_evrard_yml(src, dst, ic, eps, tend, cfl=None, dt_max=None):
    text = open(src).read()
    if cfl is not None:
        text = re.sub(r"(CFL_condition:\s*)\S+", rf"\g<1>{cfl!r}", text)
    if dt_max is not None:
        text = re.sub(r"(dt_max:\s*)\S+", rf"\g<1>{dt_max!r}", text)
    text = re.sub(r"(time_end:\s*)\S+", rf"\g<1>{tend!r}", text)
    text = re.sub(r"(file_name:\s*)\S+", rf"\g<1>{ic}", text)
    text = re.sub(r"(max_physical_baryon_softening:\s*)\S+", rf"\g<1>{eps!r}", text)
    with open(dst, "w") as f:
        f.write(text)
    return text


def swift_statistics_energy(path):
    """relative energy error at the end from SWIFT's statistics.txt (E_kin + E_int + E_pot)"""
    cols = {}
    with open(path) as f:
        for line in f:
            m = re.match(r"#\s*\((\d+)\)\s+Total (kinetic|internal|potential) ", line)
            if m:
                cols[m.group(2)] = int(m.group(1))
    data = np.loadtxt(path, ndmin=2)
    e = sum(data[:, c] for c in cols.values())
    return data[-1, 1], (e[-1] - e[0]) / abs(e[0])


def part_b(args, env):
    rows = []
    src = os.path.join(args.swift_src, "examples", "HydroTests", "EvrardCollapse_3D",
                       "evrard.yml")
    for nc in args.sizes:
        ic = evrard_ic(nc)
        n, hmean = len(ic["id"]), float(np.mean(ic["h"]))
        d = os.path.join(args.outdir, f"B_n{nc}")
        sd = os.path.join(d, "sph")
        os.makedirs(sd, exist_ok=True)
        print(f"part B, n {nc}: N = {n}, mean h of SPH-ASTRO's ICs {hmean:.5f}", flush=True)
        wall = run(lmp_cmd(args, "-in", os.path.join(ROOT, "examples", "evrard", "in.evrard"),
                           "-var", "n", str(nc), "-var", "tend", str(args.tend), "-var",
                           "steps", "individual", "-var", "thermoevery", "50", "-var", "out",
                           "dump.evrard", "-log", "log.evrard", "-screen", "none"),
                   sd, os.path.join(sd, "stdout"), env)
        log = open(os.path.join(sd, "log.evrard")).read()
        loop = _LOOP.findall(log)[-1]
        m = re.search(r"^Evrard: t = (\S+) after (\d+) steps; relative energy error (\S+)",
                      log, re.M)
        upd = thermo_last(log, "v_updates")
        r = {"n": n, "code": "SPH-ASTRO", "setting": f"in.evrard -var n {nc}, individual "
             f"steps, tree, {args.np} ranks", "soft": "M4, per-particle h", "wall": wall,
             "loop": float(loop[0]), "steps": int(m.group(2)), "updates": upd,
             "t": float(m.group(1)), "eerr": float(m.group(3))}
        rows.append(r)
        print(fmt_b(r), flush=True)
        variants = [(0.001, "published 0.001", None, None),
                    (hmean, "mean h of SPH-ASTRO's ICs", None, None)]
        if args.matched:      # SPH-ASTRO's Courant number 0.3 and top step 0.05
            variants.append((hmean, "mean h of SPH-ASTRO's ICs", 0.3, 0.05))
        for eps, label, cfl, dt_max in variants:
            wd = os.path.join(d, f"swift_eps{eps:.5g}" + (f"_cfl{cfl:g}" if cfl else ""))
            shutil.rmtree(wd, ignore_errors=True)
            os.makedirs(wd)
            swift_evrard_ic(os.path.join(wd, "evrard.hdf5"), n)
            yml = swift_evrard_yml(src, os.path.join(wd, "evrard.yml"),
                                   os.path.join(wd, "evrard.hdf5"), eps, args.tend, cfl, dt_max)
            cfl_used = re.search(r"CFL_condition:\s*(\S+)", yml).group(1)
            dtmax_used = re.search(r"dt_max:\s*(\S+)", yml).group(1)
            wall = run([args.swift, "--hydro", "--self-gravity", "--limiter",
                        f"--threads={args.threads}", "evrard.yml"], wd,
                       os.path.join(wd, "stdout"))
            text = open(os.path.join(wd, "stdout")).read()
            steps = swift_steps(text)
            t_end, eerr = swift_statistics_energy(os.path.join(wd, "statistics.txt"))
            done = re.search(r"^\[(\d+\.\d+)\] main: done", text, re.M)
            r = {"n": n, "code": "SWIFT", "setting": f"EvrardCollapse_3D, CFL {cfl_used}, "
                 f"dt_max {dtmax_used}{'' if cfl is None else ' (as SPH-ASTRO)'}, "
                 f"{args.threads} threads", "soft": f"eps {eps:.4g} ({label})", "wall": wall,
                 "loop": float(done.group(1)) if done else float("nan"),
                 "steps": steps[-1][0], "updates": sum(s[3] for s in steps), "t": t_end,
                 "eerr": eerr}
            rows.append(r)
            print(fmt_b(r), flush=True)
    return rows


def thermo_last(log, column):
    """the last value of a thermo column of the last run in a LAMMPS log"""
    lines = log.splitlines()
    for i in range(len(lines) - 1, -1, -1):
        words = lines[i].split()
        if words[:1] == ["Step"] and column in words:
            k, last = words.index(column), None
            for line in lines[i + 1:]:
                if line.startswith("Loop time"):
                    break
                parts = line.split()
                if len(parts) == len(words) and re.match(r"^-?\d", parts[0]):
                    last = parts
            return float(last[k]) if last else float("nan")
    return float("nan")

HEAD_B = ("| N | code | setting | softening | wall s (around the run) | code's own s | steps | "
          "particle updates | t end | relative energy error |\n"
          "|---|---|---|---|---|---|---|---|---|---|")


def fmt_b(r):
    return (f"| {r['n']} | {r['code']} | {r['setting']} | {r['soft']} | {r['wall']:.1f} | "
            f"{r['loop']:.1f} | {r['steps']} | {r['updates']:.4g} | {r['t']:.4g} | "
            f"{r['eerr']:.2e} |")


# ------------------------------------------------------------------ main

def plugin_stamp(env):
    """modification times of the plugins LAMMPS will load (a rebuild during the run shows)"""
    out = []
    for d in env.get("LAMMPS_PLUGIN_PATH", "").split(":"):
        so = os.path.join(d, "sphastroplugin.so")
        if d and os.path.exists(so):
            out.append((so, os.path.getmtime(so)))
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--swift", help="SWIFT executable (timing build)")
    p.add_argument("--swift-checks", help="SWIFT built with --enable-gravity-force-checks=1")
    p.add_argument("--swift-src", help="SWIFT source tree (default: the directory of --swift)")
    p.add_argument("--outdir", default=os.path.join(ROOT, "build", "output",
                                                    "compare_swift_gravity"))
    p.add_argument("--part", default="all", choices=["A", "B", "all"])
    p.add_argument("--states", default="ic,t0.6", help="part A: ic and/or t0.6")
    p.add_argument("--relative", default="0.002", help="part A: tree relative criteria")
    p.add_argument("--epsilon-fmm", default="0.001",
                   help="part A: SWIFT's adaptive-MAC tolerances (its example: 0.001)")
    p.add_argument("--np", type=int, default=2, help="MPI ranks of SPH-ASTRO")
    p.add_argument("--threads", type=int, default=2, help="threads of SWIFT")
    p.add_argument("--evals", type=int, default=10, help="part A: timed SPH-ASTRO evaluations")
    p.add_argument("--repeats", type=int, default=3,
                   help="part A: timing rounds (every setting once per round; least mean kept)")
    p.add_argument("--swift-box", type=float, default=100.0,
                   help="part A: side of SWIFT's box around the sphere (its example's 100)")
    p.add_argument("--sizes", default="16,24", help="part B: in.evrard -var n values")
    p.add_argument("--tend", type=float, default=0.8, help="part B: end time")
    p.add_argument("--matched", action="store_true",
                   help="part B: also SWIFT with CFL 0.3 and dt_max 0.05, SPH-ASTRO's Courant "
                   "number and top step (softening: the mean h)")
    args = p.parse_args()
    if not args.swift and not args.swift_checks:
        p.error("give --swift (and/or --swift-checks for part A's errors)")
    for k in ("swift", "swift_checks"):
        if getattr(args, k):
            setattr(args, k, os.path.abspath(getattr(args, k)))
    args.swift_src = os.path.abspath(args.swift_src or os.path.dirname(args.swift or
                                                                        args.swift_checks))
    args.states = [s for s in args.states.split(",") if s]
    args.relative = [float(a) for a in args.relative.split(",") if a]
    args.epsilon_fmm = [float(a) for a in args.epsilon_fmm.split(",") if a]
    args.sizes = [int(s) for s in args.sizes.split(",") if s]
    args.outdir = os.path.abspath(args.outdir)
    os.makedirs(args.outdir, exist_ok=True)
    env = lammps_environment()
    plugin_at_start = plugin_stamp(env)
    out = [f"load average at the start: {os.getloadavg()[0]:.2f}"]
    if args.part in ("A", "all"):
        rows = part_a(args, env)
        out += ["", "Part A: one full gravity evaluation of the Evrard sphere", "", HEAD_A]
        out += [fmt_a(r) for r in rows]
        prov = [r["prov"] for r in rows if "prov" in r]
        out += [""] + [f"provenance: {p_}" for p_ in dict.fromkeys(prov)]
    if args.part in ("B", "all"):
        if not args.swift:
            p.error("part B needs --swift")
        rows = part_b(args, env)
        out += ["", f"Part B: Evrard collapse to t = {args.tend}", "", HEAD_B]
        out += [fmt_b(r) for r in rows]
    out.append(f"load average at the end: {os.getloadavg()[0]:.2f}")
    if plugin_stamp(env) != plugin_at_start:
        out.append("WARNING: the plugin on LAMMPS_PLUGIN_PATH changed during the run (rebuilt?): "
                   "the SPH-ASTRO rows may come from different builds")
    text = "\n".join(out) + "\n"
    with open(os.path.join(args.outdir, "table.md"), "w") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
