#!/usr/bin/env python3
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
"""Sedov errors of a SWIFT snapshot, measured as examples/sedov/analyse.py measures SPH-ASTRO's.

SWIFT writes HDF5 snapshots (PartType0/Coordinates, Velocities, Densities,
InternalEnergies; Header/Time, BoxSize). The blast of its Sedov example sits at the box centre.
Prints the shock radius offsets (binned density peak, half height), the peak density and the
L1 errors of rho, v_r and P against the self-similar solution over r < 1.2 R_s
(python/sphastro/sedov.py), for E = 1, rho0 = 1, gamma 5/3 unless given.

Usage: python3 tools/swift_sedov_errors.py SNAPSHOT.hdf5 [--E 1] [--rho0 1]
Needs h5py (Debian: python3-h5py); SWIFT itself is never part of this repository.
"""

import argparse
import sys

import numpy as np

from sphastro import sedov


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("snapshot")
    parser.add_argument("--E", type=float, default=1.0)
    parser.add_argument("--rho0", type=float, default=1.0)
    parser.add_argument("--gamma", type=float, default=5.0 / 3.0)
    args = parser.parse_args(argv)
    import h5py
    with h5py.File(args.snapshot, "r") as f:
        t = float(np.atleast_1d(f["Header"].attrs["Time"])[0])
        box = np.atleast_1d(f["Header"].attrs["BoxSize"]).astype(float)
        if box.size == 1:
            box = np.repeat(box, 3)
        gas = f["PartType0"]
        x = np.asarray(gas["Coordinates"], dtype=float)
        v = np.asarray(gas["Velocities"], dtype=float)
        rho = np.asarray(gas["Densities"], dtype=float)
        u = np.asarray(gas["InternalEnergies"], dtype=float)
    columns = {"x": x[:, 0], "y": x[:, 1], "z": x[:, 2], "vx": v[:, 0], "vy": v[:, 1],
               "vz": v[:, 2], "rho": rho, "u": u}
    centre = tuple(0.5 * box)
    res = sedov.sedov_errors(columns, t, args.E, args.rho0, args.gamma, centre=centre)
    print(f"{args.snapshot}: {len(rho)} particles, t = {t:g}")
    print(f"R_s SPH, binned density peak = {res['r_peak']:.5f}: {100 * res['err_r_peak']:+.2f} %")
    print(f"R_s SPH, half height of the jump = {res['r_half']:.5f}: "
          f"{100 * res['err_r_half']:+.2f} %")
    print(f"peak density (binned) = {res['rho_peak']:.4f}")
    print(f"L1(rho) = {res['rho']:.4e}")
    print(f"L1(v_r) = {res['v']:.4e}")
    print(f"L1(P) = {res['p']:.4e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
