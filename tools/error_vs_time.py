#!/usr/bin/env python3
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
"""Accuracy versus cost: run an SPH-ASTRO test scene at several resolutions and plot its L1
errors against the wall time of each run.

Usage (from the repository root; python3 of build/venv, on PATH after source build/env.sh)::

    python3 tools/error_vs_time.py sod [--resolutions 32,48,64,96,128] [--np 1]
        [--outdir build/output/error_vs_time] [--variants 'hfact=1.2;hfact=1.5']

For each variant and resolution the scene's LAMMPS input is run once (``-log``/``-screen
none``, ``-var RESVAR RES``, ``-var OUTVAR DUMP`` plus the variant's ``-var`` settings); the wall
time is measured around the ``lmp`` (or ``mpirun``) call, the particle count N and the number of
steps are read from the log's ``Loop time of T on P procs for S steps with N atoms`` lines, and
the scene's analysis function turns the final dump into L1 errors.  Output in OUTDIR:

* ``SCENE_table.txt`` -- one block per variant with the columns
  ``res N steps wall_s loop_s particle_steps_per_s L1_...`` (also printed);
* ``SCENE_error_vs_time.png`` -- log-log L1 errors against wall seconds, one panel per plotted
  quantity, one curve per variant, each marker labelled with N;
* ``runs/...`` -- the logs and dumps of the single runs (``--reuse`` re-analyses them
  instead of running again when the command is unchanged).

The convergence order printed is the least-squares slope ``-d log L1 / d log RES``, i.e. with
respect to the linear resolution RES (the scene's resolution variable, e.g. nx for Sod).  It is
also given with respect to N (``L1 ~ N^-q``): for 3D scenes ``N ~ RES^3`` and ``q = p/3``, i.e.
``p`` is the order against ``N^(1/3)``; the quasi-1D Sod tube keeps its cross-section fixed in
lattice cells, so there ``N ~ nx`` and ``q = p``.

Further scenes are added as entries of :data:`SCENES` (name -> :class:`Scene`: input file,
resolution variable, dump variable, default resolutions, analysis function, error columns).

``--variants physics`` runs the scene's own set of physics variants (Sod: fixed h with hfact
1.5, variable h, variable h with the Morris-Monaghan or the Cullen-Dehnen switch, and the
signal-velocity viscosity with Cullen-Dehnen, and the viscosity on reconstructed velocities;
Sedov: constant alpha, both switches and the reconstruction; Noh: constant alpha, both
switches, the signal viscosity, artificial conductivity, the signal viscosity with
Cullen-Dehnen and conductivity, the reconstruction alone and with the Morris-Monaghan switch
and conductivity).

Variants: ``--variants`` takes ``;``-separated variants, each a ``,``-separated list of
``name=value`` LAMMPS variable settings, e.g. ``'hfact=1.2;hfact=1.5,kernel=m6'``; every variant
is run at every resolution and drawn as its own curve.  ``--var name=value`` (repeatable) applies
to all runs.
"""

import argparse
import dataclasses
import hashlib
import os
import re
import subprocess
import sys
import time
from typing import Callable, Dict, Sequence, Tuple

import numpy as np

from sphastro.dump import read_last_frame
from sphastro.runs import provenance, lammps_environment
from sphastro.sod import sod_errors

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir))


# --------------------------------------------------------------------------------------------
# scenes


@dataclasses.dataclass
class Preset:
    """A comparison run by ``--preset NAME``: resolutions, MPI ranks, variables for all runs,
    variants, and the other code's published points ``(N, wall s, error of the fit key)``,
    drawn as a dashed curve in the panel of the fit key and listed under the table."""
    resolutions: Sequence[int]
    np: int
    var: Sequence[str]
    variants: str
    reference_label: str
    reference: Sequence[Tuple[int, float, float]]
    notes: str = ""
    # variants run only at the resolutions up to this one (slow solvers), unless
    # --resolutions is given
    max_resolution: Dict[str, int] = dataclasses.field(default_factory=dict)


@dataclasses.dataclass
class Scene:
    """A test scene with a known solution.

    input : LAMMPS input, relative to the repository root.
    res_var : name of the LAMMPS variable setting the (linear) resolution.
    out_var : name of the LAMMPS variable giving the path of the final dump.
    default_res : resolutions run when --resolutions is not given.
    analyse : ``f(dump_path, run) -> {error key: value}``; ``run`` is the :class:`Run`
        (resolution, variables, log figures) for scenes that need them.
    errors : ``(key, column label)`` of the errors, in table order.
    plot : keys of ``errors`` drawn against wall time (one panel each).
    fit : key whose convergence order is fitted.
    notes : one line printed under the table.
    physics : the variants of ``--variants physics`` (smoothing-length modes, switches).
    presets : named comparisons for ``--preset NAME``: a :class:`Preset` each.
    """
    input: str
    res_var: str
    out_var: str
    default_res: Sequence[int]
    analyse: Callable
    errors: Sequence[Tuple[str, str]]
    plot: Sequence[str]
    fit: str
    notes: str = ""
    physics: str = ""
    presets: Dict[str, Preset] = dataclasses.field(default_factory=dict)


def analyse_sod(dump_path, run):
    """L1 errors of the periodic Sod tube (examples/sod/in.sod) against the exact solution."""
    frame = read_last_frame(dump_path)
    gamma = float(run.vars.get("gamma", 5.0 / 3.0))
    t = frame.time if frame.time is not None else float(run.vars.get("tend", 0.2))
    err = sod_errors(frame, gamma, t, left=(1.0, 0.0, 1.0), right=(0.125, 0.0, 0.1), x0=0.0,
                     xrange=(-0.5, 0.5), x_periodic=tuple(frame.box[0]))
    return {"rho": err["rho"], "vx": err["vx"], "p": err["p"], "u": err["u"],
            "n_measured": err["n"]}


def analyse_gresho(dump_path, run):
    """L1 of v_phi (and v_r, P, rho) of the Gresho-Chan vortex (examples/gresho/in.gresho) over
    r < 0.5 against the steady vortex; errors by examples/gresho/analyse.py."""
    from sphastro.gresho import gresho_errors
    err = gresho_errors(read_last_frame(dump_path), rmax=0.5)
    return {"vphi": err["vphi"], "vr": err["vr"], "p": err["p"], "rho": err["rho"],
            "n_measured": err["n"]}


def analyse_sedov(dump_path, run):
    """Sedov-Taylor blast (examples/sedov/in.sedov) against the self-similar solution: L1 of
    rho, v_r, P over r < 1.2 R_s, |relative error| of the shock radius from the binned density
    peak (headline) and from the jump's half height, the binned peak density, and from the log
    the |relative energy error| and the particles held at the h cap."""
    from sphastro import sedov
    from sphastro.runs import parse_sph_log
    frame = read_last_frame(dump_path)
    t = frame.time if frame.time is not None else float(run.vars.get("tend", 0.1))
    err = sedov.sedov_errors(frame, t, E=float(run.vars.get("E", 1.0)))
    log = parse_sph_log(os.path.join(os.path.dirname(dump_path), "log.lammps"), loops="sum")
    return {"rho": err["rho"], "vr": err["v"], "p": err["p"],
            "rshock": abs(err["err_r_peak"]), "rhalf": abs(err["err_r_half"]),
            "peak": err["rho_peak"], "energy": abs(log["energy"]), "capped": log["capped"],
            "n_measured": err["n"]}


def analyse_toystar(dump_path, run):
    """Toy star (examples/toystar/in.toystar) against its equilibrium rho(r): L1(rho)/rho_c and the
    |relative error| of the fitted radius R_fit after the damped relaxation (DUMP.relaxed), their
    drift over the undamped continuation (DUMP), and from the log the largest kinetic energy
    of the continuation over the thermal energy and its |relative energy error|."""
    from sphastro import toystar
    M, R = float(run.vars.get("M", 2.0)), float(run.vars.get("R", 0.75))
    k, n = float(run.vars.get("k", 0.1)), float(run.vars.get("npoly", 1.0))
    e1 = toystar.toystar_errors(read_last_frame(dump_path + ".relaxed"), M, R, k, n)
    e2 = toystar.toystar_errors(read_last_frame(dump_path), M, R, k, n)
    log = toystar.parse_log(os.path.join(os.path.dirname(dump_path), "log.lammps"))
    return {"l1": e1["l1_rel"], "rfit": abs(e1["err_r_fit"]), "rrms": abs(e1["err_r_rms"]),
            "rhoc": abs(e1["rho_c_sph"] / e1["rho_c"] - 1.0),
            "drift_l1": abs(e2["l1_rel"] - e1["l1_rel"]), "drift_r": abs(e2["r_fit"] - e1["r_fit"]) / R,
            "ekin": log["ekin_free_max"] / log["eth_relaxed"], "energy": abs(log["energy"]),
            "n_measured": e1["n"]}


def analyse_evrard(dump_path, run):
    """Evrard collapse (examples/evrard/in.evrard): from the log, the largest |relative total
    energy error| over the run's thermo rows and (individual steps) over its synchronisation
    points (fix sph/astro's end-of-run line; global steps: the thermo rows'), the minimum of the potential energy W (maximum compression) and
    its time, and K, U, W at t = 0.8 and 3 (examples/evrard/analyse.py)."""
    from sphastro import evrard as module
    log = os.path.join(os.path.dirname(dump_path), "log.lammps")
    rows, _ = module.read_log(log)
    sync, _ = module.read_sync_energy(log)
    K, U, W, ERR = "c_sum[8]", "c_sum[9]", "c_sum[10]", "c_sum[12]"
    rmin = min(rows, key=lambda r: r[W])
    energy = max(abs(r[ERR]) for r in rows)
    out = {"energy": energy, "energy_sync": energy if sync is None else sync,
           "wmin": -rmin[W], "tmin": rmin["Time"], "n_measured": len(rows)}
    for t, tag in ((0.8, "08"), (3.0, "3")):
        out["W" + tag] = -(module.at_time(rows, t, W) or float("nan"))
        out["U" + tag] = module.at_time(rows, t, U) or float("nan")
    return out


def analyse_noh(dump_path, run):
    """Noh implosion (examples/noh/in.noh) against the exact solution, with the measures of
    examples/noh/analyse.py: |relative error| of the post-shock density (mean over
    0.25-0.75 R_s, headline) and of the shock radius (binned rho through half the measured
    post-shock value), L1(rho)/64 over r < 1.5 R_s, the wall heating (mean u over r < 0.25 R_s
    / 0.5), the smallest u, and from the log the |relative energy error| and the largest
    number of particles at the h cap (every step, else at the thermo lines)."""
    import math
    from sphastro import noh as module
    frame = read_last_frame(dump_path)
    t = frame.time if frame.time is not None else float(run.vars.get("tend", 0.6))
    res, _ = module.noh_measures(frame, t, u0=float(run.vars.get("u0", 1e-6)))
    log = module.parse_log(os.path.join(os.path.dirname(dump_path), "log.lammps"))
    capped = log["capped_steps"] if math.isfinite(log["capped_steps"]) else log["capped_max"]
    return {"rhopost": abs(res["err_rho_post"]), "rshock": abs(res["err_r_shock"]),
            "l1rho": res["l1rho"], "wallheat": res["wallheat"], "umin": res["umin"],
            "energy": abs(log["energy"]), "capped": capped, "n_measured": res["n_window"]}


def analyse_kelvin_helmholtz(dump_path, run):
    """Kelvin-Helmholtz (examples/kelvin_helmholtz/in.kelvin_helmholtz): the mode amplitude M(t)
    of McNally et al. (2012) from the log's thermo column v_M against the converged grid reference
    (examples/kelvin_helmholtz/kh_grid_reference.txt, sphastro.kh_grid) over t in [0, 2]
    (examples/kelvin_helmholtz/analyse.py): mean and largest |M / M_ref - 1|, the growth to
    t = 2 over the reference's, M(1), M(2), the growth rate fitted over [0.5, 1] and the largest
    |relative energy error|."""
    import importlib.util
    here = os.path.join(ROOT, "examples", "kelvin_helmholtz")
    spec = importlib.util.spec_from_file_location("kh_analyse", os.path.join(here, "analyse.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    ref = module.grid_reference()
    thermo = module.read_thermo(os.path.join(os.path.dirname(dump_path), "log.lammps"))
    r = module.measures(thermo, ref, tcmp=2.0)
    return {"mrel": r["l1"], "mmax": r["maxrel"], "mgrowth": r["growth"], "M1": r["M1"],
            "M2": r["M2"], "rate": r["rate"], "energy": r["energy"],
            "n_measured": len(thermo["Time"])}


SCENES: Dict[str, Scene] = {
    "evrard": Scene(
        input="examples/evrard/in.evrard", res_var="n", out_var="out",
        default_res=(6, 8, 12), analyse=analyse_evrard,
        errors=(("energy", "dE_max"), ("energy_sync", "dE_sync"), ("wmin", "-W_min"),
                ("tmin", "t_Wmin"), ("W08", "-W(0.8)"), ("U08", "U(0.8)"), ("W3", "-W(3)"),
                ("U3", "U(3)")),
        plot=("energy", "wmin"), fit="energy",
        notes="Evrard collapse, 3D, to t = 3: N ~ 2.1 n^3; dE_max: largest |relative total-energy "
              "error| over the run; dE_sync: the same at the synchronisation points (individual "
              "steps; with global steps every step is one); -W_min: depth of the potential "
              "energy at maximum compression (no exact value: watch it converge with N)",
        presets={"steps": Preset(
            resolutions=(6, 8, 12), np=2, var=(),
            variants="steps=global;steps=individual;steps=individual,kicks=particle",
            reference_label="no peer code run", reference=(),
            notes="Evrard collapse with global and individual timesteps (pair kicks, the "
                  "default, and particle kicks), 2 MPI ranks"),
            "gravity": Preset(
            resolutions=(8, 12, 16), np=2, var=("steps=individual", "thermoevery=50"),
            variants="gravity=tree;gravity=direct;gravity=msm,hmax=0.35",
            reference_label="no peer code run", reference=(),
            max_resolution={"gravity=msm,hmax=0.35": 8},
            notes="Evrard collapse to t = 3 with individual steps and each self-gravity solver: "
                  "the tree (relative 0.002), direct summation, MSM 1e-5 (its short-range "
                  "cutoff bounds h: hmax 0.35; n 8 only: MSM computes every particle at every "
                  "step on a grid that grows to 64^3 as the halo expands, n 12 takes over 15 "
                  "minutes), 2 MPI ranks")}),

    "sod": Scene(
        input="examples/sod/in.sod", res_var="nx", out_var="out",
        default_res=(32, 48, 64, 96, 128), analyse=analyse_sod,
        errors=(("rho", "L1_rho"), ("vx", "L1_vx"), ("p", "L1_P"), ("u", "L1_u")),
        plot=("rho", "vx", "p"), fit="rho",
        notes="Sod: ny cells across y,z are fixed, so N ~ nx (quasi-1D); errors over |x| < 0.5",
        physics="hmode=fixed,hfact=1.5;hmode=iterate;hmode=iterate,switch=mm;"
                "hmode=iterate,switch=cd;hmode=iterate,visc=signal,switch=cd;"
                "hmode=iterate,recon=yes",
        presets={"phantom": Preset(
            # Phantom's 3D Sod (Price et al. 2018, PASA 35, e031; gamma 5/3, quintic kernel,
            # 2 OpenMP threads, L1(rho) per particle over |x| < 0.5); ny 8 and these nx give
            # its exact particle counts (4 x 8^2 x nx left, an eighth of that right)
            resolutions=(57, 129, 273), np=2, var=("ny=8", "switch=cd"),
            # the third: Wendland C4 at hfact 1.6 with Courant 0.6, margin 1.4 and skin 1.0
            # (examples/sod/README.md)
            variants="kernel=m4,hfact=1.2;kernel=m6,hfact=1.0;"
                     "kernel=wendland/c4,hfact=1.6,courant=0.6,margin=1.4,skin=1.0",
            reference_label="Phantom (2 OpenMP threads)",
            reference=((16416, 44.0, 1.56e-2), (37152, 131.0, 7.46e-3), (78624, 536.0, 3.85e-3)),
            notes="Phantom's particle counts, variable h + Cullen-Dehnen switch, 2 MPI ranks")}),
    "gresho": Scene(
        input="examples/gresho/in.gresho", res_var="n", out_var="out",
        default_res=(32, 64, 128), analyse=analyse_gresho,
        errors=(("vphi", "L1_vphi"), ("vr", "L1_vr"), ("p", "L1_P"), ("rho", "L1_rho")),
        plot=("vphi", "p"), fit="vphi",
        notes="Gresho-Chan vortex, 2D, t = 1: N ~ 1.15 n^2; errors over r < 0.5; e.g. "
              "--variants 'visc=constant;visc=switch' --var kernel=wendland/c4 --var hfact=2.0",
        physics="visc=constant;visc=switch,swform=morris-monaghan;"
                "visc=switch,swform=cullen-dehnen"),
    "sedov": Scene(
        input="examples/sedov/in.sedov", res_var="n", out_var="out",
        default_res=(12, 16, 20), analyse=analyse_sedov,
        errors=(("rho", "L1_rho"), ("vr", "L1_vr"), ("p", "L1_P"), ("rshock", "Rs_err_peak"),
                ("rhalf", "Rs_err_half"), ("peak", "rho_peak"), ("energy", "dE_rel"),
                ("capped", "h_capped")),
        plot=("rho", "rshock"), fit="rho",
        notes="Sedov-Taylor, 3D, t = 0.1: N = 4 n^3; L1 over r < 1.2 R_s; Rs_err: |relative "
              "error| of the shock radius (binned density peak; half height of the jump)",
        physics="switch=no;switch=mm;switch=cd;recon=yes",
        presets={"steps": Preset(
            # global against individual timesteps (fix sph/astro steps individual), 2 ranks;
            # SWIFT's Sedov (SPHENIX, cubic spline, --hydro --limiter, 2 threads) measured by
            # tools/benchmark_scenes.py in one script with SPH-ASTRO's rows (the script of
            # doc/validation.md's table, not this run: compare its times with that table's),
            # its L1(rho) by tools/swift_sedov_errors.py on its t = 0.1 snapshot
            resolutions=(12, 16, 22), np=2, var=(),
            variants="steps=global;steps=individual;steps=individual,limiter=1;"
                     "steps=individual,kicks=particle",
            reference_label="SWIFT (2 threads)",
            reference=((42875, 8.9, 0.448), (175616, 47.1, 0.398)),
            notes="Sedov with global and individual timesteps (the defaults: pair kicks, a "
                  "limiter of 2 levels; a limiter of 1 level; particle kicks, whose default "
                  "limiter is 1 level), 2 MPI ranks")}),
    "toystar": Scene(
        input="examples/toystar/in.toystar", res_var="n", out_var="out",
        default_res=(8, 12, 16), analyse=analyse_toystar,
        errors=(("l1", "L1_rho/rho_c"), ("rfit", "R_fit_err"), ("rrms", "R_rms_err"),
                ("rhoc", "rho_c_err"), ("drift_l1", "dL1_free"), ("drift_r", "dR_free"),
                ("ekin", "Ekin/Eth_free"), ("energy", "dE_free")),
        plot=("l1", "rfit"), fit="l1",
        notes="toy star, 3D, n = 1: N ~ 2.1 n^3; damped to t = 12, then undamped "
              "to t = 18; L1 over all particles; R_fit: radius of the fitted rho^(1/n) = "
              "A (R^2 - r^2); *_free: drift/largest values over the undamped continuation"),
    "kelvin_helmholtz": Scene(
        input="examples/kelvin_helmholtz/in.kelvin_helmholtz", res_var="n", out_var="out",
        default_res=(32, 64, 128), analyse=analyse_kelvin_helmholtz,
        errors=(("mrel", "L1_M/M_ref"), ("mmax", "max_M/M_ref"), ("mgrowth", "growth/ref"),
                ("M1", "M(1)"), ("M2", "M(2)"), ("rate", "rate"), ("energy", "dE_max")),
        plot=("mrel", "mgrowth"), fit="mrel",
        notes="Kelvin-Helmholtz (McNally et al. 2012), 2D, to t = 2: N ~ 1.74 n^2; L1_M/M_ref: "
              "mean |M/M_ref - 1| over t in [0, 2] against the converged grid solution "
              "(sphastro.kh_grid, 1024^2: M(2) = 0.234); growth/ref: M(2)/M(0) over the "
              "reference's; rate: d ln M/dt over [0.5, 1]",
        physics="switch=none;cond=1.0;switch=cd,cond=1.0",
        presets={"mcnally": Preset(
            # the three dissipation variants at three resolutions, 1 MPI rank (2 ranks on the
            # shared 2-core machine ran 8x slower); the input finds kh_setup.py through root
            resolutions=(32, 64, 128), np=1, var=(f"root={ROOT}",),
            variants="switch=none;cond=1.0;switch=cd,cond=1.0",
            reference_label="no peer code run", reference=(),
            notes="McNally et al. (2012) Kelvin-Helmholtz: classic viscosity, + artificial "
                  "conductivity, Cullen-Dehnen switch + conductivity; 1 MPI rank")}),
    "noh": Scene(
        input="examples/noh/in.noh", res_var="n", out_var="out",
        default_res=(8, 12, 16), analyse=analyse_noh,
        errors=(("rhopost", "rho_post_err"), ("rshock", "R_s_err"), ("l1rho", "L1_rho/64"),
                ("wallheat", "u_centre/0.5"), ("umin", "u_min"), ("energy", "dE_rel"),
                ("capped", "h_capped")),
        plot=("rhopost", "rshock"), fit="rhopost",
        notes="Noh implosion, 3D, t = 0.6: N ~ 16.8 n^3; rho_post_err: |mean rho over "
              "0.05 < r < 0.15 / 64 - 1|; R_s_err: |shock radius / 0.2 - 1| (half the measured "
              "post-shock density); u_centre: mean u over r < 0.05",
        physics="switch=no;switch=mm;switch=cd;visc=signal;cond=1.0;"
                "visc=signal,switch=cd,cond=1.0;recon=yes;recon=yes,switch=mm,cond=1.0"),
}


# --------------------------------------------------------------------------------------------
# running


@dataclasses.dataclass
class Run:
    scene: str
    variant: str
    res: int
    vars: Dict[str, str]
    workdir: str
    wall_s: float = float("nan")
    loop_s: float = float("nan")
    steps: int = 0
    natoms: int = 0
    procs: int = 0
    mem_mb: float = float("nan")
    errors: Dict[str, float] = dataclasses.field(default_factory=dict)
    reused: bool = False


_LOOP = re.compile(r"^Loop time of (\S+) on (\d+) procs for (\d+) steps with (\d+) atoms", re.M)
_MEM = re.compile(r"^Per MPI rank memory allocation \(min/avg/max\) = (\S+) \| (\S+) \| (\S+)",
                  re.M)


def parse_log(path):
    """Return (loop seconds summed, steps summed, atoms of the last run, procs, max MB/rank)."""
    with open(path, encoding="utf-8", errors="replace") as f:
        text = f.read()
    loops = _LOOP.findall(text)
    if not loops:
        raise RuntimeError(f"{path}: no 'Loop time' line (did the run fail?)")
    mem = _MEM.findall(text)
    return (sum(float(t) for t, _, _, _ in loops), sum(int(s) for _, _, s, _ in loops),
            int(loops[-1][3]), int(loops[-1][1]),
            max(float(m[2]) for m in mem) if mem else float("nan"))






def lmp_command(nproc, lmp="lmp"):
    return [lmp] if nproc == 1 else ["mpirun", "-np", str(nproc), lmp]


def run_one(scene, run, nproc, env, lmp="lmp", reuse=False):
    """Run (or with ``reuse``, re-analyse an earlier identical run of) one resolution.

    LAMMPS reads its input while it runs, so the scene's input is copied into the run
    directory first and run from there: edits to the input during a run cannot corrupt it,
    and the copy records what was run.  (Inputs that ``include`` files by relative path
    would need those files next to the copy.)
    """
    os.makedirs(run.workdir, exist_ok=True)
    dump = os.path.join(run.workdir, "dump.final")
    log = os.path.join(run.workdir, "log.lammps")
    done = os.path.join(run.workdir, "command_wall.txt")
    source = os.path.join(ROOT, scene.input)
    with open(source, "rb") as f:
        text = f.read()
    digest = hashlib.sha256(text).hexdigest()
    args = ["-log", log, "-screen", "none", "-var", scene.res_var, str(run.res),
            "-var", scene.out_var, dump]
    for name, value in run.vars.items():
        args += ["-var", name, value]
    # the command as the user would type it: the key under which --reuse finds a run
    command = " ".join(lmp_command(nproc, lmp) + ["-in", source] + args)
    previous = None
    if reuse and os.path.exists(done) and os.path.exists(dump) and os.path.exists(log):
        with open(done, encoding="utf-8") as f:
            lines = f.read().splitlines()
        if (len(lines) >= 2 and lines[0] == command
                and (len(lines) < 3 or lines[2] == f"input sha256 {digest}")):
            previous = float(lines[1])
    if previous is not None:
        run.wall_s = previous
        run.reused = True
    else:
        if os.path.exists(done):
            os.remove(done)
        copy = os.path.join(run.workdir, os.path.basename(scene.input))
        with open(copy, "wb") as f:
            f.write(text)
        cmd = lmp_command(nproc, lmp) + ["-in", copy] + args
        start = time.perf_counter()
        proc = subprocess.run(cmd, cwd=run.workdir, env=env, stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT)
        run.wall_s = time.perf_counter() - start
        if proc.returncode != 0:
            tail = proc.stdout.decode(errors="replace")[-2000:]
            raise RuntimeError(f"{' '.join(cmd)} failed (exit {proc.returncode}); see {log}\n"
                               f"{tail}")
        with open(done, "w", encoding="utf-8") as f:
            f.write(f"{command}\n{run.wall_s!r}\ninput sha256 {digest}\n")
    run.loop_s, run.steps, run.natoms, run.procs, run.mem_mb = parse_log(log)
    run.errors = scene.analyse(dump, run)
    return run


# --------------------------------------------------------------------------------------------
# output


def parse_variants(text):
    """'a=1,b=2;a=3' -> [('a=1,b=2', {'a': '1', 'b': '2'}), ('a=3', {'a': '3'})]."""
    if not text:
        return [("default", {})]
    variants = []
    for item in text.split(";"):
        item = item.strip()
        if not item:
            continue
        settings = parse_settings(item.replace(",", " ").split())
        variants.append((",".join(f"{k}={v}" for k, v in settings.items()), settings))
    return variants or [("default", {})]


def parse_settings(items):
    settings = {}
    for item in items:
        if "=" not in item:
            raise argparse.ArgumentTypeError(f"expected name=value, got {item!r}")
        name, value = item.split("=", 1)
        settings[name.strip()] = value.strip()
    return settings


def fit_slope(x, y):
    """Least-squares slope of log y against log x (nan with fewer than two points)."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    ok = (x > 0) & (y > 0) & np.isfinite(x) & np.isfinite(y)
    if np.count_nonzero(ok) < 2:
        return float("nan")
    return float(np.polyfit(np.log(x[ok]), np.log(y[ok]), 1)[0])


def format_table(scene_name, scene, runs_by_variant, nproc):
    cols = ["res", "N", "steps", "wall_s", "loop_s", "particle_steps_per_s"]
    cols += [label for _, label in scene.errors]
    widths = [max(len(c), 11) for c in cols]
    lines = [f"# {scene_name}: {scene.input}, resolution variable {scene.res_var}, "
             f"{nproc} MPI rank(s)",
             "# wall_s: wall time around the lmp call (start-up, set-up, run, dump); loop_s: "
             "LAMMPS' Loop time; particle_steps_per_s = N steps / wall_s"]
    if scene.notes:
        lines.append(f"# {scene.notes}")
    first = next(iter(runs_by_variant.values()))
    if first:
        lines.append(f"# {provenance(os.path.join(first[0].workdir, 'log.lammps'))}")
    summary = []
    for variant, runs in runs_by_variant.items():
        lines.append(f"# variant: {variant}")
        lines.append("  ".join(c.rjust(w) for c, w in zip(cols, widths)))
        for r in runs:
            vals = [str(r.res), str(r.natoms), str(r.steps), f"{r.wall_s:.3f}", f"{r.loop_s:.3f}",
                    f"{r.natoms * r.steps / r.wall_s:.4g}"]
            vals += [f"{r.errors[key]:.4e}" for key, _ in scene.errors]
            lines.append("  ".join(v.rjust(w) for v, w in zip(vals, widths)))
        res = [r.res for r in runs]
        err = [r.errors[scene.fit] for r in runs]
        p = -fit_slope(res, err)
        s_n = fit_slope([r.natoms for r in runs], err)
        k = fit_slope(res, [r.natoms for r in runs])
        s_w = fit_slope([r.wall_s for r in runs], err)
        label = dict(scene.errors)[scene.fit]
        summary.append(f"# {variant}: {label} ~ {scene.res_var}^-p with p = {p:.2f} "
                       f"(convergence order vs linear resolution); N ~ {scene.res_var}^{k:.2f}, "
                       f"{label} ~ N^({s_n:.2f}); {label} ~ wall_s^({s_w:.2f})")
        if len(runs) >= 3:
            p_hi = -fit_slope(res[-2:], err[-2:])
            summary.append(f"#   order from the two finest resolutions: p = {p_hi:.2f}")
    return "\n".join(lines + summary) + "\n"


def plot(scene_name, scene, runs_by_variant, png_path, nproc, preset=None):
    from matplotlib.figure import Figure     # no pyplot: no GUI backend, no global state

    labels = {"rho": r"$L_1(\rho)$", "vx": r"$L_1(v_x)$", "p": r"$L_1(P)$", "u": r"$L_1(u)$",
              "vphi": r"$L_1(v_\phi)$", "vr": r"$L_1(v_r)$",
              "rshock": r"$|R_{peak} - R_s| / R_s$", "l1": r"$L_1(\rho) / \rho_c$",
              "rfit": r"$|R_{fit} - R| / R$", "rhopost": r"$|\rho_{post} / 64 - 1|$",
              "mrel": r"mean $|M / M_{lin} - 1|$, $t \leq 1$", "mgrowth": r"$M$ growth / linear"}
    fig = Figure(figsize=(4.2 * len(scene.plot), 4.2))
    axes = fig.subplots(1, len(scene.plot), squeeze=False)[0]
    markers = "osD^v<>px"
    for ax, key in zip(axes, scene.plot):
        for k, (variant, runs) in enumerate(runs_by_variant.items()):
            t = [r.wall_s for r in runs]
            e = [r.errors[key] for r in runs]
            ax.loglog(t, e, "-" + markers[k % len(markers)], label=variant, ms=5)
            for r in runs:
                ax.annotate(f"N={r.natoms}", (r.wall_s, r.errors[key]), fontsize=7,
                            textcoords="offset points", xytext=(4, 3))
        if preset is not None and key == scene.fit:
            ax.loglog([p[1] for p in preset.reference], [p[2] for p in preset.reference], "--k",
                      marker="x", label=preset.reference_label, ms=6)
            for n, wall, err in preset.reference:
                ax.annotate(f"N={n}", (wall, err), fontsize=7, textcoords="offset points",
                            xytext=(4, -9))
        ax.set_xlabel(f"wall time [s] ({nproc} MPI rank{'s' if nproc > 1 else ''})")
        ax.set_ylabel(labels.get(key, f"L1({key})"))
        ax.grid(True, which="both", alpha=0.3)
    if len(runs_by_variant) > 1 or next(iter(runs_by_variant)) != "default" or preset:
        axes[0].legend(fontsize=8)
    fig.suptitle(f"{scene_name}: L1 error vs wall time")
    fig.tight_layout()
    fig.savefig(png_path, dpi=130)
    return png_path


# --------------------------------------------------------------------------------------------


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scene", choices=sorted(SCENES), help="test scene")
    parser.add_argument("--resolutions", default=None,
                        help="comma-separated values of the scene's resolution variable "
                             "(Sod: nx; default 32,48,64,96,128)")
    parser.add_argument("--np", type=int, default=None,
                        help="MPI ranks per run (default 1, or the preset's)")
    parser.add_argument("--outdir", default=os.path.join(ROOT, "build", "output",
                                                         "error_vs_time"))
    parser.add_argument("--variants", default=None,
                        help="';'-separated variants of ','-separated name=value LAMMPS "
                             "variables, one curve each, e.g. 'hfact=1.2;hfact=1.5', or "
                             "'physics' for the scene's h modes and switches")
    parser.add_argument("--var", action="append", default=[], metavar="NAME=VALUE",
                        help="LAMMPS variable for every run (repeatable)")
    parser.add_argument("--lmp", default="lmp", help="LAMMPS executable (default lmp)")
    parser.add_argument("--reuse", action="store_true",
                        help="do not rerun a resolution/variant whose identical earlier run "
                             "(same command) left its log, dump and wall time in OUTDIR/runs; "
                             "re-analyse it (e.g. to add a variant to an existing plot)")
    parser.add_argument("--preset", default=None,
                        help="a named comparison of the scene (Sod: 'phantom'): its resolutions, "
                             "ranks, variables and variants, with the other code's published "
                             "points as a reference curve")
    args = parser.parse_args(argv)

    scene = SCENES[args.scene]
    preset = None
    resolutions_given = args.resolutions is not None
    if args.preset is not None:
        if args.preset not in scene.presets:
            parser.error(f"scene {args.scene} has no preset '{args.preset}' "
                         f"(has: {', '.join(sorted(scene.presets)) or 'none'})")
        preset = scene.presets[args.preset]
        if args.resolutions is None:
            args.resolutions = ",".join(str(r) for r in preset.resolutions)
        if args.variants is None:
            args.variants = preset.variants
        if args.np is None:
            args.np = preset.np
        args.var = list(preset.var) + args.var
    if args.np is None:
        args.np = 1
    res_list = ([int(float(v)) for v in args.resolutions.split(",") if v.strip()]
                if args.resolutions else list(scene.default_res))
    common = parse_settings(args.var)
    if args.variants == "physics" and not scene.physics:
        parser.error(f"scene {args.scene} has no physics variants")
    variants = parse_variants(scene.physics if args.variants == "physics" else args.variants)
    env = lammps_environment()
    outdir = os.path.abspath(args.outdir)
    os.makedirs(outdir, exist_ok=True)

    runs_by_variant = {}
    for variant, settings in variants:
        settings = {**common, **settings}
        tag = re.sub(r"[^A-Za-z0-9_.=-]+", "_", variant)
        runs_by_variant[variant] = []
        limit = (preset.max_resolution.get(variant)
                 if preset is not None and not resolutions_given else None)
        for res in res_list:
            if limit is not None and res > limit:
                continue
            workdir = os.path.join(outdir, "runs", f"{args.scene}_{tag}_{scene.res_var}{res}")
            run = Run(args.scene, variant, res, settings, workdir)
            print(f"[{args.scene} {variant} {scene.res_var}={res}] running ...", end=" ",
                  flush=True)
            run_one(scene, run, args.np, env, args.lmp, args.reuse)
            print(f"{'(reused) ' if run.reused else ''}N={run.natoms} steps={run.steps} wall={run.wall_s:.2f}s "
                  f"L1({scene.fit})={run.errors[scene.fit]:.3e}", flush=True)
            runs_by_variant[variant].append(run)

    table = format_table(args.scene, scene, runs_by_variant, args.np)
    if preset is not None:
        fit_label = dict(scene.errors)[scene.fit]
        table += f"# {preset.notes}\n# {preset.reference_label}: N, wall_s, {fit_label}"
        table += "".join(f"; {n}, {w:g}, {e:.3g}" for n, w, e in preset.reference) + "\n"
        for variant, runs in runs_by_variant.items():
            ratios = []
            for r in runs:
                ref = [p for p in preset.reference if p[0] == r.natoms]
                if ref:
                    ratios.append(f"N={r.natoms}: {fit_label} {r.errors[scene.fit] / ref[0][2]:.2f}x, "
                                  f"wall {r.wall_s / ref[0][1]:.2f}x")
            if ratios:
                table += f"# {variant} against {preset.reference_label}: " + "; ".join(ratios) + "\n"
    table_path = os.path.join(outdir, f"{args.scene}_table.txt")
    with open(table_path, "w", encoding="utf-8") as f:
        f.write(table)
    png_path = plot(args.scene, scene, runs_by_variant,
                    os.path.join(outdir, f"{args.scene}_error_vs_time.png"), args.np, preset)
    print()
    print(table, end="")
    print(f"table: {table_path}\nplot: {png_path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
