#!/usr/bin/env python3
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
"""Stiff and extreme cases: tiny LAMMPS runs that must end cleanly or stop with a clear error.

Usage: python3 unittest/stiff_cases.py WORKDIR [--only NAME[,NAME...]]

Each case writes a small LAMMPS input into WORKDIR/NAME/, runs it with ``lmp`` (one MPI
rank, a few seconds), and checks the log and the final dump. Every case that should run
must reach its end time (fix sph/astro *tend*) with

* no LAMMPS error, all dumped values finite, no particle with u < 0 (dump and thermo
  minimum of u),
* no timestep collapse: fix sph/astro *dtmin* is set to about 1e-9 of an estimate of the
  initial timestep (a smaller step stops the run with an error), and the smallest timestep
  of the thermo lines must stay above 1e-6 of the first one,

and pass the physics checks of the case. The cases:

1. ``sedov_pbg1e-10``: Sedov-Taylor blast (E = 1) into a background of P = 1e-10 (shock
   Mach number ~ 1e5), 2 048 particles, t = 0.05: shock radius, energy error.
2. ``mach100_collision``: two cold streams (v = +-1, c_s = 0.02: relative Mach 100) collide
   at x = 0 (and at the periodic boundary); post-shock density ~ 4 (strong shock, gamma 5/3)
   within 25 %, post-shock u ~ 1/2.
3. ``contact_1000``: contact discontinuity rho 1 | 1e-3 in pressure balance (P = 1): equal
   masses on fcc lattices with lattice constants 0.1 and 1 (dense slab 0.4 thick, tenuous
   gas 4 long, periodic), run to t = 0.5 (1.6 sound-crossing times of the dense slab, 5 of
   the tenuous gas): runs to the end; all pressures within a factor 3 of 1 (no blow-up);
   reported: median pressure of each gas and of the dense gas beyond 2 h of the contact
   (not within 20 % yet: the contact pressure blip of plain SPH).
4. ``isolated_particle``: a cold cluster plus one particle far from it: its density is
   m W(0, h) exactly (h at the cap of fix sph/astro/h, its hmax), v and u do not change, dt
   finite.
   ``single_particle``: the same particle alone in the box.
5. ``ballistic_sphere``: a uniform cold sphere (u = 1e-8) expanding ballistically into
   vacuum, v = H r with H = 1, to t = 1 (radius doubles): v stays v0, x = x0 + v0 t,
   0 <= u <= u0.
6. ``ballistic_sphere_entropy``: the same with fix sph/astro thermal entropy.
7. ``hot_sphere``: a uniform hot sphere (u = 1) expanding into vacuum to t = 1 (radius
   0.5 -> ~2.5): the gas cools towards u = 0 (energy timestep criterion); energy error.
8. ``negative_u_refused``: an initial u < 0 is physics out of range: the run must stop with
   a LAMMPS error that names the atom and u.
9. ``dtmin_guard``: the collapse detector works: case 2 with dtmin 0.01 (above its real
   timestep, 2.2e-3) must stop with an error naming dtmin, the atom and the criteria.

One line per case (PASS/FAIL, figures, wall time), then 'N passed, M failed'; the exit
status is 1 if any case failed.
"""

import argparse
import math
import os
import re
import subprocess
import sys
import time

import numpy as np

from sphastro import sedov
from sphastro.dump import read_last_frame
from sphastro.runs import lammps_environment

HERE = os.path.dirname(os.path.abspath(__file__))

GAMMA = 5.0 / 3.0
SIGMA_M4_3D = 1.0 / math.pi          # M4 kernel: W(0, h) = sigma / h^3 in 3D
TIMEOUT = 900                         # a hang guard, not a speed bound (each case takes < 40 s alone)

HEADER = """units           lj
atom_style      atomic
atom_modify     map array sort 0 0.0
"""

# per-atom output and global monitors shared by all cases (compute sph: rho pressure u h)
MONITORS = """compute         sph all sph/astro/atom rho pressure u h
compute         sum all sph/astro/global
compute         umin all reduce min c_sph[3]
thermo_style    custom step time dt c_sum[11] c_sum[12] c_sum[13] c_sum[14] c_sum[18] c_umin
thermo_modify   norm no format float %.10g
thermo          {every}
"""

DUMP = """write_dump      all custom {name} id type x y z vx vy vz c_sph[1] c_sph[2] c_sph[3] c_sph[4] &
                modify colname c_sph[1] rho colname c_sph[2] pressure colname c_sph[3] u &
                colname c_sph[4] h format float %.16g time yes
"""


def dt_estimate(h, c, v=0.0, alpha=1.0, beta=2.0, courant=0.3):
    """Rough Courant-viscosity timestep of fix sph/astro (for the dtmin guard only)."""
    return courant * h / (c + v + 1.2 * (alpha * c + beta * v))


# further pair_style sph/astro keywords for every case (--pair-options, e.g. "reconstruct yes")
PAIR_OPTIONS = ""


def pair_and_fixes(tend, dt0, thermal="energy", margin=1.5, hfact=1.2, extra="", hmax=None):
    hmax_option = f" hmax {hmax:.10g}" if hmax else ""
    return f"""pair_style      sph/astro kernel m4 eos ideal {GAMMA:.10g} viscosity classic 1.0 2.0 {PAIR_OPTIONS}
pair_coeff      * *
fix             gas all sph/astro courant 0.3 tend {tend} dtmin {1e-9 * dt0:.3g} thermal {thermal}
fix             hvar all sph/astro/h iterate hfact {hfact} margin {margin}{hmax_option}
{extra}"""


# ------------------------------------------------------------------ log and dump helpers

_LOOP = re.compile(r"^Loop time of (\S+) on \d+ procs for (\d+) steps with (\d+) atoms", re.M)


def parse_log(path):
    """Thermo rows (dicts), error lines, 'reached tend' flag and steps of a LAMMPS log."""
    out = {"rows": [], "errors": [], "reached": False, "steps": 0, "natoms": 0, "loop_s": 0.0}
    if not os.path.exists(path):
        return out
    with open(path, encoding="utf-8", errors="replace") as f:
        text = f.read()
    header = None
    for line in text.splitlines():
        words = line.split()
        if words[:1] == ["Step"]:
            header = words
            continue
        if line.startswith("ERROR"):
            out["errors"].append(line.strip())
        if "reached tend" in line:
            out["reached"] = True
        if header is None:
            continue
        if len(words) != len(header):
            if line.startswith("Loop time"):
                header = None
            continue
        if "Dt" not in header:
            continue
        try:
            out["rows"].append(dict(zip(header, (float(w) for w in words))))
        except ValueError:
            continue
    for t, steps, natoms in _LOOP.findall(text):
        out["loop_s"] += float(t)
        out["steps"] += int(steps)
        out["natoms"] = int(natoms)
    return out


class Failure(Exception):
    """A check of a case did not hold."""


def check(cond, text):
    if not cond:
        raise Failure(text)


def common_checks(log, frame, tend):
    """Reached tend, no error, finite values, u >= 0, no timestep collapse; returns figures."""
    check(not log["errors"], "LAMMPS error: " + " | ".join(log["errors"]))
    check(log["reached"], "the run did not reach tend")
    check(frame is not None, "no final dump")
    check(frame.time is not None and abs(frame.time - tend) <= 1e-9 * max(1.0, tend),
          f"final dump at t = {frame.time}, not {tend}")
    for name, col in frame.columns.items():
        if col.dtype.kind == "f":
            check(np.all(np.isfinite(col)), f"non-finite values in column {name}")
    umin = float(frame.columns["u"].min())
    check(umin >= 0.0, f"u < 0 in the dump (min {umin:.3e})")
    rows = log["rows"]
    check(len(rows) >= 2, "fewer than two thermo lines")
    dts = np.array([r["Dt"] for r in rows])
    check(np.all(np.isfinite(dts)) and np.all(dts > 0.0), "non-finite or non-positive dt")
    # the step that reaches tend is shortened on purpose: leave out the last line
    ratio = float(dts[:-1].min() / dts[0])
    check(ratio > 1e-6, f"timestep collapse: smallest dt / first dt = {ratio:.3e}")
    uthermo = min(r["c_umin"] for r in rows)
    check(uthermo >= 0.0, f"u < 0 at a thermo line (min {uthermo:.3e})")
    return {"steps": log["steps"], "dt_ratio": ratio, "umin": umin,
            "eerr": rows[-1]["c_sum[12]"], "capped": rows[-1]["c_sum[18]"]}


# ------------------------------------------------------------------------------ cases

def case_sedov(work):
    """Sedov-Taylor blast with background pressure 1e-10 (in.sedov's set-up, n = 8)."""
    n, tend, E, pbg = 8, 0.05, 1.0, 1e-10
    a = 1.0 / n
    m = a ** 3 / 4
    h0 = 1.2 * m ** (1.0 / 3.0)
    ubg = pbg / (GAMMA - 1.0)
    chot = math.sqrt(GAMMA * (GAMMA - 1.0) * E / (30 * m))
    text = HEADER + f"""boundary        p p p
region          box block -0.5 0.5 -0.5 0.5 -0.5 0.5 units box
create_box      1 box
lattice         fcc {4.0 / a ** 3:.10g} origin 0.0 0.0 0.0
create_atoms    1 box
mass            1 {m:.10g}
reset_atoms     id sort yes
variable        q atom sqrt(x*x+y*y+z*z)/{h0:.16g}
variable        wk atom (v_q<1.0)*(1.0-1.5*v_q^2+0.75*v_q^3)+(v_q>=1.0)*(v_q<2.0)*0.25*(2.0-v_q)^3
compute         wsum all reduce sum v_wk
thermo_style    custom step c_wsum
run             0
variable        wsum equal $(c_wsum:%.17g)
variable        uinit atom {ubg:.10g}+{E}*v_wk/(${{wsum}}*{m:.16g})
uncompute       wsum
""" + pair_and_fixes(tend, dt_estimate(h0, chot), margin=2.0) + f"""set             group all d_h {h0:.10g}
set             group all d_u v_uinit
neighbor        {0.5 * h0:.6g} bin
""" + MONITORS.format(every=10) + """timestep        1e-6
run             100000
""" + DUMP.format(name="dump.final")

    def checks(log, frame):
        fig = common_checks(log, frame, tend)
        res = sedov.sedov_errors(frame, tend, E, 1.0, GAMMA)
        fig.update(rshock=res["err_r_half"], peak=res["rho_peak"])
        check(abs(fig["eerr"]) < 1e-2, f"energy error {fig['eerr']:.2e}")
        check(abs(res["err_r_half"]) < 0.2, f"shock radius error {100 * res['err_r_half']:+.1f} %")
        check(res["rho_peak"] > 1.15, f"binned peak density {res['rho_peak']:.2f} <= 1.15")
        return (f"R_s {100 * res['err_r_half']:+.1f} %, peak rho {res['rho_peak']:.2f}, "
                f"energy error {fig['eerr']:+.1e}, capped {fig['capped']:g}")
    return text, checks


def case_mach100(work):
    """Two cold streams colliding at relative Mach 100 (periodic in x: two collisions)."""
    nx, ny, tend, v, cs = 24, 4, 0.3, 1.0, 0.02
    a = 1.0 / nx
    L = ny * a
    m = a ** 3 / 4
    h0 = 1.2 * m ** (1.0 / 3.0)
    u0 = cs ** 2 / (GAMMA * (GAMMA - 1.0))
    mach = (v + v * (GAMMA - 1.0) / 2.0) / cs         # upstream speed in the shock frame / c
    jump = (GAMMA + 1.0) * mach ** 2 / ((GAMMA - 1.0) * mach ** 2 + 2.0)
    xs = (GAMMA - 1.0) / 2.0 * v * tend               # shock position (post-shock gas at rest)
    text = HEADER + f"""boundary        p p p
region          box block -1.0 1.0 0.0 {L:.16g} 0.0 {L:.16g} units box
create_box      1 box
lattice         fcc {4.0 / a ** 3:.10g} origin 0.25 0.25 0.25
create_atoms    1 box
mass            1 {m:.10g}
reset_atoms     id sort yes
variable        vx0 atom -{v}*(x>0.0)+{v}*(x<0.0)
velocity        all set v_vx0 0.0 0.0 units box
""" + pair_and_fixes(tend, dt_estimate(h0, cs, 2 * v), margin=1.3) + f"""set             group all d_h {h0:.10g}
set             group all d_u {u0:.10g}
neighbor        {0.3 * h0:.6g} bin
""" + MONITORS.format(every=20) + """timestep        1e-5
run             100000
""" + DUMP.format(name="dump.final")

    def checks(log, frame):
        fig = common_checks(log, frame, tend)
        c = frame.columns
        ax = np.abs(c["x"])
        ax = np.minimum(ax, 1.0 - ax)                   # distance from the nearer collision plane
        sel = (ax > 0.3 * xs) & (ax < 0.7 * xs)
        check(sel.sum() > 10, "too few particles in the post-shock window")
        rho = float(c["rho"][sel].mean())
        u = float(c["u"][sel].mean())
        ucen = float(c["u"][ax < 0.1 * xs].mean())
        check(abs(rho / jump - 1.0) < 0.25, f"post-shock rho {rho:.3f} vs {jump:.3f}")
        check(abs(u / (0.5 * v * v) - 1.0) < 0.25, f"post-shock u {u:.3f} vs 0.5")
        check(abs(fig["eerr"]) < 1e-2, f"energy error {fig['eerr']:.2e}")
        return (f"shock Mach {mach:.0f}: post-shock rho {rho:.3f} (exact {jump:.3f}, "
                f"{100 * (rho / jump - 1):+.1f} %), u {u:.3f} (0.5), u at the collision "
                f"plane {ucen:.3f}, energy error {fig['eerr']:+.1e}")
    return text, checks


def case_contact(work):
    """Contact discontinuity 1000:1 in pressure balance (equal masses, spacings 1:10)."""
    tend, P = 0.5, 1.0
    a1, a2 = 0.1, 1.0                 # fcc lattice constants: rho 1 and 1e-3
    wy, wz = 2.0, 1.0                 # box width in y and z: 2 and 1 cells of the tenuous lattice
    m = a1 ** 3 / 4
    h1 = 1.2 * (m / 1.0) ** (1.0 / 3.0)
    h2 = 1.2 * (m / 1e-3) ** (1.0 / 3.0)
    u1, u2 = P / ((GAMMA - 1.0) * 1.0), P / ((GAMMA - 1.0) * 1e-3)
    c2 = math.sqrt(GAMMA * P / 1e-3)
    xl, xr = -0.4, 4.0                # dense slab -0.4 < x < 0, tenuous 0 < x < 4 (periodic)
    text = HEADER + f"""boundary        p p p
region          box block {xl} {xr} 0.0 {wy} 0.0 {wz} units box
create_box      2 box
region          dense block {xl} 0.0 EDGE EDGE EDGE EDGE units box
region          thin block 0.0 {xr} EDGE EDGE EDGE EDGE units box
lattice         fcc {4.0 / a1 ** 3:.10g} origin 0.25 0.25 0.25
create_atoms    1 region dense
lattice         fcc {4.0 / a2 ** 3:.10g} origin 0.25 0.25 0.25
create_atoms    2 region thin
mass            * {m:.10g}
reset_atoms     id sort yes
""" + pair_and_fixes(tend, dt_estimate(h1, c2), margin=1.3) + f"""set             type 1 d_h {h1:.10g}
set             type 1 d_u {u1:.10g}
set             type 2 d_h {h2:.10g}
set             type 2 d_u {u2:.10g}
neighbor        {0.3 * h1:.6g} bin
# a tenuous particle's support (2 x 1.3 x its h = 2 in the cutoff) covers thousands of dense ones
neigh_modify    one 20000 page 400000
""" + MONITORS.format(every=20) + """timestep        1e-5
run             100000
""" + DUMP.format(name="dump.final")

    def checks(log, frame):
        fig = common_checks(log, frame, tend)
        c = frame.columns
        x = c["x"] - xl
        width = xr - xl
        x = np.mod(x, width) + xl                       # wrap into the box
        # distance from the nearer of the two contacts (x = 0 and x = xl = xr)
        d = np.minimum(np.abs(x), np.minimum(np.abs(x - xl), np.abs(x - xr)))
        p = c["pressure"]
        dense = c["type"] == 1
        far = d > 2.0 * np.where(dense, h1, h2)         # outside the kernel support (2h)
        pd, pt = float(np.median(p[dense])), float(np.median(p[~dense]))
        lo, hi = float(p.min()), float(p.max())
        pfar = p[dense & far]
        check(len(pfar) > 0, "no dense particle outside 2 h of the contact")
        dev_far = float(np.max(np.abs(pfar / P - 1.0)))
        vmax = float(np.max(np.sqrt(c["vx"] ** 2 + c["vy"] ** 2 + c["vz"] ** 2)))
        summary = (f"median P dense {pd:.3f}, tenuous {pt:.3f}; dense P beyond 2h of the contact "
                f"within {100 * dev_far:.0f} %; all P in [{lo:.3f}, {hi:.3f}]; |v|max {vmax:.3g}; "
                f"energy error {fig['eerr']:+.1e}")
        # the issue asks this case to survive (common_checks); the pressure is a figure. It
        # must not blow up (within a factor 3 of nominal); within 20 % it is not yet: the
        # tenuous side carries SPH's contact pressure blip (no conductivity here)
        check(lo > P / 3.0 and hi < 3.0 * P, "pressure left [P/3, 3P]: " + summary)
        within = abs(pd / P - 1.0) < 0.2 and abs(pt / P - 1.0) < 0.2 and dev_far < 0.2
        return summary + ("" if within else " (medians not within 20 % of P: contact blip)")
    return text, checks


def _isolated(work, with_cluster):
    tend = 0.2
    a = 0.1
    m = a ** 3 / 4
    h0 = 1.2 * m ** (1.0 / 3.0)
    hiso, uiso, viso = 0.1, 1.0, 0.1
    margin = 1.5
    cluster = ""
    if with_cluster:
        cluster = f"""region          blob block 0.0 0.4 0.0 0.4 0.0 0.4 units box
lattice         fcc {4.0 / a ** 3:.10g} origin 0.25 0.25 0.25
create_atoms    1 region blob
"""
    text = HEADER + f"""boundary        p p p
region          box block -2.0 2.0 -2.0 2.0 -2.0 2.0 units box
create_box      2 box
{cluster}create_atoms    2 single -1.5 -1.5 -1.5 units box
mass            * {m:.10g}
reset_atoms     id sort yes
group           iso type 2
""" + pair_and_fixes(tend, dt_estimate(h0, 0.1), margin=margin,
                    hmax=margin * hiso) + f"""set             type 1 d_h {h0:.10g}
set             type 1 d_u 0.01
set             type 2 d_h {hiso:.10g}
set             type 2 d_u {uiso:.10g}
velocity        iso set {viso} 0.0 0.0 units box
neighbor        {0.3 * h0:.6g} bin
""" + MONITORS.format(every=10) + """timestep        1e-5
run             100000
""" + DUMP.format(name="dump.final")

    def checks(log, frame):
        fig = common_checks(log, frame, tend)
        c = frame.columns
        i = int(np.nonzero(c["type"] == 2)[0][0])
        h, rho = c["h"][i], c["rho"][i]
        expect = m * SIGMA_M4_3D / h ** 3
        check(abs(rho / expect - 1.0) < 1e-12, f"rho {rho!r} != m W(0,h) = {expect!r}")
        check(abs(h / (margin * hiso) - 1.0) < 1e-12, f"h {h!r} not at the cap "
                                                       f"{margin * hiso!r}")
        check(c["vx"][i] == viso and c["vy"][i] == 0.0 and c["vz"][i] == 0.0,
              f"velocity changed: {c['vx'][i]!r} {c['vy'][i]!r} {c['vz'][i]!r}")
        check(abs(c["u"][i] / uiso - 1.0) < 1e-14, f"u changed: {c['u'][i]!r}")
        xexp = -1.5 + viso * tend
        check(abs(c["x"][i] - xexp) < 1e-12, f"x {c['x'][i]!r} != {xexp!r}")
        return (f"rho = m W(0,h) to {abs(rho / expect - 1):.1e}, h at the cap, v and u "
                f"unchanged, {fig['steps']} steps, smallest dt/first {fig['dt_ratio']:.2f}")
    return text, checks


def case_isolated(work):
    return _isolated(work, True)


def case_single(work):
    return _isolated(work, False)


def _sphere(work, thermal, hot):
    """Uniform sphere of radius 0.5 into vacuum: ballistic (v = H r, u = 1e-8) or hot."""
    a, R = 0.1, 0.5
    m = a ** 3 / 4
    h0 = 1.2 * m ** (1.0 / 3.0)
    if hot:
        tend, H, u0, margin = 1.0, 0.0, 1.0, 1.5
        cs = math.sqrt(GAMMA * (GAMMA - 1.0) * u0)
        dt0 = dt_estimate(h0, cs)
    else:
        tend, H, u0, margin = 1.0, 1.0, 1e-8, 1.6
        dt0 = 0.3 / (3.0 * H * (1.0 + 1.2 * 2.0))   # C h / (h divv (1 + 1.2 beta)), divv = 3H
    text = HEADER + f"""boundary        s s s
region          box block -0.6 0.6 -0.6 0.6 -0.6 0.6 units box
create_box      1 box
region          ball sphere 0.0 0.0 0.0 {R} units box
lattice         fcc {4.0 / a ** 3:.10g} origin 0.0 0.0 0.0
create_atoms    1 region ball
mass            1 {m:.10g}
reset_atoms     id sort yes
variable        vx0 atom {H}*x
variable        vy0 atom {H}*y
variable        vz0 atom {H}*z
velocity        all set v_vx0 v_vy0 v_vz0 units box
""" + pair_and_fixes(tend, dt0, thermal=thermal, margin=margin) + f"""set             group all d_h {1.3 * h0:.10g}
set             group all d_u {u0:.10g}
neighbor        {0.3 * h0:.6g} bin
write_dump      all custom dump.initial id type x y z vx vy vz d_u d_h &
                modify format float %.16g time yes
""" + MONITORS.format(every=10) + f"""timestep        1e-5
# h grows with the radius: runs of 10 steps, so that the h cap (margin x the largest h at
# the start of a run) follows it
variable        done equal time>={tend}*(1.0-1e-12)
label           segment
run             10
if "${{done}}" then "jump SELF finished"
jump            SELF segment
label           finished
""" + DUMP.format(name="dump.final")

    def checks(log, frame):
        fig = common_checks(log, frame, tend)
        init = read_last_frame(os.path.join(work, "dump.initial"))
        o0 = np.argsort(init.columns["id"])
        o1 = np.argsort(frame.columns["id"])
        c0 = {k: v[o0] for k, v in init.columns.items()}
        c1 = {k: v[o1] for k, v in frame.columns.items()}
        u = c1["u"]
        if hot:
            check(abs(fig["eerr"]) < 1e-2, f"energy error {fig['eerr']:.2e}")
            rmax = float(np.sqrt(c1["x"] ** 2 + c1["y"] ** 2 + c1["z"] ** 2).max())
            return (f"u in [{u.min():.3e}, {u.max():.3f}], outer radius {rmax:.3f}, "
                    f"energy error {fig['eerr']:+.1e}, {fig['steps']} steps, "
                    f"smallest dt/first {fig['dt_ratio']:.3f}, capped {fig['capped']:g}")
        dv = np.sqrt((c1["vx"] - c0["vx"]) ** 2 + (c1["vy"] - c0["vy"]) ** 2
                     + (c1["vz"] - c0["vz"]) ** 2)
        dx = np.sqrt((c1["x"] - c0["x"] - c0["vx"] * tend) ** 2
                     + (c1["y"] - c0["y"] - c0["vy"] * tend) ** 2
                     + (c1["z"] - c0["z"] - c0["vz"] * tend) ** 2)
        dvmax, dxmax = float(dv.max()) / (H * R), float(dx.max()) / R
        check(dvmax < 1e-5, f"not ballistic: max |v - v0| = {dvmax:.2e} of H R")
        check(dxmax < 1e-5, f"not ballistic: max |x - x0 - v0 t| = {dxmax:.2e} of R")
        check(u.max() <= u0 * (1.0 + 1e-6), f"u grew: max {u.max():.3e} > u0 {u0:.1e}")
        r1 = np.sqrt(c1["x"] ** 2 + c1["y"] ** 2 + c1["z"] ** 2)
        core = r1 < 0.5 * R * (1 + H * tend)
        rho_c = float(c1["rho"][core].mean())
        rho_exact = (1.0 + H * tend) ** -3
        return (f"max |v - v0| = {dvmax:.1e} H R, max |x - x0 - v0 t| = {dxmax:.1e} R, "
                f"u in [{u.min():.3e}, {u.max():.3e}] (u0 {u0:g}), core rho {rho_c:.4f} "
                f"(exact {rho_exact:.4f}), capped {fig['capped']:g}, {fig['steps']} steps")
    return text, checks


def case_ballistic(work):
    return _sphere(work, "energy", hot=False)


def case_ballistic_entropy(work):
    return _sphere(work, "entropy", hot=False)


def case_hot(work):
    return _sphere(work, "energy", hot=True)


def case_negative_u(work):
    """u < 0 at the start: the run must stop with an error naming the atom and u."""
    a = 0.25
    m = a ** 3 / 4
    h0 = 1.2 * m ** (1.0 / 3.0)
    text = HEADER + f"""boundary        p p p
region          box block 0.0 1.0 0.0 1.0 0.0 1.0 units box
create_box      1 box
lattice         fcc {4.0 / a ** 3:.10g} origin 0.25 0.25 0.25
create_atoms    1 box
mass            1 {m:.10g}
reset_atoms     id sort yes
""" + pair_and_fixes(0.1, dt_estimate(h0, 1.0)) + f"""set             group all d_h {h0:.10g}
set             group all d_u 1.0
set             atom 7 d_u -0.5
neighbor        {0.3 * h0:.6g} bin
""" + MONITORS.format(every=10) + """timestep        1e-5
run             100000
"""

    def checks(log, frame):
        check(log["errors"], "no LAMMPS error for u = -0.5")
        msg = log["errors"][0]
        check(re.search(r"\b7\b", msg) and re.search(r"\bu\b", msg) and "-0.5" in msg,
              f"error does not name atom 7, u and its value: {msg}")
        return f"stops with: {msg}"
    return text, checks


def case_dtmin_guard(work):
    """The collapse detector itself: a dtmin above the real timestep must stop the run with
    an error that names dtmin, the limiting atom and the three criteria."""
    text, _ = case_mach100(work)
    text = re.sub(r"dtmin \S+", "dtmin 0.01", text)

    def checks(log, frame):
        check(log["errors"], "no LAMMPS error although dt < dtmin")
        msg = log["errors"][0]
        check("fell below dtmin" in msg and re.search(r"atom \d+", msg) and "Courant dt" in msg
              and "force dt" in msg and "energy dt" in msg, f"unclear error: {msg}")
        return f"stops with: {msg}"
    return text, checks


CASES = [
    ("sedov_pbg1e-10", case_sedov, True),
    ("mach100_collision", case_mach100, True),
    ("contact_1000", case_contact, True),
    ("isolated_particle", case_isolated, True),
    ("single_particle", case_single, True),
    ("ballistic_sphere", case_ballistic, True),
    ("ballistic_sphere_entropy", case_ballistic_entropy, True),
    ("hot_sphere", case_hot, True),
    ("negative_u_refused", case_negative_u, False),
    ("dtmin_guard", case_dtmin_guard, False),
]


def run_case(name, make, expect_run, root, env):
    work = os.path.join(root, name)
    os.makedirs(work, exist_ok=True)
    for old in ("dump.final", "dump.initial", "log.lammps"):
        if os.path.exists(os.path.join(work, old)):
            os.remove(os.path.join(work, old))
    text, checks = make(work)
    inp = os.path.join(work, f"in.{name}")
    with open(inp, "w", encoding="utf-8") as f:
        f.write(f"# stiff case {name}, written by unittest/stiff_cases.py\n" + text)
    start = time.monotonic()
    try:
        proc = subprocess.run(["lmp", "-in", inp, "-log", "log.lammps", "-screen", "none",
                               "-nocite"], cwd=work, env=env, capture_output=True, text=True,
                              timeout=TIMEOUT)
        rc = proc.returncode
    except subprocess.TimeoutExpired:
        rc = None
    wall = time.monotonic() - start
    log = parse_log(os.path.join(work, "log.lammps"))
    try:
        check(rc is not None, f"no end after {TIMEOUT} s: the run hangs")
        if expect_run:
            check(rc == 0 or not log["errors"], f"lmp exit status {rc}")
        dump = os.path.join(work, "dump.final")
        frame = read_last_frame(dump) if os.path.exists(dump) else None
        detail = checks(log, frame)
        ok = True
    except Failure as exc:
        detail, ok = str(exc), False
    except Exception as exc:                    # a broken dump or log is a failure too
        detail, ok = f"{type(exc).__name__}: {exc}", False
    natoms = log["natoms"]
    print(f"{'PASS' if ok else 'FAIL'} {name}: {detail} [N = {natoms}, {log['steps']} steps, "
          f"wall {wall:.1f} s]", flush=True)
    return ok


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("workdir", help="directory for the inputs, logs and dumps")
    parser.add_argument("--only", default=None, help="comma-separated case names")
    parser.add_argument("--pair-options", default="",
                        help="further pair_style sph/astro keywords for every case, e.g. "
                             "'reconstruct yes'")
    args = parser.parse_args(argv)
    global PAIR_OPTIONS
    PAIR_OPTIONS = args.pair_options
    env = lammps_environment()
    os.makedirs(args.workdir, exist_ok=True)
    root = os.path.abspath(args.workdir)
    names = set(args.only.split(",")) if args.only else None
    unknown = (names or set()) - {c[0] for c in CASES}
    if unknown:
        parser.error(f"unknown case(s) {', '.join(sorted(unknown))}")
    passed = failed = 0
    for name, make, expect_run in CASES:
        if names and name not in names:
            continue
        if run_case(name, make, expect_run, root, env):
            passed += 1
        else:
            failed += 1
    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
