"""The toy star of Monaghan & Price (2004, MNRAS 350, 1449; 2006, MNRAS 365, 991):
a polytrope P = k rho^(1+1/n) held by the linear force -lambda r per unit mass, in
equilibrium (v = 0), and the analysis of an SPH-ASTRO toy-star dump against it.

Equilibrium: 0 = -grad P / rho - lambda r gives

    rho(r) = [ lambda / (2 k (1 + n)) (R^2 - r^2) ]^n     for r < R, 0 outside,

and M = integral of rho over the ball of radius R fixes lambda:

    d = 3:  lambda = 2 k (1 + n) pi^(-3/(2n)) / R^2 [ M Gamma(5/2 + n) / (R^3 Gamma(1 + n)) ]^(1/n)
    d = 2:  lambda = 2 k pi^(-1/n) / M [ M (1 + n) / R^2 ]^(1 + 1/n)

(3D: M = 4 pi A^n R^(2n+3) int_0^1 s^2 (1 - s^2)^n ds = pi^(3/2) A^n R^(2n+3) Gamma(1+n) /
Gamma(5/2+n) with A = lambda / (2k(1+n)); the exponent of pi is -3/(2n),
not -3/2.)

Radius measures of an SPH star (``toystar_errors``):

* ``r_fit`` (the headline): rho^(1/n) = A R^2 - A r^2 is linear in r^2, so a least-squares
  line through (r_i^2, rho_i^(1/n)) of the particles with r_i < ``fit_fraction`` R gives
  A and R^2 = intercept / A. The surface layer, where the SPH density is smoothed over a
  kernel and the profile's slope is infinite for n < 1, is left out of the fit;
* ``r_rms``: from the mass-weighted mean square radius, <r^2> = 3 R^2 / (2n + 5) for the
  profile above, i.e. R = sqrt((2n + 5) <r^2> / 3) (uses positions only, not densities);
* ``r_max``: the outermost particle (it sits about one smoothing length beyond R).
"""

import math
import re

import numpy as np

__all__ = ["parse_log", "toystar_lambda", "density", "central_density", "enclosed_mass",
           "mean_square_radius", "toystar_errors", "plot_profile"]


def _check(M, R, k, n):
    if not (M > 0 and R > 0 and k > 0 and n > 0):
        raise ValueError(f"toy star needs M, R, k, n > 0 (got M={M}, R={R}, k={k}, n={n})")


def toystar_lambda(M, R, k, n, dim=3):
    """lambda of the linear force -lambda r for a toy star of mass M and radius R."""
    _check(M, R, k, n)
    if dim == 3:
        return (2.0 * k * (1.0 + n) * math.pi ** (-3.0 / (2.0 * n)) / R ** 2
                * (M * math.gamma(2.5 + n) / (R ** 3 * math.gamma(1.0 + n))) ** (1.0 / n))
    if dim == 2:
        return 2.0 * k * math.pi ** (-1.0 / n) / M * (M * (1.0 + n) / R ** 2) ** (1.0 + 1.0 / n)
    raise ValueError(f"dim must be 2 or 3 (got {dim})")


def density(r, M, R, k, n, dim=3):
    """Equilibrium density rho(r) = [lambda/(2k(1+n)) (R^2 - r^2)]^n, 0 for r >= R."""
    lam = toystar_lambda(M, R, k, n, dim)
    r = np.asarray(r, dtype=float)
    base = lam / (2.0 * k * (1.0 + n)) * np.clip(R * R - r * r, 0.0, None)
    return base ** n


def central_density(M, R, k, n, dim=3):
    return float(density(0.0, M, R, k, n, dim))


def enclosed_mass(r, M, R, k, n, npts=4001):
    """Mass of the 3D profile inside radius r, by Simpson's rule (for tests and set-ups)."""
    r = min(float(r), R)
    if r <= 0.0:
        return 0.0
    if npts % 2 == 0:
        npts += 1
    s = np.linspace(0.0, r, npts)
    f = 4.0 * math.pi * s * s * density(s, M, R, k, n)
    hstep = r / (npts - 1)
    return float(hstep / 3.0 * (f[0] + f[-1] + 4.0 * f[1:-1:2].sum() + 2.0 * f[2:-1:2].sum()))


def mean_square_radius(R, n):
    """Mass-weighted <r^2> of the 3D profile: 3 R^2 / (2n + 5)."""
    return 3.0 * R * R / (2.0 * n + 5.0)


def toystar_errors(columns, M, R, k, n, fit_fraction=0.8, masses=None):
    """Density and radius errors of an SPH toy star centred at the origin.

    ``columns``: dict (or dump frame ``.columns``) with x, y, z, rho and optionally vx, vy, vz.
    Returns a dict:

    * ``l1`` = mean_i |rho_i - rho(r_i)| over all particles, ``l1_rel`` = l1 / rho_c,
      ``l1_inner`` the same over r_i < fit_fraction R;
    * ``r_fit``, ``err_r_fit`` (headline radius, relative error), ``a_fit`` (the fitted
      lambda/(2k(1+n)), ``err_lambda`` its relative error);
    * ``r_rms``, ``err_r_rms``; ``r_max``, ``err_r_max``;
    * ``rho_c_sph`` (mean SPH density of the particles with r < 0.2 R) against ``rho_c``;
    * ``com`` distance of the centre of mass from the origin; ``vrms`` if velocities given.
    """
    _check(M, R, k, n)
    if hasattr(columns, "columns"):
        columns = columns.columns
    x, y, z = (np.asarray(columns[c], float) for c in ("x", "y", "z"))
    rho = np.asarray(columns["rho"], float)
    npart = len(x)
    m = np.full(npart, M / npart) if masses is None else np.asarray(masses, float)
    r = np.sqrt(x * x + y * y + z * z)
    exact = density(r, M, R, k, n)
    rho_c = central_density(M, R, k, n)
    out = {"n": npart, "rho_c": rho_c, "lambda": toystar_lambda(M, R, k, n)}
    out["l1"] = float(np.mean(np.abs(rho - exact)))
    out["l1_rel"] = out["l1"] / rho_c
    inner = r < fit_fraction * R
    out["n_inner"] = int(inner.sum())
    out["l1_inner"] = float(np.mean(np.abs(rho[inner] - exact[inner]))) if inner.any() else math.nan
    # rho^(1/n) = A R^2 - A r^2: a straight line in r^2
    if inner.sum() >= 3:
        slope, intercept = np.polyfit(r[inner] ** 2, np.clip(rho[inner], 0.0, None) ** (1.0 / n), 1)
        a_fit = -slope
        out["a_fit"] = float(a_fit)
        out["r_fit"] = float(math.sqrt(intercept / a_fit)) if a_fit > 0 and intercept > 0 else math.nan
    else:
        out["a_fit"] = out["r_fit"] = math.nan
    a_exact = out["lambda"] / (2.0 * k * (1.0 + n))
    out["err_lambda"] = out["a_fit"] / a_exact - 1.0
    out["err_r_fit"] = out["r_fit"] / R - 1.0
    msq = float(np.sum(m * r * r) / np.sum(m))
    out["r_rms"] = math.sqrt(msq / mean_square_radius(1.0, n))
    out["err_r_rms"] = out["r_rms"] / R - 1.0
    out["r_max"] = float(r.max())
    out["err_r_max"] = out["r_max"] / R - 1.0
    core = r < 0.2 * R
    out["rho_c_sph"] = float(rho[core].mean()) if core.any() else math.nan
    com = np.array([np.sum(m * x), np.sum(m * y), np.sum(m * z)]) / np.sum(m)
    out["com"] = float(np.linalg.norm(com))
    if all(c in columns for c in ("vx", "vy", "vz")):
        v2 = sum(np.asarray(columns[c], float) ** 2 for c in ("vx", "vy", "vz"))
        out["vrms"] = float(math.sqrt(np.sum(m * v2) / np.sum(m)))
        out["ekin"] = float(0.5 * np.sum(m * v2))
    return out


def plot_profile(frames, png, M, R, k, n, title=""):
    """rho_i against r_i for one or more frames ((label, columns) pairs) with rho(r)."""
    from matplotlib.figure import Figure
    fig = Figure(figsize=(6.4, 4.6))
    ax = fig.subplots()
    markers = ".x+"
    for j, (label, columns) in enumerate(frames):
        if hasattr(columns, "columns"):
            columns = columns.columns
        r = np.sqrt(sum(np.asarray(columns[c], float) ** 2 for c in ("x", "y", "z")))
        ax.plot(r, columns["rho"], markers[j % len(markers)], ms=2.5, alpha=0.5, label=label)
    s = np.linspace(0.0, 1.05 * R, 400)
    ax.plot(s, density(s, M, R, k, n), "k-", lw=1.5,
            label=r"$[\lambda/(2k(1+n))\,(R^2-r^2)]^n$")
    ax.set_xlabel("r")
    ax.set_ylabel(r"$\rho$")
    ax.set_xlim(0.0, None)
    ax.set_ylim(0.0, None)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    if title:
        ax.set_title(title, fontsize=9)
    fig.tight_layout()
    fig.savefig(png, dpi=130)
    return png


def parse_log(path):
    """Figures of the relaxation (compute sum) and the free run (compute free) from the LAMMPS
    log of examples/toystar/in.toystar."""
    out = {"ekin_relaxed": math.nan, "eth_relaxed": math.nan, "ekin_free_max": math.nan,
           "energy": math.nan, "energy_max": math.nan, "capped": math.nan, "steps": 0,
           "loop_s": 0.0, "natoms": 0, "procs": 0, "ekin_free_end": math.nan,
           "capped_steps": math.nan}
    header = None
    relax_rows, free_rows = [], []
    with open(path, encoding="utf-8", errors="replace") as f:
        for line in f:
            words = line.split()
            if words[:1] == ["Step"]:
                header = words
                continue
            m = re.search(r"largest over all steps (\S+)", line)
            if m and not line.startswith("print"):
                out["capped_steps"] = max(out["capped_steps"], float(m.group(1))) \
                    if math.isfinite(out["capped_steps"]) else float(m.group(1))
            if line.startswith("Loop time of"):
                header = None
                w = line.split()
                out["loop_s"] += float(w[3])
                out["procs"] = int(w[5])
                out["steps"] += int(w[8])
                out["natoms"] = int(w[11])
                continue
            if header is None or len(words) != len(header):
                continue
            try:
                row = dict(zip(header, (float(w) for w in words)))
            except ValueError:
                continue
            (free_rows if "c_free[8]" in header else relax_rows).append(row)
    if relax_rows:
        out["ekin_relaxed"] = relax_rows[-1]["c_sum[8]"]
        out["eth_relaxed"] = relax_rows[-1]["c_sum[9]"]
        out["capped"] = relax_rows[-1]["f_hvar[4]"]
    if free_rows:
        out["ekin_free_max"] = max(r["c_free[8]"] for r in free_rows)
        out["ekin_free_end"] = free_rows[-1]["c_free[8]"]
        out["energy"] = free_rows[-1]["c_free[12]"]
        out["energy_max"] = max(abs(r["c_free[12]"]) for r in free_rows)
        out["capped"] = max(r["f_hvar[4]"] for r in free_rows)
    # in.toystar prints the largest count over all steps of each phase (fix vector)
    if math.isfinite(out["capped_steps"]):
        out["capped"] = max(out["capped"], out["capped_steps"]) if math.isfinite(out["capped"]) \
            else out["capped_steps"]
    return out
