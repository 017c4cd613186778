"""The Noh implosion (Noh 1987, J. Comput. Phys. 72, 78), 3D: the exact solution and the
measures of examples/noh/analyse.py and tools/error_vs_time.py.

For gamma = 5/3 the shock is at R_s = (gamma - 1) t / 2 = t/3; behind it
rho = ((gamma + 1)/(gamma - 1))^3 = 64, v = 0, u = 1/2; in front of it rho = (1 + t/r)^2,
v_r = -1 and u = u0 rho^(gamma - 1).
"""

import math
import re

import numpy as np

from .runs import parse_sph_log


def exact(r, t, gamma=5.0 / 3.0, u0=1e-6):
    """Exact Noh solution (3D) at radii r: dict of rho, v (radial), u, p."""
    r = np.asarray(r, dtype=float)
    rs = 0.5 * (gamma - 1.0) * t
    rho_post = ((gamma + 1.0) / (gamma - 1.0)) ** 3
    inside = r < rs
    with np.errstate(divide="ignore"):
        rho_pre = (1.0 + t / np.where(r > 0.0, r, np.inf)) ** 2
    rho = np.where(inside, rho_post, rho_pre)
    v = np.where(inside, 0.0, -1.0)
    u = np.where(inside, 0.5, u0 * rho_pre ** (gamma - 1.0))
    return {"rho": rho, "v": v, "u": u, "p": (gamma - 1.0) * rho * u}


def radial_columns(frame, gamma):
    c = frame.columns
    x, y, z = c["x"], c["y"], c["z"]
    r = np.sqrt(x * x + y * y + z * z)
    safe = np.where(r > 0.0, r, 1.0)
    vr = np.where(r > 0.0, (x * c["vx"] + y * c["vy"] + z * c["vz"]) / safe, 0.0)
    rho, u = c["rho"], c["u"]
    p = c["pressure"] if "pressure" in c else (gamma - 1.0) * rho * u
    return {"r": r, "v": vr, "rho": rho, "u": u, "p": p, "A": p / rho ** gamma}


def binned(r, q, edges):
    """Bin centres and means of q (nan in empty bins)."""
    idx = np.digitize(r, edges) - 1
    ok = (idx >= 0) & (idx < len(edges) - 1)
    n = np.bincount(idx[ok], minlength=len(edges) - 1)
    s = np.bincount(idx[ok], weights=q[ok], minlength=len(edges) - 1)
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = s / n
    return 0.5 * (edges[1:] + edges[:-1]), mean, n


def shock_radius(centres, rho_bin, threshold, rstart):
    """Radius where the binned density falls through threshold (a number, or an array over
    the bin centres), outside the densest bin at r > rstart (linear interpolation between bin
    centres); nan if it never does."""
    good = np.isfinite(rho_bin)
    c = centres[good]
    # with a threshold per bin: where rho_bin - threshold falls through 0
    level = np.broadcast_to(np.asarray(threshold, dtype=float), centres.shape)[good]
    q = rho_bin[good] - level
    threshold = 0.0
    beyond = np.nonzero(c > rstart)[0]
    if len(beyond) == 0:
        return math.nan
    k = beyond[np.argmax(q[beyond])]
    for j in range(k, len(c) - 1):
        if q[j] >= threshold > q[j + 1]:
            return c[j] + (threshold - q[j]) * (c[j + 1] - c[j]) / (q[j + 1] - q[j])
    return math.nan


def noh_measures(frame, t, gamma=5.0 / 3.0, u0=1e-6, radius=1.0, nbins=40,
                 window=(0.25, 0.75)):
    d = radial_columns(frame, gamma)
    rs = 0.5 * (gamma - 1.0) * t
    rho_post = ((gamma + 1.0) / (gamma - 1.0)) ** 3
    u_post = 0.5
    a_post = (gamma - 1.0) * u_post / rho_post ** (gamma - 1.0)
    rmax = radius - t                       # the gas moves inwards with |v| = 1
    edges = np.linspace(0.0, rmax, nbins + 1)
    centres, rho_bin, _ = binned(d["r"], d["rho"], edges)
    wlo, whi = window[0] * rs, window[1] * rs
    win = (d["r"] > wlo) & (d["r"] < whi)
    res = {"rs": rs, "rho_post_exact": rho_post, "wlo": wlo, "whi": whi,
           "n": len(d["r"]), "n_window": int(win.sum()), "bin_width": edges[1] - edges[0]}
    res["rho_post"] = float(d["rho"][win].mean()) if win.any() else math.nan
    res["err_rho_post"] = res["rho_post"] / rho_post - 1.0
    res["u_window"] = float(d["u"][win].mean()) if win.any() else math.nan
    res["r_shock"] = shock_radius(centres, rho_bin, 0.5 * res["rho_post"], wlo)
    res["err_r_shock"] = res["r_shock"] / rs - 1.0
    res["r_shock32"] = shock_radius(centres, rho_bin, 0.5 * rho_post, wlo)
    res["err_r_shock32"] = res["r_shock32"] / rs - 1.0
    with np.errstate(divide="ignore"):
        rho_pre = (1.0 + t / centres) ** 2
    res["r_shock_mid"] = shock_radius(centres, rho_bin, 0.5 * (res["rho_post"] + rho_pre), wlo)
    res["err_r_shock_mid"] = res["r_shock_mid"] / rs - 1.0
    res["umin"] = float(d["u"].min())
    res["n_negative_u"] = int((d["u"] < 0.0).sum())
    res["finite"] = bool(np.all(np.isfinite(d["rho"])) and np.all(np.isfinite(d["u"]))
                         and np.all(np.isfinite(d["v"])))
    centre = d["r"] < wlo
    res["n_centre"] = int(centre.sum())
    res["u_centre"] = float(d["u"][centre].mean()) if centre.any() else math.nan
    res["rho_centre"] = float(d["rho"][centre].mean()) if centre.any() else math.nan
    res["A_centre"] = float(d["A"][centre].mean()) if centre.any() else math.nan
    i0 = int(np.argmin(d["r"]))
    res["u_innermost"], res["rho_innermost"], res["r_innermost"] = (
        float(d["u"][i0]), float(d["rho"][i0]), float(d["r"][i0]))
    res["wallheat"] = res["u_centre"] / u_post
    res["A_post"] = a_post
    # pre-shock gas: from 1.25 R_s to where the free surface (at radius - t) is felt; the
    # surface deficit reaches ~2 h inwards, h of the pre-shock gas there
    hsurf = float(np.median(frame.columns["h"][d["r"] > 0.9 * rmax])) if "h" in frame.columns \
        else 0.05
    pre = (d["r"] > 1.5 * rs) & (d["r"] < rmax - 2.0 * hsurf)
    res["pre_range"] = (1.5 * rs, rmax - 2.0 * hsurf)
    res["n_pre"] = int(pre.sum())
    if pre.any():
        ex = exact(d["r"][pre], t, gamma, u0)
        res["u_pre"] = float(d["u"][pre].mean())
        res["v_pre"] = float(d["v"][pre].mean())
        res["rho_pre_ratio"] = float((d["rho"][pre] / ex["rho"]).mean())
    else:
        res["u_pre"] = res["v_pre"] = res["rho_pre_ratio"] = math.nan
    sel = d["r"] < 1.5 * rs
    ex = exact(d["r"][sel], t, gamma, u0)
    res["l1rho"] = float(np.abs(d["rho"][sel] - ex["rho"]).mean() / rho_post)
    return res, d


def parse_log(path):
    """Energy error, capped particles and run size from the scene's LAMMPS log; ``capped_steps``:
    the largest number of particles at the h cap over all steps (in.noh's final print of its
    fix vector of f_hvar[4]; nan if absent), ``widenings``: ghost-cutoff widenings of fix
    sph/astro/h (its log lines)."""
    out = parse_sph_log(path, loops="sum")
    out["capped_steps"] = math.nan
    out["widenings"] = 0
    with open(path, encoding="utf-8", errors="replace") as f:
        for line in f:
            m = re.search(r"largest over all steps (\S+)", line)
            if m and not line.startswith("print"):
                out["capped_steps"] = float(m.group(1))
            if line.startswith("fix sph/astro/h: ghost cutoff widened"):
                out["widenings"] += 1
    return out
