#!/usr/bin/env python3
"""Binary star (examples/binary/in.binary): conservation and the Kepler orbit from the log.

Reads the thermo rows (columns Step Time v_px v_py v_pz c_pscale v_Lz c_ke pe v_etot v_sep) and
the masses, a and e from the line the input prints, and prints:
  - the linear momentum drift: the largest |P(t) - P(0)| (per component) over the run, relative
    to the momentum scale sum_i m_i |v_i| of the same row,
  - the largest relative angular momentum error |L_z(t) - L_z(0)| / |L_z(0)|,
  - the largest relative energy error |E(t) - E(0)| / |E(0)|, and both at the end,
  - the orbit's a and e from E and L at the start and the end, against the input's:
    E = -G m1 m2 / (2 a), L = mu sqrt(G M a (1 - e^2)), mu = m1 m2 / M (Murray & Dermott 1999,
    Solar System Dynamics, ch. 2), G = 1,
  - the smallest and largest separation over the thermo rows against a (1 -/+ e),
  - the phase error of the relative orbit after its whole periods: the angle from the relative
    position x2 - x1 at the start (apocentre) to that of the last row at a whole period,
  - orbits, steps and the loop time.

Usage: analyse.py LOG [--assert momentum=X,angmom=Y,energy=Z,phase=W]
"""
import argparse
import math
import re
import sys

from sphastro import cli
from sphastro.evrard import read_log


def orbit(E, L, m1, m2):
    """Semi-major axis and eccentricity of the relative orbit of energy E and angular momentum
    L (G = 1)."""
    M, mu = m1 + m2, m1 * m2 / (m1 + m2)
    a = -m1 * m2 / (2.0 * E)
    e2 = 1.0 - (L / mu) ** 2 / (M * a)
    return a, math.sqrt(max(e2, 0.0))


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("log")
    cli.add_assert_argument(p, "comma-separated bounds, e.g. momentum=1e-13: exit 1 when "
                            "exceeded")
    args = p.parse_args()
    try:
        rows, wall = read_log(args.log)
    except ValueError as exc:
        sys.exit(f"analyse.py: {exc}")
    params = None
    loop = None
    with open(args.log) as fh:
        for line in fh:
            if line.startswith("Loop time of"):
                loop = float(line.split()[3])
            m = re.match(r"binary: m1 (\S+) m2 (\S+) a (\S+) e (\S+) P (\S+) dt (\S+), (\S+) orbits",
                         line)
            if m:
                params = [float(v) for v in m.groups()]
    if params is None:
        sys.exit("analyse.py: no 'binary:' line in the log (examples/binary/in.binary prints it)")
    m1, m2, a_in, e_in, period, dt, orbits = params
    r0 = rows[0]
    momentum = max(abs(r[k] - r0[k]) / r["c_pscale"]
                   for r in rows for k in ("v_px", "v_py", "v_pz"))
    angmom = max(abs(r["v_Lz"] - r0["v_Lz"]) / abs(r0["v_Lz"]) for r in rows)
    energy = max(abs(r["v_etot"] - r0["v_etot"]) / abs(r0["v_etot"]) for r in rows)
    end = rows[-1]
    print(f"binary: m1 {m1} m2 {m2}, a {a_in} e {e_in}, P {period:.6f}, dt {dt:.4e}: "
          f"{end['Time'] / period:.2f} orbits in {int(end['Step'])} steps, loop time {loop} s")
    print(f"linear momentum drift, largest |P - P0| / sum m |v|: {momentum:.3e}")
    print(f"relative angular momentum error: largest {angmom:.3e}, at the end "
          f"{abs(end['v_Lz'] - r0['v_Lz']) / abs(r0['v_Lz']):.3e}")
    print(f"relative energy error: largest {energy:.3e}, at the end "
          f"{abs(end['v_etot'] - r0['v_etot']) / abs(r0['v_etot']):.3e}")
    for label, r in (("start", r0), ("end", end)):
        a, e = orbit(r["v_etot"], r["v_Lz"], m1, m2)
        print(f"orbit at the {label}: a {a:.10f} (input {a_in}), e {e:.10f} (input {e_in})")
    seps = [r["v_sep"] for r in rows]
    print(f"separation over the thermo rows: {min(seps):.6f} .. {max(seps):.6f} (pericentre "
          f"{a_in * (1 - e_in):.6f}, apocentre {a_in * (1 + e_in):.6f})")
    # the last row at a whole number of periods (the steps per period divide into whole rows)
    phase = float("nan")
    whole = [r for r in rows if r["Time"] > 0 and
             abs(r["Time"] / period - round(r["Time"] / period)) < 0.5 * dt / period]
    if whole:
        w = whole[-1]
        phase = math.atan2(r0["v_rx"] * w["v_ry"] - r0["v_ry"] * w["v_rx"],
                           r0["v_rx"] * w["v_rx"] + r0["v_ry"] * w["v_ry"])
        print(f"phase error after {round(w['Time'] / period)} periods: {phase:.3e} rad "
              f"(relative position {w['v_rx']:.8f} {w['v_ry']:.8f}, at the start "
              f"{r0['v_rx']:.8f} {r0['v_ry']:.8f})")
    if args.bounds:
        return cli.assert_bounds(args.bounds, {"momentum": momentum, "angmom": angmom,
                                               "energy": energy, "phase": abs(phase)},
                                 error=p.error)
    return 0


if __name__ == "__main__":
    sys.exit(main())
