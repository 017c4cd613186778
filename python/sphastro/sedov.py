"""Self-similar Sedov-Taylor solution of a point explosion in a uniform, cold medium.

A total energy ``E`` released at ``r = 0`` and ``t = 0`` in a uniform gas of density
``rho0`` and zero pressure (ideal gas, ratio of specific heats ``gamma``, 3D, spherical
symmetry) drives a strong shock whose radius is

    R_s(t) = xi0(gamma) * (E t^2 / rho0)^(1/5).

Inside the shock the flow is self-similar in ``xi = r / R_s``.  With Landau and Lifshitz's
variables (Fluid Mechanics, 2nd ed., sec. 106; the same closed form as Sedov, Similarity
and Dimensional Methods in Mechanics, 1959, ch. IV, and Kamm & Timmes 2007, "On efficient
generation of numerically robust Sedov solutions", LA-UR-07-2849, "standard case" with
j = 3, w = 0)

    v = (2 r / (5 t)) V,    c^2 = (2 r / (5 t))^2 Z,    rho = rho0 G,

the parameter ``V`` runs from ``2/(gamma+1)`` at the shock (``xi = 1``) to ``1/gamma`` at
the centre (``xi = 0``), and

    xi^5 = [(gamma+1) V / 2]^-2  b1^nu1  b2^nu2
    G    = (gamma+1)/(gamma-1)  b2^nu3  b1^nu4  b3^nu5
    Z    = gamma (gamma-1) (1-V) V^2 / (2 (gamma V - 1))

with ``b1 = (gamma+1)/(7-gamma) [5 - (3 gamma - 1) V]``, ``b2 = (gamma+1)/(gamma-1)
(gamma V - 1)``, ``b3 = (gamma+1)/(gamma-1) (1 - V)`` and

    nu1 = -(13 gamma^2 - 7 gamma + 12) / ((3 gamma - 1)(2 gamma + 1))
    nu2 = 5 (gamma - 1) / (2 gamma + 1)
    nu3 = 3 / (2 gamma + 1)
    nu4 = -nu1 / (2 - gamma)
    nu5 = -2 / (2 - gamma).

The pressure ``p = rho c^2 / gamma`` is evaluated in a form in which the powers of ``b2``
cancel, so that it stays finite and accurate at the centre.  ``xi0`` follows from energy
conservation,

    E = (16 pi / 25) rho0 R_s^5 / t^2  *  I,
    I = int_0^1 [ G xi^2 V^2 / 2 + P / (gamma - 1) ] xi^2 d xi,     P = p / (rho0 Rdot^2),

i.e. ``xi0 = (25 / (16 pi I))^(1/5)``, with ``I`` integrated numerically (Gauss-Legendre
quadrature in ``xi``; ``V(xi)`` is found by bisection in ``log b2``, which resolves the
steep centre where ``gamma V - 1`` falls below double-precision resolution of ``V``).
Values: xi0 = 1.15167 for gamma = 5/3 and 1.03275 for gamma = 1.4 (Kamm & Timmes, table 1
and sec. 4; Landau & Lifshitz quote 1.033 for 7/5).

Valid for 1 < gamma < 7 (at gamma >= 7 the uniform-medium solution has a vacuum core,
Kamm & Timmes' "vacuum case").  At gamma = 2 the exponents nu4, nu5 are singular while
their product is not (Kamm & Timmes' singular case w = w3 = j (2 - gamma)); there the
solution is the mean of those at gamma = 2 -+ 1e-5, accurate to about 1e-9.

Functions: :func:`xi0`, :func:`shock_radius`, :func:`profile`, :func:`energy_integral`,
:func:`post_shock`.  Comparison with particle data (a :class:`sphastro.dump.Frame` with
columns x, y, z, vx, vy, vz, rho, pressure, u): :func:`radial_columns`,
:func:`binned_profile`, :func:`shock_measures`, :func:`sedov_errors`, :func:`plot_profiles`.
"""

import functools
import math

import numpy as np

__all__ = ["xi0", "shock_radius", "shock_velocity", "post_shock", "profile",
           "energy_integral", "mass_integral", "similarity_profile", "radial_columns",
           "binned_profile", "shock_measures", "sedov_errors", "plot_profiles"]

_GAMMA_SINGULAR = 2.0
_SINGULAR_HALF_WIDTH = 1e-5
_BISECTION_STEPS = 80
_LOG_S_MIN = -700.0          # b2 = exp(-700): xi ~ 1e-60 for gamma = 5/3


def _check_gamma(gamma):
    gamma = float(gamma)
    if not 1.0 < gamma < 7.0:
        raise ValueError(f"gamma = {gamma} outside the range 1 < gamma < 7 of the "
                         "uniform-medium Sedov solution")
    return gamma


def _exponents(gamma):
    nu1 = -(13.0 * gamma ** 2 - 7.0 * gamma + 12.0) / ((3.0 * gamma - 1.0) * (2.0 * gamma + 1.0))
    nu2 = 5.0 * (gamma - 1.0) / (2.0 * gamma + 1.0)
    nu3 = 3.0 / (2.0 * gamma + 1.0)
    nu4 = -nu1 / (2.0 - gamma)
    nu5 = -2.0 / (2.0 - gamma)
    return nu1, nu2, nu3, nu4, nu5


def _state_of_log_s(log_s, gamma):
    """Dimensionless xi, V, G, P (= p / (rho0 Rdot^2)) as functions of log b2, b2 in (0, 1]."""
    g = gamma
    nu1, nu2, nu3, nu4, nu5 = _exponents(g)
    s = np.exp(log_s)                                   # b2
    v = (1.0 + s * (g - 1.0) / (g + 1.0)) / g           # V
    log_a = np.log(0.5 * (g + 1.0) * v)
    log_b1 = np.log((g + 1.0) / (7.0 - g) * (5.0 - (3.0 * g - 1.0) * v))
    log_b3 = np.log((g + 1.0) / (g - 1.0) * (1.0 - v))
    log_xi = (-2.0 * log_a + nu1 * log_b1 + nu2 * log_s) / 5.0
    log_g0 = math.log((g + 1.0) / (g - 1.0))
    log_G = log_g0 + nu3 * log_s + nu4 * log_b1 + nu5 * log_b3
    # P = G xi^2 Z / gamma with Z = gamma (gamma+1) (1-V) V^2 / (2 b2): the powers of b2,
    # nu3 + 2 nu2 / 5 - 1, cancel exactly and are left out.
    log_P = (log_g0 + math.log(0.5 * (g + 1.0)) + np.log((1.0 - v) * v * v)
             + (-2.0 * log_a + nu1 * log_b1) * 0.4 + nu4 * log_b1 + nu5 * log_b3)
    return np.exp(log_xi), v, np.exp(log_G), np.exp(log_P)


def _similarity_regular(xi, gamma):
    xi = np.asarray(xi, dtype=float)
    lo = np.full(xi.shape, _LOG_S_MIN)
    hi = np.zeros(xi.shape)
    target = np.log(np.clip(xi, 1e-300, 1.0))
    for _ in range(_BISECTION_STEPS):            # xi(b2) increases monotonically
        mid = 0.5 * (lo + hi)
        x_mid = _state_of_log_s(mid, gamma)[0]
        below = np.log(x_mid) < target
        lo = np.where(below, mid, lo)
        hi = np.where(below, hi, mid)
    _, v, g_, p_ = _state_of_log_s(0.5 * (lo + hi), gamma)
    # exact centre values: V = 1/gamma, G = 0, P finite
    centre = xi <= 0.0
    if np.any(centre):
        _, vc, _, pc = _state_of_log_s(np.array([_LOG_S_MIN]), gamma)
        v = np.where(centre, 1.0 / gamma, v)
        g_ = np.where(centre, 0.0, g_)
        p_ = np.where(centre, pc[0], p_)
    return v, g_, p_


def similarity_profile(xi, gamma):
    """Dimensionless profile at ``xi = r / R_s`` in [0, 1]: ``(V, G, P)``.

    ``v = Rdot xi V``, ``rho = rho0 G``, ``p = rho0 Rdot^2 P`` with ``Rdot = dR_s/dt =
    2 R_s / (5 t)``.  Values of xi outside [0, 1] are clipped.
    """
    gamma = _check_gamma(gamma)
    xi = np.clip(np.asarray(xi, dtype=float), 0.0, 1.0)
    if abs(gamma - _GAMMA_SINGULAR) < _SINGULAR_HALF_WIDTH:
        a = _similarity_regular(xi, _GAMMA_SINGULAR - _SINGULAR_HALF_WIDTH)
        b = _similarity_regular(xi, _GAMMA_SINGULAR + _SINGULAR_HALF_WIDTH)
        w = (gamma - (_GAMMA_SINGULAR - _SINGULAR_HALF_WIDTH)) / (2.0 * _SINGULAR_HALF_WIDTH)
        return tuple((1.0 - w) * qa + w * qb for qa, qb in zip(a, b))
    return _similarity_regular(xi, gamma)


def _gauss_legendre(n):
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (x + 1.0), 0.5 * w


def energy_integral(gamma, n=400):
    """``I(gamma) = int_0^1 [G xi^2 V^2 / 2 + P / (gamma - 1)] xi^2 dxi`` (Gauss-Legendre, n points)."""
    gamma = _check_gamma(gamma)
    # the integrand has fractional powers of xi near the centre: split [0, 1] so that the
    # rule converges quickly (checked against n = 2000 to better than 1e-10)
    edges = np.array([0.0, 0.25, 0.5, 0.75, 0.9, 1.0])
    x, w = _gauss_legendre(n // (len(edges) - 1))
    total = 0.0
    for a, b in zip(edges[:-1], edges[1:]):
        xi = a + (b - a) * x
        v, g_, p_ = similarity_profile(xi, gamma)
        f = (0.5 * g_ * (xi * v) ** 2 + p_ / (gamma - 1.0)) * xi * xi
        total += (b - a) * float(np.dot(w, f))
    return total


def mass_integral(gamma, n=400):
    """``int_0^1 G xi^2 dxi``; mass conservation requires 1/3 (a check of the profile)."""
    gamma = _check_gamma(gamma)
    edges = np.array([0.0, 0.25, 0.5, 0.75, 0.9, 1.0])
    x, w = _gauss_legendre(n // (len(edges) - 1))
    total = 0.0
    for a, b in zip(edges[:-1], edges[1:]):
        xi = a + (b - a) * x
        g_ = similarity_profile(xi, gamma)[1]
        total += (b - a) * float(np.dot(w, g_ * xi * xi))
    return total


@functools.lru_cache(maxsize=64)
def xi0(gamma):
    """Dimensionless shock-radius constant ``xi0(gamma)`` from energy conservation."""
    gamma = _check_gamma(gamma)
    return (25.0 / (16.0 * math.pi * energy_integral(gamma))) ** 0.2


def shock_radius(E, rho0, t, gamma):
    """Shock radius ``R_s = xi0 (E t^2 / rho0)^(1/5)``."""
    return xi0(float(gamma)) * (float(E) * float(t) ** 2 / float(rho0)) ** 0.2


def shock_velocity(E, rho0, t, gamma):
    """Shock speed ``dR_s/dt = 2 R_s / (5 t)``."""
    return 0.4 * shock_radius(E, rho0, t, gamma) / float(t)


def post_shock(E, rho0, t, gamma):
    """Strong-shock (Rankine-Hugoniot) state just behind the shock: dict rho, v, p, u."""
    gamma = float(gamma)
    d = shock_velocity(E, rho0, t, gamma)
    rho = (gamma + 1.0) / (gamma - 1.0) * rho0
    v = 2.0 / (gamma + 1.0) * d
    p = 2.0 / (gamma + 1.0) * rho0 * d * d
    return {"rho": rho, "v": v, "p": p, "u": p / ((gamma - 1.0) * rho)}


def profile(r, E, rho0, t, gamma, p0=0.0):
    """Sedov-Taylor solution at radii ``r`` (array) and time ``t``.

    Returns a dict of arrays ``rho`` (density), ``v`` (radial velocity), ``p`` (pressure),
    ``u`` (specific internal energy ``p / ((gamma - 1) rho)``; ``inf`` at ``r = 0``).
    Outside the shock (``r > R_s``) the gas is at rest with density ``rho0`` and pressure
    ``p0`` (default 0, the cold medium of the self-similar solution).  ``r = R_s`` belongs
    to the shocked side.
    """
    gamma = _check_gamma(gamma)
    r = np.abs(np.asarray(r, dtype=float))
    rs = shock_radius(E, rho0, t, gamma)
    d = 0.4 * rs / float(t)
    xi = r / rs
    inside = xi <= 1.0
    v_, g_, p_ = similarity_profile(np.where(inside, xi, 1.0), gamma)
    rho = np.where(inside, rho0 * g_, rho0)
    vel = np.where(inside, d * xi * v_, 0.0)
    p = np.where(inside, rho0 * d * d * p_, p0)
    with np.errstate(divide="ignore", invalid="ignore"):
        u = np.where(rho > 0.0, p / ((gamma - 1.0) * np.where(rho > 0.0, rho, 1.0)), np.inf)
    return {"rho": rho, "v": vel, "p": p, "u": u}


# --------------------------------------------------------------------------------------------
# comparison with SPH particle data


def radial_columns(frame, centre=(0.0, 0.0, 0.0), gamma=5.0 / 3.0):
    """Radius and radial fields of particle data about ``centre``.

    ``frame`` is a :class:`sphastro.dump.Frame` (positions are taken to the nearest periodic
    image of ``centre`` within its box) or a mapping of columns.  Returns a dict of arrays
    ``r``, ``v`` (radial velocity ``x.v / r``), ``rho``, ``p``, ``u`` (``p`` from
    ``(gamma - 1) rho u`` if the data have no pressure column, and the other way round).
    """
    cols = getattr(frame, "columns", frame)
    box = getattr(frame, "box", None)
    d = []
    for k, name in enumerate(("x", "y", "z")):
        x = np.asarray(cols[name], dtype=float) - centre[k]
        if box is not None:
            length = box[k][1] - box[k][0]
            x = x - length * np.round(x / length)
        d.append(x)
    d = np.array(d)
    r = np.sqrt(np.sum(d * d, axis=0))
    vel = np.array([np.asarray(cols[name], dtype=float) for name in ("vx", "vy", "vz")])
    with np.errstate(invalid="ignore", divide="ignore"):
        vr = np.where(r > 0.0, np.sum(d * vel, axis=0) / np.where(r > 0.0, r, 1.0), 0.0)
    rho = np.asarray(cols["rho"], dtype=float)
    if "pressure" in cols:
        p = np.asarray(cols["pressure"], dtype=float)
        u = (np.asarray(cols["u"], dtype=float) if "u" in cols
             else p / ((gamma - 1.0) * rho))
    else:
        u = np.asarray(cols["u"], dtype=float)
        p = (gamma - 1.0) * rho * u
    return {"r": r, "v": vr, "rho": rho, "p": p, "u": u, "v2": np.sum(vel * vel, axis=0)}


def binned_profile(r, q, edges):
    """Mean of ``q`` in radial bins ``edges``: (bin centres, means (nan if empty), counts)."""
    r = np.asarray(r, dtype=float)
    q = np.asarray(q, dtype=float)
    idx = np.digitize(r, edges) - 1
    ok = (idx >= 0) & (idx < len(edges) - 1)
    counts = np.bincount(idx[ok], minlength=len(edges) - 1)
    sums = np.bincount(idx[ok], weights=q[ok], minlength=len(edges) - 1)
    with np.errstate(invalid="ignore", divide="ignore"):
        means = np.where(counts > 0, sums / np.maximum(counts, 1), np.nan)
    return 0.5 * (edges[:-1] + edges[1:]), means, counts


def shock_measures(r, rho, rs, rho0=1.0, nbins=60, rmax_factor=1.2):
    """Shock position and peak density from the binned radial density profile.

    The density of the particles with ``r < rmax_factor * rs`` is averaged in ``nbins``
    equal radial bins.  Returns a dict:

    * ``rho_peak``: the largest bin mean;
    * ``r_peak``: radius of that maximum, refined by the vertex of the parabola through
      the peak bin and its two neighbours;
    * ``r_half``: radius outside the peak where the bin means fall through
      ``(rho0 + rho_peak) / 2`` (linear interpolation between bin centres): the centre of
      the smoothed density jump;
    * ``bin_width``, ``centres``, ``means``, ``counts``: the binned profile.
    """
    edges = np.linspace(0.0, rmax_factor * rs, nbins + 1)
    centres, means, counts = binned_profile(r, rho, edges)
    filled = np.where(counts > 0, means, -np.inf)
    k = int(np.argmax(filled))
    rho_peak = float(means[k])
    r_peak = float(centres[k])
    if 0 < k < nbins - 1 and counts[k - 1] > 0 and counts[k + 1] > 0:
        y0, y1, y2 = means[k - 1], means[k], means[k + 1]
        curv = y0 - 2.0 * y1 + y2
        if curv < 0.0:
            r_peak += 0.5 * (y0 - y2) / curv * (edges[1] - edges[0])
    level = 0.5 * (rho0 + rho_peak)
    r_half = float("nan")
    # between consecutive non-empty bins: on a coarse lattice a bin may hold no particle, and
    # the crossing may straddle it
    prev = k
    for j in range(k + 1, nbins):
        if counts[j] == 0:
            continue
        if means[prev] >= level > means[j]:
            frac = (means[prev] - level) / (means[prev] - means[j])
            r_half = float(centres[prev] + frac * (centres[j] - centres[prev]))
            break
        prev = j
    return {"rho_peak": rho_peak, "r_peak": r_peak, "r_half": r_half,
            "bin_width": float(edges[1] - edges[0]), "centres": centres, "means": means,
            "counts": counts}


def sedov_errors(frame, t, E=1.0, rho0=1.0, gamma=5.0 / 3.0, centre=(0.0, 0.0, 0.0),
                 rmax_factor=1.2, nbins=60):
    """Compare SPH particle data with the Sedov-Taylor solution.

    Returns a dict of floats:

    * ``rs``: analytic shock radius; ``r_half``, ``r_peak``: shock radius from the binned
      density (:func:`shock_measures`) and ``err_r_half``, ``err_r_peak`` their relative
      errors ``(r - rs) / rs`` (negative: inside the analytic shock);
    * ``rho_peak``: binned peak density (strong-shock value ``(gamma+1)/(gamma-1) rho0``);
    * ``rho``, ``v``, ``p``: per-particle L1 errors ``mean |q_sph - q_exact(r)|`` of density,
      radial velocity and pressure over the ``n`` particles with ``r < rmax_factor * rs``;
    * ``e_particles``: kinetic + thermal energy of all particles, ``sum m (v^2/2 + u)`` with
      equal masses ``m = rho0 V_box / N`` (needs the frame's box; nan without it);
    * ``bin_width``.
    """
    data = radial_columns(frame, centre, gamma)
    rs = shock_radius(E, rho0, t, gamma)
    sel = data["r"] < rmax_factor * rs
    n = int(np.count_nonzero(sel))
    if n == 0:
        raise ValueError(f"no particles within {rmax_factor} R_s = {rmax_factor * rs:g}")
    exact = profile(data["r"][sel], E, rho0, t, gamma)
    out = {"rs": rs, "n": n, "t": float(t)}
    for key in ("rho", "v", "p"):
        out[key] = float(np.mean(np.abs(data[key][sel] - exact[key])))
    shock = shock_measures(data["r"], data["rho"], rs, rho0, nbins, rmax_factor)
    for key in ("rho_peak", "r_peak", "r_half", "bin_width"):
        out[key] = shock[key]
    out["err_r_half"] = (shock["r_half"] - rs) / rs
    out["err_r_peak"] = (shock["r_peak"] - rs) / rs
    box = getattr(frame, "box", None)
    if box is not None:
        mass = rho0 * float(np.prod(box[:, 1] - box[:, 0])) / len(data["r"])
        out["e_particles"] = float(mass * np.sum(0.5 * data["v2"] + data["u"]))
    else:
        out["e_particles"] = float("nan")
    return out


def plot_profiles(frame, t, png_path, E=1.0, rho0=1.0, gamma=5.0 / 3.0,
                  centre=(0.0, 0.0, 0.0), rmax=None, nbins=60, title=""):
    """Write a PNG of density, radial velocity and pressure against radius.

    Particles as dots, their binned means as markers, the Sedov-Taylor solution as lines;
    the analytic shock radius is marked.  Returns ``png_path``.
    """
    from matplotlib.figure import Figure     # no pyplot: no GUI backend, no global state

    data = radial_columns(frame, centre, gamma)
    rs = shock_radius(E, rho0, t, gamma)
    rmax = rmax if rmax is not None else 1.3 * rs
    rr = np.linspace(0.0, rmax, 2001)
    exact = profile(rr, E, rho0, t, gamma)
    edges = np.linspace(0.0, rmax, int(round(nbins * rmax / (1.2 * rs))) + 1)
    sel = data["r"] < rmax
    fig = Figure(figsize=(13, 4.2))
    axes = fig.subplots(1, 3)
    labels = {"rho": r"$\rho$", "v": r"$v_r$", "p": r"$P$"}
    for ax, key in zip(axes, ("rho", "v", "p")):
        ax.plot(data["r"][sel], data[key][sel], ".", ms=1.0, alpha=0.4, color="tab:blue",
                label="SPH particles", rasterized=True)
        centres, means, _ = binned_profile(data["r"], data[key], edges)
        ax.plot(centres, means, "o", ms=3, color="tab:red", label="SPH, binned")
        ax.plot(rr, exact[key], "-", lw=1.2, color="black", label="Sedov-Taylor")
        ax.axvline(rs, color="grey", lw=0.8, ls=":")
        ax.set_xlabel("r")
        ax.set_ylabel(labels[key])
        ax.set_xlim(0.0, rmax)
        ax.grid(alpha=0.3)
    axes[0].legend(loc="upper left", markerscale=3, fontsize=8)
    fig.suptitle(title or f"Sedov-Taylor, t = {t:g}, gamma = {gamma:g}, E = {E:g}")
    fig.tight_layout()
    fig.savefig(png_path, dpi=140)
    return png_path
