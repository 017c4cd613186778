"""Comparison of SPH shock-tube (Sod-type) results with the exact Riemann solution.

The particle data come from a :class:`sphastro.dump.Frame` (or any mapping of
column name -> array) with the columns ``x``, ``vx``, ``rho``, ``pressure`` and
``u`` (specific internal energy).  If one of ``pressure``/``u`` is missing it is
derived from the other with the ideal-gas law ``p = (gamma - 1) rho u``.

The exact solution is computed with :mod:`sphastro.riemann` (Toro, *Riemann
Solvers and Numerical Methods for Fluid Dynamics*, 3rd ed., ch. 4).
"""

import numpy as np

from . import riemann

__all__ = ["particle_columns", "exact_profile", "sod_errors", "plot_profiles"]

_QUANTITIES = (("rho", "rho"), ("vx", "vx"), ("p", "pressure"), ("u", "u"))


def particle_columns(frame, gamma):
    """Return ``x, {'rho', 'vx', 'p', 'u'}`` float arrays from a frame or a column mapping."""
    cols = getattr(frame, "columns", frame)
    missing = [name for name in ("x", "vx", "rho") if name not in cols]
    if "pressure" not in cols and "u" not in cols:
        missing.append("pressure or u")
    if missing:
        raise KeyError(f"particle data lack the column(s): {', '.join(missing)}")
    rho = np.asarray(cols["rho"], dtype=float)
    if "pressure" in cols:
        p = np.asarray(cols["pressure"], dtype=float)
    else:
        p = (gamma - 1.0) * rho * np.asarray(cols["u"], dtype=float)
    if "u" in cols:
        u = np.asarray(cols["u"], dtype=float)
    else:
        u = p / ((gamma - 1.0) * rho)
    return np.asarray(cols["x"], dtype=float), {
        "rho": rho, "vx": np.asarray(cols["vx"], dtype=float), "p": p, "u": u}


def exact_profile(x, gamma, t, left, right, x0=0.0, x_periodic=None):
    """Exact solution at positions ``x`` (dict with 'rho', 'vx', 'p', 'u').

    With ``x_periodic = (xlo, xhi)`` the tube is taken to be periodic in x, as
    in the usual periodic SPH shock-tube set-up: the initial condition then
    holds a second discontinuity at the boundary xlo = xhi (``right`` state on
    its left, ``left`` state on its right).  Positions are wrapped into
    [xlo, xhi) and the exact solution is the union of the two Riemann
    problems, which is exact as long as their waves have not met; a
    ``ValueError`` is raised otherwise.
    """
    x = np.asarray(x, dtype=float)
    if x_periodic is None:
        return riemann.sample(x, t, left, right, gamma, x0)

    xlo, xhi = (float(v) for v in x_periodic)
    if not xlo < x0 < xhi:
        raise ValueError(f"x0 = {x0} must lie inside the periodic interval ({xlo}, {xhi})")
    xw = xlo + np.mod(x - xlo, xhi - xlo)
    main = riemann.wave_positions(t, left, right, gamma, x0)
    edge_hi = riemann.wave_positions(t, right, left, gamma, xhi)   # boundary problem seen at xhi
    edge_lo = riemann.wave_positions(t, right, left, gamma, xlo)   # ... and at xlo
    if main["right_head"] > edge_hi["left_head"] or edge_lo["right_head"] > main["left_head"]:
        raise ValueError(f"at t = {t} the waves from x0 and from the periodic boundary "
                         "have met; the exact two-problem solution no longer applies")

    out = riemann.sample(xw, t, left, right, gamma, x0)
    near_hi = xw > main["right_head"]
    near_lo = xw < main["left_head"]
    for mask, x_edge in ((near_hi, xhi), (near_lo, xlo)):
        if np.any(mask):
            edge = riemann.sample(xw[mask], t, right, left, gamma, x_edge)
            for key in out:
                out[key][mask] = edge[key]
    return out


def sod_errors(frame, gamma, t, left=(1.0, 0.0, 1.0), right=(0.125, 0.0, 0.1), x0=0.0,
               xrange=(-0.5, 0.5), x_periodic=None):
    """Per-particle L1 errors against the exact Riemann solution.

    For each quantity q in rho, vx, p, u returns ``mean(|q_sph - q_exact|)``
    over the particles with ``xrange[0] <= x <= xrange[1]`` (positions taken
    after periodic wrapping if ``x_periodic`` is given, see
    :func:`exact_profile`).

    Parameters
    ----------
    frame : Frame or mapping
        Particle data with columns 'x', 'vx', 'rho', 'pressure', 'u'.
    gamma : float
        Ratio of specific heats.
    t : float
        Time since the discontinuity was released.
    left, right : tuple of float
        Initial states ``(rho, v, p)``.
    x0 : float
        Initial position of the discontinuity.
    xrange : (float, float)
        Measurement window.
    x_periodic : (float, float) or None
        Periodic x interval of the tube, or None for a single discontinuity.

    Returns
    -------
    dict
        ``{'rho': float, 'vx': float, 'p': float, 'u': float, 'n': int}``.
    """
    x, sph = particle_columns(frame, gamma)
    if x_periodic is not None:
        xlo, xhi = (float(v) for v in x_periodic)
        x = xlo + np.mod(x - xlo, xhi - xlo)
    sel = (x >= xrange[0]) & (x <= xrange[1])
    n = int(np.count_nonzero(sel))
    if n == 0:
        raise ValueError(f"no particles with {xrange[0]} <= x <= {xrange[1]}")
    exact = exact_profile(x[sel], gamma, t, left, right, x0, x_periodic)
    errors = {key: float(np.mean(np.abs(sph[key][sel] - exact[key]))) for key in exact}
    errors["n"] = n
    return errors


def assert_values(err):
    """The ``--assert`` figures of a :func:`sod_errors` result: rho, vx, P (or p), u."""
    return {"rho": err["rho"], "vx": err["vx"], "P": err["p"], "p": err["p"], "u": err["u"]}


def plot_profiles(frame, gamma, t, left, right, x0, png_path, xlim=None, title="",
                  x_periodic=None):
    """Write a 2x2 PNG of rho, vx, P and u versus x: particles as dots, exact solution as lines.

    ``xlim`` limits the horizontal axis (default: the particle x range);
    ``x_periodic`` is passed on to :func:`exact_profile`.  Returns ``png_path``.
    """
    from matplotlib.figure import Figure     # no pyplot: no GUI backend, no global state

    x, sph = particle_columns(frame, gamma)
    if x_periodic is not None:
        xlo, xhi = (float(v) for v in x_periodic)
        x = xlo + np.mod(x - xlo, xhi - xlo)
    lo, hi = xlim if xlim is not None else (float(x.min()), float(x.max()))
    xs = np.linspace(lo, hi, 4001)
    exact = exact_profile(xs, gamma, t, left, right, x0, x_periodic)

    fig = Figure(figsize=(10, 7))
    axes = fig.subplots(2, 2, sharex=True)
    labels = {"rho": r"$\rho$", "vx": r"$v_x$", "p": r"$P$", "u": r"$u$"}
    for ax, key in zip(axes.flat, ("rho", "vx", "p", "u")):
        ax.plot(x, sph[key], ".", ms=1.5, color="tab:blue", label="SPH", rasterized=True)
        ax.plot(xs, exact[key], "-", lw=1.0, color="black", label="exact")
        ax.set_ylabel(labels[key])
        ax.set_xlim(lo, hi)
        ax.grid(alpha=0.3)
    for ax in axes[1]:
        ax.set_xlabel("x")
    axes[0, 0].legend(loc="best", markerscale=4)
    fig.suptitle(title or f"t = {t:g}, gamma = {gamma:g}")
    fig.tight_layout()
    fig.savefig(png_path, dpi=150)
    return png_path
