"""Tests of sphastro.render: SPH-kernel-weighted slice and column maps (sphastro render).

Measured (python -m pytest python/tests/test_render.py): a cubic lattice of spacing a with
h = 1.2 a renders rho = 1 to 4.1e-3 in a slice (bound 1e-2); the slice of A = 2 + 3x
reproduces it to 1.34e-2 (bound 3e-2); the column of a slab of 21 layers is 21 a to 5e-3
(bound 1.5e-2); one particle's column map sums to its mass to 2e-6 (bound 1e-4).
"""

import math
import os
import tempfile
import unittest

import numpy as np

from sphastro import render
from sphastro.__main__ import main as sphastro_main

A = 0.1                                     # lattice spacing
WINDOW = ((-0.5, 0.5), (-0.5, 0.5))          # well inside the lattice (|x| <= 1)


def lattice(hfact=1.2):
    g = np.arange(-1.0, 1.0 + 1e-9, A)
    x, y, z = np.meshgrid(g, g, g, indexing="ij")
    pos = np.column_stack([x.ravel(), y.ravel(), z.ravel()])
    return render.Particles(pos, A ** 3, 1.0, hfact * A)


def centres(n, lo=-0.5, hi=0.5):
    return lo + (np.arange(n) + 0.5) * (hi - lo) / n


class KernelTest(unittest.TestCase):
    def test_m4_normalisation_in_3d(self):
        # 4 pi int_0^2 sigma w(q) q^2 dq = 1 (support 2h, as sph_astro_kernel.h)
        q = np.linspace(0.0, 2.0, 200001)
        total = np.trapz(4.0 * math.pi * q * q * render.SIGMA[3] * render.kernel_w(q), q)
        self.assertAlmostEqual(total, 1.0, places=6)

    def test_column_kernel_integrates_to_one_over_the_plane(self):
        q = np.linspace(0.0, 2.0, 200001)
        total = np.trapz(2.0 * math.pi * q * render.kernel_column(q), q)
        self.assertAlmostEqual(total, 1.0, places=5)

    def test_column_kernel_at_the_centre(self):
        # F(0) = 2 sigma int_0^2 w(s) ds = 2/pi (3/4 + 1/16 ... ) : int_0^1 w = 1 - 1/2 + 3/16,
        # int_1^2 (2-s)^3/4 = 1/16, so F(0) = 2/pi * 3/4 = 1.5/pi
        self.assertAlmostEqual(float(render.kernel_column(0.0)), 1.5 / math.pi, places=7)
        self.assertEqual(float(render.kernel_column(2.0)), 0.0)


class SliceTest(unittest.TestCase):
    def test_uniform_lattice_renders_a_uniform_density(self):
        p = lattice()
        img, _ = render.slice_map(p, p.rho, "z", 0.03, 64, WINDOW)
        self.assertLess(np.abs(img - 1.0).max(), 1e-2)

    def test_slice_of_a_linear_field_reproduces_it(self):
        p = lattice()
        img, _ = render.slice_map(p, 2.0 + 3.0 * p.pos[:, 0], "z", 0.03, 64, WINDOW)
        exact = 2.0 + 3.0 * centres(64)[None, :]
        self.assertLess(np.abs(img - exact).max(), 3e-2)

    def test_slice_along_x_sees_the_field_in_y(self):
        p = lattice()
        img, _ = render.slice_map(p, 1.0 - 2.0 * p.pos[:, 1], "x", 0.0, 32, WINDOW)
        # image axes (y, z): columns follow y
        exact = 1.0 - 2.0 * centres(32)[None, :]
        self.assertLess(np.abs(img - exact).max(), 3e-2)

    def test_normalised_slice_is_exact_for_a_constant(self):
        p = lattice()
        img, _ = render.slice_map(p, np.full(len(p.pos), 7.0), "z", 0.0, 32, WINDOW,
                                  normalise=True)
        self.assertLess(np.abs(img - 7.0).max(), 1e-12)

    def test_two_dimensional_data(self):
        g = np.arange(-1.0, 1.0 + 1e-9, A)
        x, y = np.meshgrid(g, g, indexing="ij")
        p = render.Particles(np.column_stack([x.ravel(), y.ravel()]), A * A, 1.0, 1.2 * A)
        img, _ = render.slice_map(p, p.rho, res=32, extent=WINDOW)
        self.assertLess(np.abs(img - 1.0).max(), 2e-2)


class ColumnTest(unittest.TestCase):
    def test_single_particle_column_conserves_mass(self):
        p = render.Particles(np.array([[0.013, -0.021, 0.3]]), 2.5, 1.0, 0.2)
        for res in (16, 64):
            img, _ = render.column_map(p, p.rho, "z", res, WINDOW)
            total = img.sum() * (1.0 / res) ** 2
            self.assertLess(abs(total / 2.5 - 1.0), 1e-4, res)

    def test_column_of_a_slab_is_its_surface_density(self):
        p = lattice()
        img, _ = render.column_map(p, p.rho, "z", 64, WINDOW)
        self.assertLess(np.abs(img / (21 * A) - 1.0).max(), 1.5e-2)


def write_dump(path, pos, rho, h, extra=None):
    extra = extra or {}
    names = ["id", "x", "y", "z", "rho", "h"] + list(extra)
    with open(path, "w") as f:
        f.write("ITEM: TIME\n0.25\nITEM: TIMESTEP\n100\n")
        f.write(f"ITEM: NUMBER OF ATOMS\n{len(pos)}\nITEM: BOX BOUNDS pp pp pp\n")
        f.write("-1.05 1.05\n-1.05 1.05\n-1.05 1.05\n")
        f.write("ITEM: ATOMS " + " ".join(names) + "\n")
        for i, r in enumerate(pos):
            vals = [i + 1, *r, rho, h] + [extra[k][i] for k in extra]
            f.write(" ".join(repr(float(v)) if k else str(v) for k, v in enumerate(vals)) + "\n")


class FilesTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.p = lattice()

    def tearDown(self):
        self.tmp.cleanup()

    def test_dump_mass_from_the_h_constraint_and_the_command(self):
        dump = os.path.join(self.tmp.name, "dump.lattice")
        write_dump(dump, self.p.pos, 1.0, 1.2 * A, {"vx": -self.p.pos[:, 1], "vy": self.p.pos[:, 0],
                                                   "vz": 0.0 * self.p.pos[:, 0]})
        q = render.read_particles(dump)          # m = rho (h / 1.2)^3 = A^3
        self.assertTrue(np.allclose(q.mass, A ** 3))
        self.assertEqual(q.time, 0.25)
        png = os.path.join(self.tmp.name, "out", "rho.png")
        self.assertEqual(sphastro_main(["render", dump, "--out", png, "--slice", "z=0.03",
                                        "--res", "32", "--extent=-0.5,0.5,-0.5,0.5"]), 0)
        self.assertGreater(os.path.getsize(png), 1000)
        png2 = os.path.join(self.tmp.name, "v.png")
        self.assertEqual(sphastro_main(["render", dump, "--out", png2, "--field", "v",
                                        "--column", "z", "--res", "24", "--vectors",
                                        "--mass", repr(A ** 3)]), 0)

    def test_frames_of_a_dump_by_index(self):
        first = os.path.join(self.tmp.name, "a")
        second = os.path.join(self.tmp.name, "b")
        write_dump(first, self.p.pos[:10], 1.0, 1.2 * A)
        write_dump(second, self.p.pos[:12], 2.0, 1.2 * A)
        dump = os.path.join(self.tmp.name, "dump.two")
        with open(dump, "w") as f:
            f.write(open(first).read() + open(second).read())
        self.assertEqual(len(render.read_particles(dump).pos), 12)           # the last
        self.assertEqual(len(render.read_particles(dump, frame=0).pos), 10)
        self.assertEqual(render.read_particles(dump, frame=-2).rho[0], 1.0)
        with self.assertRaises(ValueError):
            render.read_particles(dump, frame=2)

    def test_dump_of_a_2d_run_is_2d(self):
        g = np.arange(-0.5, 0.5 - 1e-9, 0.05)
        x, y = np.meshgrid(g, g, indexing="ij")
        pos = np.column_stack([x.ravel(), y.ravel(), 0.0 * x.ravel()])
        dump = os.path.join(self.tmp.name, "dump.2d")
        write_dump(dump, pos, 1.0, 1.2 * 0.05)
        q = render.read_particles(dump)            # m = rho (h / 1.2)^2: the 2D constraint
        self.assertEqual(q.dim, 2)
        self.assertTrue(np.allclose(q.mass, 0.05 ** 2))

    def test_unknown_field_is_a_usage_error(self):
        dump = os.path.join(self.tmp.name, "dump.lattice")
        write_dump(dump, self.p.pos[:10], 1.0, 1.2 * A)
        with self.assertRaises(SystemExit) as cm:
            sphastro_main(["render", dump, "--out", os.path.join(self.tmp.name, "x.png"),
                           "--field", "temperature"])
        self.assertEqual(cm.exception.code, 2)

    def test_swift_layout_hdf5(self):
        try:
            import h5py
        except ImportError:
            self.skipTest("h5py not installed")
        path = os.path.join(self.tmp.name, "snap.hdf5")
        n = len(self.p.pos)
        gamma_k = render.SWIFT_KERNEL_GAMMA[3]
        with h5py.File(path, "w") as f:
            f.create_group("Header").attrs.update({"BoxSize": [2.1, 2.1, 2.1], "Time": 0.5,
                                                   "Dimension": 3})
            g = f.create_group("PartType0")
            g["Coordinates"] = self.p.pos + 1.05
            g["Masses"] = np.full(n, A ** 3)
            g["Density"] = np.ones(n)
            # SWIFT's h: the M4 support 2h_M4 = gamma_K h_SWIFT
            g["SmoothingLengths"] = np.full(n, 2.0 * 1.2 * A / gamma_k)
            g["Velocities"] = np.zeros((n, 3))
        q = render.read_particles(path)
        self.assertTrue(np.allclose(q.h, 1.2 * A))
        self.assertEqual(q.time, 0.5)
        img, _ = render.slice_map(q, q.rho, "z", 1.08, 32, ((0.55, 1.55), (0.55, 1.55)))
        self.assertLess(np.abs(img - 1.0).max(), 1e-2)
        # a file of fix sph/astro/snapshot holds the run's own h
        with h5py.File(path, "a") as f:
            f.create_group("Code").attrs["Code"] = np.bytes_("SPH-ASTRO (LAMMPS plugin)")
            del f["PartType0/SmoothingLengths"]
            f["PartType0/SmoothingLengths"] = np.full(n, 1.2 * A)
        q = render.read_particles(path)
        self.assertTrue(np.allclose(q.h, 1.2 * A))


class PeriodicTest(unittest.TestCase):
    def test_periodic_images_make_the_map_uniform_up_to_the_faces(self):
        g = np.arange(-1.0, 1.0 - 1e-9, A)          # 20 layers: period 2
        x, y, z = np.meshgrid(g, g, g, indexing="ij")
        pos = np.column_stack([x.ravel(), y.ravel(), z.ravel()])
        box = [(-1.0, 1.0)] * 3
        p = render.Particles(pos, A ** 3, 1.0, 1.2 * A, box=box)
        full = ((-1.0, 1.0), (-1.0, 1.0))
        without, _ = render.slice_map(p, p.rho, "z", 0.03, 40, full)
        self.assertLess(without.min(), 0.6)           # the faces lack their neighbours
        q = render.periodic_images(p)
        img, _ = render.slice_map(q, q.rho, "z", 0.03, 40, full)
        self.assertLess(np.abs(img - 1.0).max(), 1e-2)
        q = render.periodic_images(p, axes=(0, 1))      # none along the line of sight
        col, _ = render.column_map(q, q.rho, "z", 40, full)
        self.assertLess(np.abs(col / 2.0 - 1.0).max(), 1.5e-2)


if __name__ == "__main__":
    unittest.main()
