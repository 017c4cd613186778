"""The Evrard collapse (Evrard 1988, MNRAS 235, 911): the energies of an SPH-ASTRO run from its
LAMMPS log (examples/evrard/in.evrard: thermo Step Time Dt c_sum[8..12] = kinetic K, thermal U,
potential W, total E, (E - E0)/|E0|; v_updates = particle-updates since the start, and with
-var ownrate yes v_ownupdates = those the particles' own rates would need)."""
import re

_SYNC = re.compile(r"relative energy error at the (\d+) synchronisation points of the run: "
                   r"largest \|error\| (\S+), at the last (\S+)")


def read_log(path):
    """Thermo rows (dicts keyed by the column names; a row repeated at a run boundary kept
    once) of the runs whose thermo starts with Step Time, and the total wall time in s."""
    rows = {}
    wall = None
    with open(path) as fh:
        header = None
        for line in fh:
            words = line.split()
            if words[:2] == ["Step", "Time"]:
                header = words
                continue
            if header and words and words[0] == "Loop":
                header = None
                continue
            if line.startswith("Total wall time:"):
                h, m, s = words[-1].split(":")
                wall = 3600 * int(h) + 60 * int(m) + int(s)
            if header and len(words) == len(header):
                try:
                    vals = [float(w) for w in words]
                except ValueError:
                    continue
                rows[int(vals[0])] = dict(zip(header, vals))
    steps = sorted(rows)
    if not steps:
        raise ValueError(f"{path}: no thermo rows with Step Time columns")
    return [rows[s] for s in steps], wall


def at_time(rows, t, key):
    """``key`` at time ``t``, interpolated linearly between thermo rows (None outside)."""
    for a, b in zip(rows, rows[1:]):
        if a["Time"] <= t <= b["Time"]:
            w = (t - a["Time"]) / (b["Time"] - a["Time"]) if b["Time"] > a["Time"] else 0.0
            return a[key] + w * (b[key] - a[key])
    return None


def read_sync_energy(path):
    """From fix sph/astro's end-of-run line (individual steps): the relative total-energy error
    at the synchronisation points, the steps at which every particle ends its step, as (largest
    |error| over all runs, number of points); (None, 0) without that line (global steps, where
    every step is one: use the thermo rows)."""
    largest, points = None, 0
    with open(path) as fh:
        for m in _SYNC.finditer(fh.read()):
            points += int(m.group(1))
            largest = max(largest or 0.0, float(m.group(2)))
    return largest, points


def updates_against(rows, reference, t):
    """Particle-updates of ``rows`` to time ``t`` (None past its end) and, against the
    global-step run ``reference`` (rows, or None), how many times fewer they are than its
    updates to the same time and how many times fewer the particles' own rates need (its
    v_ownupdates column): (updates, fewer, own_fewer), the last two None where not known."""
    updates = at_time(rows, t, "v_updates")
    if updates is None or not reference:
        return updates, None, None
    ref = at_time(reference, t, "v_updates")
    if ref is None or updates <= 0:
        return updates, None, None
    own = at_time(reference, t, "v_ownupdates") if "v_ownupdates" in reference[0] else None
    return updates, ref / updates, (ref / own if own else None)


def create_sphere(lmp, n, hfact=1.2):
    """The particles of examples/evrard/in.evrard at -var n N in a LAMMPS instance whose box
    style is set (boundary, units, atom style): an fcc lattice of n cells across the unit
    sphere, stretched radially r -> r^(3/2) so that M(<r) ~ r^2 (rho ~ 1/r), masses 1/N, and
    the atom-style variable ``hinit`` = hfact (m / rho(r))^(1/3) with rho = 1/(2 pi r) (r held
    above the lattice's innermost shell). Returns the number of particles."""
    a = 2.0 / n
    lmp.commands_list([
        f"lattice fcc {4.0 / a**3!r} origin 0.25 0.25 0.25",
        "region box block -1.05 1.05 -1.05 1.05 -1.05 1.05 units box", "create_box 1 box",
        "region ball sphere 0 0 0 1.0 units box", "create_atoms 1 region ball"])
    natoms = lmp.get_natoms()
    m = 1.0 / natoms
    rfloor = 0.5 * (a / 2.0 ** 0.5) ** 1.5
    lmp.commands_list([
        f"mass 1 {m!r}", "reset_atoms id sort yes",
        "variable r atom sqrt(x*x+y*y+z*z)", "variable dx atom x*(sqrt(v_r)-1.0)",
        "variable dy atom y*(sqrt(v_r)-1.0)", "variable dz atom z*(sqrt(v_r)-1.0)",
        "displace_atoms all move v_dx v_dy v_dz units box",
        f"variable rf atom (v_r>{rfloor!r})*v_r+(v_r<={rfloor!r})*{rfloor!r}",
        f"variable hinit atom {hfact!r}*({m!r}*2.0*PI*v_rf)^(1.0/3.0)"])
    return natoms
