#!/usr/bin/env python3
"""Evrard collapse (examples/evrard/in.evrard): energies from the LAMMPS log.

Reads the thermo rows of every run in the log (a row repeated at a run boundary is kept
once), columns
  Step Time Dt c_sum[8] c_sum[9] c_sum[10] c_sum[11] c_sum[12] ...
     = kinetic K, thermal U, potential W, total E, (E - E0)/|E0|,
and prints one line per figure:
  - the largest relative total-energy error over the run (bar: 1 %), and with individual
    timesteps the largest at the synchronisation points (fix sph/astro's end-of-run line: the
    steps at which every particle ends its step; between them the thermo rows sum predicted
    v and u of the particles inside their steps),
  - the time of maximum compression (minimum of W) and K, U, W, E there,
  - the kinetic-energy maximum,
  - K, U, W, E at t = 0.8 and t = 3 (linear interpolation between thermo rows),
  - wall time and steps,
  - the particle-updates (column v_updates) at t = 0.8, at maximum compression and at the
    end; with --global LOG (a global-step run of the same scene) how many times fewer they are
    than that run's at the same times, and, if that run had -var ownrate yes (column
    v_ownupdates), how many times fewer the particles' own rates would need.
The initial state is compared with its continuum values: W0 = -2/3 G M^2/R for rho ~ 1/r,
U0 = M u0 = 0.05, K0 = 0. Published curves (Evrard 1988, Fig. of the energies; Springel 2005,
GADGET-2) are not reproduced as numbers here: see README.md.

Usage: analyse.py LOG [--global LOG] [--png FILE] [--assert maxerr=X,maxerr_sync=Y]
"""
import argparse
import sys

from sphastro import cli
from sphastro.evrard import at_time, read_log, read_sync_energy, updates_against


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("log")
    p.add_argument("--png", help="write the energy curves to this PNG")
    p.add_argument("--global", dest="global_log",
                   help="log of a global-step run of the same scene: the particle-updates "
                        "against it")
    cli.add_assert_argument(p, "comma-separated bounds, e.g. maxerr=2e-3: exit 1 when exceeded")
    args = p.parse_args()
    try:
        rows, wall = read_log(args.log)
    except ValueError as exc:
        sys.exit(f"analyse.py: {exc}")
    K, U, W, E, ERR = "c_sum[8]", "c_sum[9]", "c_sum[10]", "c_sum[11]", "c_sum[12]"
    r0 = rows[0]
    maxerr = max(abs(r[ERR]) for r in rows)
    # global steps: every step is a synchronisation point (the thermo rows' largest)
    maxerr_sync, sync_points = read_sync_energy(args.log)
    imin = min(range(len(rows)), key=lambda i: rows[i][W])
    kmax = max(rows, key=lambda r: r[K])
    umax = max(rows, key=lambda r: r[U])
    tend = rows[-1]["Time"]
    print(f"Evrard: {len(rows)} thermo rows, t = 0 .. {tend:.4g}, {int(rows[-1]['Step'])} steps, "
          f"wall {wall} s")
    print(f"initial: K {r0[K]:.4f} U {r0[U]:.4f} W {r0[W]:.4f} (continuum rho ~ 1/r: -2/3 = "
          f"{-2.0 / 3.0:.4f}) E {r0[E]:.4f}")
    print(f"max relative total-energy error: {maxerr:.3e} (bar 1e-2: "
          f"{'ok' if maxerr < 1e-2 else 'FAILED'}); at the end {rows[-1][ERR]:.3e}")
    if maxerr_sync is not None:
        print(f"max relative total-energy error at the {sync_points} synchronisation points: "
              f"{maxerr_sync:.3e}")
    else:
        maxerr_sync = maxerr
    rm = rows[imin]
    print(f"maximum compression (min W): t = {rm['Time']:.3f}: K {rm[K]:.4f} U {rm[U]:.4f} "
          f"W {rm[W]:.4f} E {rm[E]:.4f}")
    print(f"kinetic maximum: t = {kmax['Time']:.3f}, K = {kmax[K]:.4f}; thermal maximum: "
          f"t = {umax['Time']:.3f}, U = {umax[U]:.4f}")
    for t in (0.8, 3.0):
        if t > tend + 1e-9:
            print(f"t = {t}: not reached")
            continue
        vals = [at_time(rows, min(t, tend), k) for k in (K, U, W, E)]
        print(f"t = {t}: K {vals[0]:.4f} U {vals[1]:.4f} W {vals[2]:.4f} E {vals[3]:.4f}")
    if "v_updates" in r0:
        try:
            reference = read_log(args.global_log)[0] if args.global_log else None
        except ValueError as exc:
            sys.exit(f"analyse.py: {exc}")
        print_updates(rows, [(0.8, "t = 0.8"), (rm["Time"], "maximum compression"),
                             (tend, "the end")], reference)

    if args.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        t = [r["Time"] for r in rows]
        fig, (ax, ax2) = plt.subplots(2, 1, figsize=(6.5, 6.5), sharex=True,
                                      gridspec_kw={"height_ratios": [3, 1]})
        for key, label, style in ((K, "kinetic K", "-"), (U, "thermal U", "--"),
                                  (W, "potential W", "-."), (E, "total E", ":")):
            ax.plot(t, [r[key] for r in rows], style, label=label)
        ax.axvline(rm["Time"], color="grey", lw=0.5)
        ax.set_ylabel("energy (G M^2 / R)")
        ax.legend(loc="lower left")
        ax.set_title("Evrard collapse")
        ax2.plot(t, [r[ERR] for r in rows])
        ax2.set_ylabel("(E - E0)/|E0|")
        ax2.set_xlabel("t")
        fig.tight_layout()
        fig.savefig(args.png, dpi=110)
        print(f"wrote {args.png}")

    if args.bounds:
        return cli.assert_bounds(args.bounds, {"maxerr": maxerr, "maxerr_sync": maxerr_sync},
                                 error=p.error)
    return 0


def print_updates(rows, times, reference):
    """The particle-updates at each (time, label) up to the run's end, and the times fewer than
    the global-step run ``reference`` (rows, or None) had at the same time."""
    for t, label in times:
        updates, fewer, own_fewer = updates_against(rows, reference, t)
        if updates is None:
            continue
        line = f"particle-updates to {label} (t {t:.3f}): {updates:.4g}"
        if fewer is not None:
            line += f", {fewer:.2f}x fewer than the global-step run"
            if own_fewer is not None:
                line += f" (the particles' own rates: {own_fewer:.2f}x fewer)"
        elif reference:
            line += " (the global-step run does not reach it)"
        print(line)


if __name__ == "__main__":
    sys.exit(main())
