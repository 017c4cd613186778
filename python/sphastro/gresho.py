"""The Gresho-Chan vortex (Gresho & Chan 1990; Springel 2010, MNRAS 401, 791): the exact
steady solution, the per-particle errors of a dump, the LAMMPS thermo figures and the plots of
examples/gresho (analyse.py, run_compare.py) and tools/error_vs_time.py.

v_phi = 5 r, 2 - 5 r, 0 and P = 5 + 12.5 r^2, 9 + 12.5 r^2 - 20 r + 4 ln(5 r), 3 + 4 ln 2 for
r < 0.2, 0.2 <= r < 0.4, r >= 0.4; rho = 1, v_r = 0.
"""

import math
import os

import numpy as np

from .dump import read_frames
from .thermo import read_thermo  # noqa: F401  (examples/gresho and error_vs_time use it here)

P_OUT = 3.0 + 4.0 * math.log(2.0)


# --------------------------------------------------------------------------------------------
# exact solution

def vphi_exact(r):
    """Azimuthal velocity of the Gresho-Chan vortex."""
    r = np.asarray(r, dtype=float)
    return np.where(r < 0.2, 5.0 * r, np.where(r < 0.4, 2.0 - 5.0 * r, 0.0))


def pressure_exact(r):
    """Pressure in balance with vphi_exact (rho = 1): dP/dr = v_phi^2 / r, P continuous."""
    r = np.asarray(r, dtype=float)
    rs = np.maximum(r, 1e-300)
    mid = 9.0 + 12.5 * rs ** 2 - 20.0 * rs + 4.0 * np.log(np.maximum(5.0 * rs, 1e-300))
    return np.where(r < 0.2, 5.0 + 12.5 * r ** 2, np.where(r < 0.4, mid, P_OUT))


# --------------------------------------------------------------------------------------------
# errors

def polar(frame):
    """r, v_phi, v_r of every particle of a frame (vortex centred at the origin)."""
    c = frame.columns
    x, y, vx, vy = c["x"], c["y"], c["vx"], c["vy"]
    r = np.hypot(x, y)
    rs = np.where(r > 0.0, r, 1.0)
    return r, (x * vy - y * vx) / rs, (x * vx + y * vy) / rs


def gresho_errors(frame, rmax=0.5):
    """Per-particle L1 errors over r < rmax: 'vphi', 'vr', 'p', 'rho' (nan if no column), 'n'."""
    r, vphi, vr = polar(frame)
    sel = r < rmax
    n = int(sel.sum())
    err = {"n": n, "vphi": float("nan"), "vr": float("nan"), "p": float("nan"),
           "rho": float("nan")}
    if n == 0:
        return err
    err["vphi"] = float(np.mean(np.abs(vphi[sel] - vphi_exact(r[sel]))))
    err["vr"] = float(np.mean(np.abs(vr[sel])))
    c = frame.columns
    if "pressure" in c:
        err["p"] = float(np.mean(np.abs(c["pressure"][sel] - pressure_exact(r[sel]))))
    if "rho" in c:
        err["rho"] = float(np.mean(np.abs(c["rho"][sel] - 1.0)))
    if "alpha" in c:
        err["alpha_mean"] = float(np.mean(c["alpha"][sel]))
    return err


def binned(r, q, rmax=0.5, nbins=50):
    """Mean of q in nbins equal r-bins over [0, rmax]: (bin centres, means) of non-empty bins."""
    edges = np.linspace(0.0, rmax, nbins + 1)
    idx = np.digitize(r, edges) - 1
    ok = (idx >= 0) & (idx < nbins)
    count = np.bincount(idx[ok], minlength=nbins)
    total = np.bincount(idx[ok], weights=q[ok], minlength=nbins)
    centres = 0.5 * (edges[1:] + edges[:-1])
    keep = count > 0
    return centres[keep], total[keep] / count[keep]


# --------------------------------------------------------------------------------------------
# LAMMPS log (read_thermo: sphastro.thermo)


def log_figures(thermo):
    """Conservation figures from the thermo columns of in.gresho (missing ones are skipped)."""
    out = {}
    if "c_sum[12]" in thermo:
        out["dE_max"] = float(np.max(np.abs(thermo["c_sum[12]"])))
        out["dE_end"] = float(thermo["c_sum[12]"][-1])
    if "c_sum[8]" in thermo and thermo["c_sum[8]"][0] != 0.0:
        out["ekin_ratio"] = float(thermo["c_sum[8]"][-1] / thermo["c_sum[8]"][0])
    if "c_sum[7]" in thermo and thermo["c_sum[7]"][0] != 0.0:
        out["lz_ratio"] = float(thermo["c_sum[7]"][-1] / thermo["c_sum[7]"][0])
    for k, name in (("px_max", "c_sum[2]"), ("py_max", "c_sum[3]")):
        if name in thermo:
            out[k] = float(np.max(np.abs(thermo[name])))
    if "f_av[1]" in thermo:
        out["alpha_mean_end"] = float(thermo["f_av[1]"][-1])
        out["alpha_mean_max"] = float(np.max(thermo["f_av[1]"]))
        out["alpha_max_end"] = float(thermo["f_av[2]"][-1]) if "f_av[2]" in thermo else math.nan
    return out


def default_log(dump):
    """log.X beside dump.X, if it exists."""
    d, base = os.path.split(os.path.abspath(dump))
    if base.startswith("dump."):
        cand = os.path.join(d, "log." + base[len("dump."):])
        if os.path.exists(cand):
            return cand
    return None


def series_errors(path, rmax=0.5):
    """(times, L1(v_phi)) for every frame of a multi-frame dump."""
    t, e = [], []
    for frame in read_frames(path):
        t.append(frame.time if frame.time is not None else float("nan"))
        e.append(gresho_errors(frame, rmax)["vphi"])
    return np.array(t), np.array(e)


# --------------------------------------------------------------------------------------------
# plots

def plot_profiles(frames, labels, path, rmax=0.5, title=None):
    """v_phi(r), P(r) and alpha(r) of one or more frames against the exact vortex."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    have_alpha = any("alpha" in f.columns for f in frames)
    npan = 3 if have_alpha else 2
    fig, axes = plt.subplots(1, npan, figsize=(5.2 * npan, 4.3))
    rr = np.linspace(0.0, rmax, 801)
    colours = ["C0", "C3", "C2", "C1", "C4"]
    axes[0].plot(rr, vphi_exact(rr), "k-", lw=1.2, label="exact (t = 0)")
    axes[1].plot(rr, pressure_exact(rr), "k-", lw=1.2, label="exact")
    for k, (frame, label) in enumerate(zip(frames, labels)):
        col = colours[k % len(colours)]
        r, vphi, _ = polar(frame)
        sel = r < rmax
        err = gresho_errors(frame, rmax)
        axes[0].plot(r[sel], vphi[sel], ".", ms=1.0, color=col, alpha=0.25, rasterized=True)
        rb, vb = binned(r[sel], vphi[sel], rmax)
        axes[0].plot(rb, vb, "-", color=col, lw=1.6,
                     label=f"{label}: L1 = {err['vphi']:.3e}")
        if "pressure" in frame.columns:
            p = frame.columns["pressure"]
            axes[1].plot(r[sel], p[sel], ".", ms=1.0, color=col, alpha=0.25, rasterized=True)
            rb, pb = binned(r[sel], p[sel], rmax)
            axes[1].plot(rb, pb, "-", color=col, lw=1.6, label=label)
        if have_alpha and "alpha" in frame.columns:
            a = frame.columns["alpha"]
            axes[2].plot(r[sel], a[sel], ".", ms=1.0, color=col, alpha=0.25, rasterized=True)
            rb, ab = binned(r[sel], a[sel], rmax)
            axes[2].plot(rb, ab, "-", color=col, lw=1.6, label=label)
    axes[0].set_ylabel(r"$v_\phi$")
    axes[1].set_ylabel("P")
    if have_alpha:
        axes[2].set_ylabel(r"$\alpha$ (viscosity)")
        axes[2].set_yscale("log")
    for ax in axes:
        ax.set_xlabel("r")
        ax.set_xlim(0.0, rmax)
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def plot_log(thermos, labels, path, series=None):
    """Relative energy error, E_kin/E_kin(0), L_z/L_z(0), mean alpha and L1(v_phi) vs time."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    panels = [("c_sum[12]", r"$(E - E_0)/|E_0|$", None),
              ("c_sum[8]", r"$E_{kin}/E_{kin}(0)$", "ratio"),
              ("c_sum[7]", r"$L_z/L_z(0)$", "ratio")]
    if any("f_av[1]" in th for th in thermos):
        panels.append(("f_av[1]", r"mean $\alpha$", None))
    have_series = series is not None and any(s is not None for s in series)
    n = len(panels) + (1 if have_series else 0)
    fig, axes = plt.subplots(1, n, figsize=(4.3 * n, 3.8))
    for ax, (col, ylabel, mode) in zip(axes, panels):
        for k, (th, label) in enumerate(zip(thermos, labels)):
            if col not in th or "Time" not in th:
                continue
            y = th[col] / th[col][0] if mode == "ratio" and th[col][0] != 0 else th[col]
            ax.plot(th["Time"], y, "-", color=f"C{[0, 3, 2, 1][k % 4]}", label=label)
        ax.set_xlabel("t")
        ax.set_ylabel(ylabel)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    if have_series:
        ax = axes[-1]
        for k, (s, label) in enumerate(zip(series, labels)):
            if s is None:
                continue
            ax.plot(s[0], s[1], "o-", ms=3, color=f"C{[0, 3, 2, 1][k % 4]}", label=label)
        ax.set_xlabel("t")
        ax.set_ylabel(r"L1($v_\phi$)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def assert_values(err):
    """The --assert figures of a gresho_errors() result: l1 (= vphi), vr, P, rho."""
    return {"l1": err["vphi"], "vphi": err["vphi"], "vr": err["vr"], "P": err["p"],
            "p": err["p"], "rho": err["rho"]}
