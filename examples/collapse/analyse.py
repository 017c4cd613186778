#!/usr/bin/env python3
"""Sinks made in the collapse of examples/collapse/in.collapse, and its total mass.

Usage (python3 of build/venv, on PATH after source build/env.sh)::

    python3 examples/collapse/analyse.py collapse.dat --log log.lammps
        [--assert 'sinks=1,made=1,mass=1e-14,offset=0.1']

collapse.dat is in.collapse's fix ave/time file: step, total mass mass(all), number of
sinks, gas particles accreted, the sinks' mass, the number of gas particles and their mass m.
The total mass is taken as the sinks' mass + N_gas m (mass(all) adds its own round-off, about
N eps, summing the particles one by one). The log gives fix sph/astro/sink's line for each sink made
(atom, step, density, position). Printed: the sinks at the end and made, the largest relative
change of the total mass, and the distance of each new sink from the centre (the sphere's
centre of mass is at the origin). ``--assert``: ``sinks`` (at the end) and ``offset`` (the
largest distance from the centre) and ``mass`` are upper bounds, ``made`` a lower bound.
"""

import argparse
import math
import re
import sys

import numpy as np

from sphastro import cli

MADE = re.compile(r"atom (\d+) became a sink at step (\d+) \(rho = (\S+)\) at (\S+) (\S+) (\S+)")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("series", help="collapse.dat of in.collapse")
    parser.add_argument("--log", default="log.lammps", help="LAMMPS log of the run")
    cli.add_assert_argument(parser, "e.g. sinks=1,made=1,mass=1e-14,offset=0.1")
    args = parser.parse_args(argv)

    data = np.atleast_2d(np.loadtxt(args.series, comments="#"))
    nsinks, nacc, msinks, ngas, mgas = data[:, 2], data[:, 3], data[:, 4], data[:, 5], data[:, 6]
    mtot = np.array([math.fsum([a, n * m]) for a, n, m in zip(msinks, ngas, mgas)])
    mass = float(np.max(np.abs(mtot - mtot[0])) / mtot[0])
    made = []
    with open(args.log) as f:
        for line in f:
            m = MADE.search(line)
            if m:
                made.append((int(m.group(1)), int(m.group(2)), float(m.group(3)),
                             [float(m.group(k)) for k in (4, 5, 6)]))
    offset = max((math.sqrt(sum(c * c for c in pos)) for *_, pos in made), default=math.nan)
    for tag, step, rho, pos in made:
        print(f"collapse: atom {tag} became a sink at step {step} (rho = {rho:g}) at distance "
              f"{math.sqrt(sum(c * c for c in pos)):.4g} from the centre")
    print(f"collapse: {int(nsinks[-1])} sinks at the end, {len(made)} made, "
          f"{int(nacc[-1])} gas particles accreted")
    print(f"collapse: largest relative change of the total mass {mass:.3e}")
    if args.bounds:
        return cli.assert_bounds(args.bounds, {"sinks": float(nsinks[-1]), "made": float(len(made)),
                                               "mass": mass, "offset": offset},
                                 lower=("made",), error=parser.error)
    return 0


if __name__ == "__main__":
    sys.exit(main())
