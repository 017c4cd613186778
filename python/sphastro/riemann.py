"""Exact Riemann solver for the one-dimensional Euler equations of an ideal gas.

The implementation follows E. F. Toro, *Riemann Solvers and Numerical Methods for
Fluid Dynamics*, 3rd edition (Springer, 2009), chapter 4:

* the pressure functions f_L, f_R and their derivatives (Sect. 4.2 and 4.3.1,
  eqs. 4.6-4.7 and 4.37),
* the Newton-Raphson iteration for the star pressure p* (Sect. 4.3.1, eq. 4.44)
  started from the two-rarefaction approximation (eq. 4.46),
* the star-region velocity (eq. 4.9) and densities behind shocks (eqs. 4.50,
  4.57) and rarefactions (eqs. 4.53, 4.60),
* the sampling of the complete wave pattern, including the interior of
  rarefaction fans (Sect. 4.4-4.5, eqs. 4.55-4.56 and 4.62-4.63),
* the pressure-positivity (vacuum generation) condition (Sect. 4.6, eq. 4.82).

States are tuples ``(rho, v, p)`` of density, velocity and pressure.  Vacuum
initial data or data that generate vacuum are rejected with ``ValueError``.
"""

import math

import numpy as np

__all__ = ["pressure_function", "star_state", "sample", "wave_positions"]

#: Relative change of p* between Newton iterations at which the iteration stops.
NEWTON_TOLERANCE = 1.0e-14
#: Upper bound on the number of Newton-Raphson iterations.
NEWTON_MAX_ITERATIONS = 100


def _check_state(state, gamma, side):
    """Validate a primitive state and return ``(rho, v, p, a)`` with sound speed ``a``."""
    rho, v, p = (float(q) for q in state)
    if not gamma > 1.0:
        raise ValueError(f"gamma must exceed 1, got {gamma}")
    if not (rho > 0.0 and p > 0.0):
        raise ValueError(f"{side} state {state!r}: density and pressure must be positive "
                         "(vacuum initial data are not supported)")
    return rho, v, p, math.sqrt(gamma * p / rho)


def pressure_function(p, rho_k, p_k, gamma):
    """Toro's pressure function f_K(p) and its derivative for the side K (eqs. 4.6-4.7, 4.37).

    For ``p > p_k`` the K wave is a shock (Rankine-Hugoniot), otherwise a
    rarefaction (isentropic).  Returns ``(f, df/dp)``.
    """
    a_k = math.sqrt(gamma * p_k / rho_k)
    if p > p_k:
        big_a = 2.0 / ((gamma + 1.0) * rho_k)
        big_b = (gamma - 1.0) / (gamma + 1.0) * p_k
        root = math.sqrt(big_a / (big_b + p))
        f = (p - p_k) * root
        df = root * (1.0 - 0.5 * (p - p_k) / (big_b + p))
    else:
        ratio = p / p_k
        f = 2.0 * a_k / (gamma - 1.0) * (ratio ** ((gamma - 1.0) / (2.0 * gamma)) - 1.0)
        df = ratio ** (-(gamma + 1.0) / (2.0 * gamma)) / (rho_k * a_k)
    return f, df


def star_state(left, right, gamma):
    """Solve for the star region between the left and right non-linear waves.

    Parameters
    ----------
    left, right : tuple of float
        Initial states ``(rho, v, p)`` to the left and right of the discontinuity.
    gamma : float
        Ratio of specific heats (> 1).

    Returns
    -------
    (p_star, v_star, rho_star_left, rho_star_right)

    Raises
    ------
    ValueError
        For non-positive density or pressure, or if the data generate vacuum
        (Toro eq. 4.82).
    RuntimeError
        If the Newton-Raphson iteration does not converge.
    """
    rho_l, v_l, p_l, a_l = _check_state(left, gamma, "left")
    rho_r, v_r, p_r, a_r = _check_state(right, gamma, "right")
    dv = v_r - v_l
    if 2.0 * (a_l + a_r) / (gamma - 1.0) <= dv:
        raise ValueError("the initial data generate vacuum (Toro eq. 4.82); "
                         "the non-vacuum exact solver does not apply")

    # Two-rarefaction approximation as starting guess (Toro eq. 4.46).
    z = (gamma - 1.0) / (2.0 * gamma)
    p_old = ((a_l + a_r - 0.5 * (gamma - 1.0) * dv)
             / (a_l / p_l ** z + a_r / p_r ** z)) ** (1.0 / z)

    # Newton-Raphson iteration on f(p) = f_L(p) + f_R(p) + dv (Toro eq. 4.44).
    # f is monotone increasing and concave, so the iteration converges; negative
    # iterates are reset to a tiny positive pressure as in Toro's STARPU.
    for _ in range(NEWTON_MAX_ITERATIONS):
        f_l, df_l = pressure_function(p_old, rho_l, p_l, gamma)
        f_r, df_r = pressure_function(p_old, rho_r, p_r, gamma)
        p_new = p_old - (f_l + f_r + dv) / (df_l + df_r)
        if p_new <= 0.0:
            p_new = NEWTON_TOLERANCE * min(p_l, p_r)
        change = 2.0 * abs(p_new - p_old) / (p_new + p_old)
        p_old = p_new
        if change <= NEWTON_TOLERANCE:
            break
    else:
        raise RuntimeError("Newton-Raphson iteration for p* did not converge")
    p_star = p_old

    # Star velocity (Toro eq. 4.9).
    f_l, _ = pressure_function(p_star, rho_l, p_l, gamma)
    f_r, _ = pressure_function(p_star, rho_r, p_r, gamma)
    v_star = 0.5 * (v_l + v_r) + 0.5 * (f_r - f_l)

    return p_star, v_star, _star_density(p_star, rho_l, p_l, gamma), \
        _star_density(p_star, rho_r, p_r, gamma)


def _star_density(p_star, rho_k, p_k, gamma):
    """Density behind the K wave: shock (eqs. 4.50, 4.57) or rarefaction (eqs. 4.53, 4.60)."""
    ratio = p_star / p_k
    if p_star > p_k:
        g = (gamma - 1.0) / (gamma + 1.0)
        return rho_k * (ratio + g) / (g * ratio + 1.0)
    return rho_k * ratio ** (1.0 / gamma)


def _wave_speeds(left, right, gamma):
    """Star state plus the (head, tail) speeds of the left and right waves.

    For a shock, head and tail coincide with the shock speed (Toro eqs. 4.52,
    4.59); for a rarefaction they are the characteristic speeds bounding the fan
    (eqs. 4.55, 4.62).  The *head* is the edge facing the undisturbed state.
    """
    p_star, v_star, rho_sl, rho_sr = star_state(left, right, gamma)
    rho_l, v_l, p_l, a_l = _check_state(left, gamma, "left")
    rho_r, v_r, p_r, a_r = _check_state(right, gamma, "right")
    g1 = (gamma + 1.0) / (2.0 * gamma)
    g2 = (gamma - 1.0) / (2.0 * gamma)
    if p_star > p_l:
        s = v_l - a_l * math.sqrt(g1 * p_star / p_l + g2)
        left_wave = ("shock", s, s)
    else:
        left_wave = ("rarefaction", v_l - a_l, v_star - a_l * (p_star / p_l) ** g2)
    if p_star > p_r:
        s = v_r + a_r * math.sqrt(g1 * p_star / p_r + g2)
        right_wave = ("shock", s, s)
    else:
        right_wave = ("rarefaction", v_r + a_r, v_star + a_r * (p_star / p_r) ** g2)
    return (p_star, v_star, rho_sl, rho_sr), left_wave, right_wave


def sample(x, t, left, right, gamma, x0=0.0):
    """Sample the exact similarity solution at positions ``x`` and time ``t > 0``.

    Parameters
    ----------
    x : array_like
        Positions at which to evaluate the solution.
    t : float
        Time since the discontinuity at ``x0`` was released (must be positive).
    left, right : tuple of float
        Initial states ``(rho, v, p)``.
    gamma : float
        Ratio of specific heats.
    x0 : float
        Initial position of the discontinuity.

    Returns
    -------
    dict of numpy.ndarray
        ``'rho'``, ``'vx'``, ``'p'`` and ``'u'`` (specific internal energy
        ``p / ((gamma - 1) rho)``), each with the shape of ``x``.
    """
    if not t > 0.0:
        raise ValueError(f"sample() needs t > 0, got {t}")
    (p_star, v_star, rho_sl, rho_sr), (l_kind, l_head, l_tail), (r_kind, r_head, r_tail) = \
        _wave_speeds(left, right, gamma)
    rho_l, v_l, p_l, a_l = _check_state(left, gamma, "left")
    rho_r, v_r, p_r, a_r = _check_state(right, gamma, "right")

    s = (np.asarray(x, dtype=float) - x0) / t          # similarity variable x/t
    rho = np.empty_like(s)
    vel = np.empty_like(s)
    prs = np.empty_like(s)

    def assign(mask, state):
        rho[mask], vel[mask], prs[mask] = state

    # Left of the contact discontinuity (Toro Sect. 4.5, Fig. 4.14).
    on_left = s <= v_star
    assign(on_left & (s <= l_head), (rho_l, v_l, p_l))
    assign(on_left & (s > l_tail), (rho_sl, v_star, p_star))
    if l_kind == "rarefaction":
        fan = on_left & (s > l_head) & (s <= l_tail)
        c = (2.0 / (gamma + 1.0)
             + (gamma - 1.0) / ((gamma + 1.0) * a_l) * (v_l - s[fan]))     # Toro eq. 4.56
        rho[fan] = rho_l * c ** (2.0 / (gamma - 1.0))
        vel[fan] = 2.0 / (gamma + 1.0) * (a_l + 0.5 * (gamma - 1.0) * v_l + s[fan])
        prs[fan] = p_l * c ** (2.0 * gamma / (gamma - 1.0))

    # Right of the contact discontinuity.
    on_right = ~on_left
    assign(on_right & (s >= r_head), (rho_r, v_r, p_r))
    assign(on_right & (s < r_tail), (rho_sr, v_star, p_star))
    if r_kind == "rarefaction":
        fan = on_right & (s < r_head) & (s >= r_tail)
        c = (2.0 / (gamma + 1.0)
             - (gamma - 1.0) / ((gamma + 1.0) * a_r) * (v_r - s[fan]))     # Toro eq. 4.63
        rho[fan] = rho_r * c ** (2.0 / (gamma - 1.0))
        vel[fan] = 2.0 / (gamma + 1.0) * (-a_r + 0.5 * (gamma - 1.0) * v_r + s[fan])
        prs[fan] = p_r * c ** (2.0 * gamma / (gamma - 1.0))

    return {"rho": rho, "vx": vel, "p": prs, "u": prs / ((gamma - 1.0) * rho)}


def wave_positions(t, left, right, gamma, x0=0.0):
    """Positions of the wave fronts at time ``t >= 0``.

    Always returned (floats):

    * ``'left_head'``, ``'left_tail'``: outer and inner edge of the left wave
      (both equal the shock position if the left wave is a shock),
    * ``'contact'``: the contact discontinuity,
    * ``'right_head'``, ``'right_tail'``: outer and inner edge of the right wave.

    For the Sod-type pattern (left rarefaction, right shock) the aliases
    ``'rarefaction_head'``, ``'rarefaction_tail'`` and ``'shock'`` are added.
    """
    (_, v_star, _, _), (l_kind, l_head, l_tail), (r_kind, r_head, r_tail) = \
        _wave_speeds(left, right, gamma)
    pos = {
        "left_head": x0 + l_head * t,
        "left_tail": x0 + l_tail * t,
        "contact": x0 + v_star * t,
        "right_head": x0 + r_head * t,
        "right_tail": x0 + r_tail * t,
    }
    if l_kind == "rarefaction" and r_kind == "shock":
        pos["rarefaction_head"] = pos["left_head"]
        pos["rarefaction_tail"] = pos["left_tail"]
        pos["shock"] = pos["right_head"]
    return pos
