#!/usr/bin/env python3
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
"""Kelvin-Helmholtz scene (examples/kelvin_helmholtz/in.kelvin_helmholtz): the mode amplitude
M(t) of McNally, Lyra & Passy (2012, ApJS 201, 18, eqs. 6-9) from the thermo output of the run
(column v_M), against a reference:

* ``--reference grid`` (default): the non-linear grid solution of sphastro.kh_grid, tabulated in
  kh_grid_reference.txt (1024^2 cells, MUSCL-Hancock + HLLC; within 0.05 % of 512^2 to t = 2),
  compared over t in [0, 2];
* ``--reference linear`` or a file name: the linear reference of sphastro.kh_linear (the seed evolved
  with the linearised Euler equations; growth rate 2.83 once the eigenmode dominates), valid
  while the perturbation is small, compared over t in [0, 1] (the file is written when missing).

Printed, one per line: M at t = 0.5, 1, 1.5, 2 (SPH and reference), and over the comparison
window t in [0, tcmp] (default 2 for the grid reference, 1 for the linear one):

* ``l1``: mean of |M_SPH(t) / M_ref(t) - 1| over the window (the headline error);
* ``maxrel``: the largest |M_SPH / M_ref - 1| in the window;
* ``growth``: M_SPH(tcmp) / M_SPH(0) divided by M_ref(tcmp) / M_ref(0) (1 for the reference
  growth);
* the growth rate d ln M / dt fitted over t in [tcmp/2, tcmp] (SPH and reference);
* from the log: the largest |relative energy error| and the wall seconds (thermo ``cpu``).

``--png`` draws M(t) of one or more logs with the reference (log scale); ``--assert``
checks bounds, e.g. ``growth=0.5`` (growth at least 0.5: a lower bound), ``l1=0.4``,
``maxrel=0.6``, ``energy=1e-3`` (upper bounds).

Usage::

    python3 analyse.py log.lammps [log2 ...] [--labels a,b] [--tcmp 2.0]
        [--png kh_M.png] [--assert growth=0.5,l1=0.4] [--reference grid|linear|kh_linear.txt]
"""

import argparse
import os
import sys

import numpy as np

from sphastro import kh_linear
from sphastro.thermo import read_thermo

GRID_TABLE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "kh_grid_reference.txt")


def reference(path=None):
    """(t, M_lin) on [0, 2] every 0.01 (ny 256: within 1e-4 of ny 1024 up to t = 2)."""
    return kh_linear.load_or_compute(path, ny=256, tend=2.0, dt_out=0.01)


def grid_reference(path=GRID_TABLE):
    """(t, M) of the grid solution (sphastro.kh_grid) on [0, 2] every 0.01."""
    data = np.loadtxt(path, ndmin=2)
    return data[:, 0], data[:, 1]


def select_reference(name):
    """(kind, (t, M), default window end) for --reference grid | linear | FILE."""
    if name in (None, "grid"):
        return "grid", grid_reference(), 2.0
    if name == "linear":
        return "linear", reference(), 1.0
    return "linear", reference(name), 1.0


def measures(thermo, ref, tcmp=1.0):
    """Figures of one run: M at fixed times, errors against the reference (t, M) over
    [0, tcmp], fitted growth rate, energy error and wall time (keys *_lin: the reference's)."""
    t, m = thermo["Time"], thermo["v_M"]
    tr, mr = ref
    out = {"tend": float(t[-1])}
    for tt in (0.5, 1.0, 1.5, 2.0):
        key = f"M{tt:g}"
        out[key] = float(np.interp(tt, t, m)) if tt <= t[-1] + 1e-6 else float("nan")
        out[key + "_lin"] = float(np.interp(tt, tr, mr))
    window = min(tcmp, float(t[-1]))
    sel = tr <= window + 1e-9
    ms = np.interp(tr[sel], t, m)
    rel = np.abs(ms / mr[sel] - 1.0)
    out["window"] = window
    out["l1"] = float(np.mean(rel))
    out["maxrel"] = float(np.max(rel))
    out["growth"] = float((ms[-1] / m[0]) / (mr[sel][-1] / mr[0]))
    fit = (t >= 0.5 * window) & (t <= window + 1e-9)
    out["rate"] = float(np.polyfit(t[fit], np.log(m[fit]), 1)[0]) if fit.sum() > 2 else float("nan")
    fitr = (tr >= 0.5 * window) & (tr <= window + 1e-9)
    out["rate_lin"] = float(np.polyfit(tr[fitr], np.log(mr[fitr]), 1)[0])
    out["energy"] = float(np.max(np.abs(thermo["c_sum[12]"]))) if "c_sum[12]" in thermo else float("nan")
    out["cpu"] = float(thermo["CPU"][-1]) if "CPU" in thermo else float("nan")
    return out


def plot(runs, labels, ref, path, tcmp, kind="linear"):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.0, 4.2))
    tr, mr = ref
    ax.semilogy(tr, mr, "k-", lw=1.6, label="linear theory (sphastro.kh_linear)" if kind == "linear"
                else "grid reference (sphastro.kh_grid)")
    for k, (th, label) in enumerate(zip(runs, labels)):
        ax.semilogy(th["Time"], th["v_M"], "-", lw=1.2, color=f"C{k}", label=label)
    ax.axvspan(0.0, tcmp, color="0.9", zorder=0)
    ax.set_xlabel("t")
    ax.set_ylabel("mode amplitude M (McNally et al. 2012)")
    ax.set_xlim(0.0, 2.0)
    ax.set_ylim(2e-3, 1.0)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)


LOWER = {"growth"}


def check(res, bounds):
    failed = []
    for item in bounds.split(","):
        name, bound = item.split("=")
        name, bound = name.strip(), float(bound)
        if name not in ("growth", "l1", "maxrel", "energy"):
            raise ValueError(f"--assert: unknown field '{name}' (growth, l1, maxrel, energy)")
        value = res[name]
        ok = value >= bound if name in LOWER else value <= bound    # False for nan
        rel = ">=" if name in LOWER else "<="
        print(f"check {name} = {value:.4g} {rel} {bound:.4g}: {'ok' if ok else 'FAILED'}")
        if not ok:
            failed.append(name)
    return failed


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("logs", nargs="+", help="LAMMPS logs of in.kelvin_helmholtz runs")
    parser.add_argument("--labels", default=None, help="comma-separated curve labels")
    parser.add_argument("--tcmp", type=float, default=None,
                        help="end of the comparison window [0, tcmp] (default 2 for the grid "
                        "reference, 1 for the linear one)")
    parser.add_argument("--reference", default="grid",
                        help="grid (kh_grid_reference.txt, default), linear, or a t M file of "
                        "sphastro.kh_linear (computed now if missing; written then)")
    parser.add_argument("--png", default=None, help="write the M(t) plot")
    parser.add_argument("--assert", dest="bounds", default=None,
                        help="e.g. growth=0.5,l1=0.4 (growth: lower bound; others upper)")
    args = parser.parse_args(argv)

    kind, ref, tdefault = select_reference(args.reference)
    tcmp = args.tcmp if args.tcmp is not None else tdefault
    print(f"reference: {kind} ({GRID_TABLE if kind == 'grid' else 'sphastro.kh_linear'}), "
          f"window [0, {tcmp:g}] (or to the run's end)")
    labels = args.labels.split(",") if args.labels else [os.path.basename(os.path.dirname(
        os.path.abspath(p))) or p for p in args.logs]
    runs, failed = [], []
    for path, label in zip(args.logs, labels):
        th = read_thermo(path)
        if "v_M" not in th or "Time" not in th:
            print(f"{path}: no thermo columns Time and v_M (not an in.kelvin_helmholtz log?)")
            return 1
        runs.append(th)
        r = measures(th, ref, tcmp)
        print(f"[{label}] {path}: t_end = {r['tend']:g}")
        for tt in (0.5, 1.0, 1.5, 2.0):
            key = f"M{tt:g}"
            print(f"  M({tt:g}) = {r[key]:.4e}   {kind} {r[key + '_lin']:.4e}")
        print(f"  over t in [0, {r['window']:g}]: l1 = {r['l1']:.4f}, maxrel = {r['maxrel']:.4f}, "
              f"growth = {r['growth']:.4f}")
        print(f"  growth rate over [{0.5 * r['window']:g}, {r['window']:g}] = {r['rate']:.3f} "
              f"({kind} {r['rate_lin']:.3f})")
        print(f"  max |relative energy error| = {r['energy']:.2e}, wall (thermo cpu) = "
              f"{r['cpu']:.1f} s")
        if args.bounds:
            try:
                failed += check(r, args.bounds)
            except ValueError as exc:
                parser.error(str(exc))
    if args.png:
        plot(runs, labels, ref, args.png, tcmp, kind)
        print(f"M(t) plot: {args.png}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
