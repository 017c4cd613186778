"""Tests of ``sphastro render`` on bad input: a bad option value is a usage error (exit status
2) naming the option, the value and what is allowed; a file that cannot be read is a one-line
error naming it (exit status 1); a picture that would come out blank is written with a warning
on stderr saying why. Run through the command's entry point, as a user would."""

import contextlib
import io
import os
import tempfile
import unittest

import numpy as np

from sphastro.__main__ import main as sphastro_main

A = 0.2                                     # lattice spacing


def run(*argv):
    """``sphastro render ARGV``: (exit status, stdout, stderr); an exception other than the
    SystemExit of an error message (a traceback for the user) fails the test."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            status = sphastro_main(["render", *argv])
        except SystemExit as exc:
            status = exc.code
    return status, out.getvalue(), err.getvalue()


def write_dump(path, pos, rho, h, extra=None, box=(-0.6, 0.6), natoms=None):
    """A LAMMPS text dump (one frame) with the columns id x y z rho h and ``extra``."""
    extra = extra or {}
    n = len(pos)
    rho, h = np.broadcast_to(rho, (n,)), np.broadcast_to(h, (n,))
    with open(path, "w") as f:
        f.write(f"ITEM: TIMESTEP\n10\nITEM: NUMBER OF ATOMS\n{n if natoms is None else natoms}\n")
        f.write("ITEM: BOX BOUNDS pp pp pp\n" + f"{box[0]} {box[1]}\n" * 3)
        f.write("ITEM: ATOMS id x y z rho h " + " ".join(extra) + "\n")
        for i in range(n):
            vals = [*pos[i], rho[i], h[i]] + [np.broadcast_to(v, (n,))[i] for v in extra.values()]
            f.write(f"{i + 1} " + " ".join(repr(float(v)) for v in vals) + "\n")


def lattice(n=6):
    """n^3 particles of spacing A centred on the origin (box -0.6 to 0.6)."""
    g = (np.arange(n) - 0.5 * (n - 1)) * A
    x, y, z = np.meshgrid(g, g, g, indexing="ij")
    return np.column_stack([x.ravel(), y.ravel(), z.ravel()])


class Case(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name
        self.png = self.path("out.png")
        pos = lattice()
        self.dump = self.path("dump.lattice")
        write_dump(self.dump, pos, 1.0, 1.2 * A,
                   {"vx": -pos[:, 1], "vy": pos[:, 0], "vz": 0.0, "u": 1.5})
        g = (np.arange(6) - 2.5) * A
        x, y = np.meshgrid(g, g, indexing="ij")
        self.dump2d = self.path("dump.2d")
        write_dump(self.dump2d, np.column_stack([x.ravel(), y.ravel(), 0.0 * x.ravel()]),
                   1.0, 1.2 * A)

    def tearDown(self):
        self.tmp.cleanup()

    def path(self, name):
        return os.path.join(self.dir, name)

    def assertUsageError(self, argv, *words):
        """Exit status 2 (argparse's) and an error line naming ``words`` (option, value)."""
        status, _, err = run(*argv)
        self.assertEqual(status, 2, (argv, err))
        line = err.strip().splitlines()[-1]
        self.assertTrue(line.startswith("sphastro render: error:"), (argv, err))
        for w in words:
            self.assertIn(w, line, (argv, err))
        self.assertNotIn("Traceback", err)
        self.assertFalse(os.path.exists(self.png), argv)


class OptionValueTest(Case):
    """Values wrong whatever the data: checked before the file is read."""

    def test_extent_of_zero_or_negative_width(self):
        for bad in ("0,0,0,1", "0,1,2,2", "1,0,0,1", "0,1,nan,1", "0,inf,0,1", "a,b,c,d",
                    "0,1,0", "-1e308,1e308,0,1"):
            self.assertUsageError([self.dump, "--out", self.png, f"--extent={bad}"],
                                  "--extent", bad, "X0 < X1")

    def test_slice_value_not_a_finite_number(self):
        for bad in ("z=abc", "z=nan", "z=inf", "z=", "w=0.1", "z", "0.5"):
            self.assertUsageError([self.dump, "--out", self.png, "--slice", bad],
                                  "--slice", repr(bad), "x, y or z", "finite number")

    def test_res_not_a_sensible_pixel_count(self):
        for bad in ("0", "-5", "100000", "2.5", "many"):
            self.assertUsageError([self.dump, "--out", self.png, f"--res={bad}"],
                                  "--res", repr(bad), "1 to 4096")

    def test_range_empty_reversed_or_not_numbers(self):
        for bad in ("5,1", "1,1", "nan,1", "0,inf", "a,b", "1", "1,2,3", "-1e308,1e308"):
            self.assertUsageError([self.dump, "--out", self.png, f"--range={bad}"],
                                  "--range", repr(bad), "LO < HI")

    def test_mass_hfact_and_h_factor_must_be_positive(self):
        for option in ("--mass", "--hfact", "--h-factor"):
            for bad in ("0", "-1", "nan", "inf", "x"):
                self.assertUsageError([self.dump, "--out", self.png, f"{option}={bad}"],
                                      option, repr(bad), "positive")

    def test_unknown_colour_map(self):
        self.assertUsageError([self.dump, "--out", self.png, "--cmap", "nope"],
                              "--cmap", "'nope'", "viridis")

    def test_title_that_matplotlib_cannot_typeset(self):
        self.assertUsageError([self.dump, "--out", self.png, "--title", r"$\nosuchsymbol$"],
                              "--title", "nosuchsymbol")

    def test_out_with_an_unknown_format_or_a_directory(self):
        self.assertUsageError([self.dump, "--out", self.path("rho.xyz")], "--out", "rho.xyz",
                              "png")
        self.assertUsageError([self.dump, "--out", self.dir], "--out", self.dir, "directory")

    def test_out_without_a_suffix_is_the_png_named(self):
        out = self.path("rho")
        status, stdout, _ = run(self.dump, "--out", out, "--res", "16")
        self.assertEqual(status, 0)
        with open(out, "rb") as f:
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
        self.assertFalse(os.path.exists(out + ".png"))
        self.assertIn(f"wrote {out}", stdout)


class OptionForTheDataTest(Case):
    """Values that the data read decide: still usage errors naming the option."""

    def test_unknown_field_names_the_available_ones(self):
        self.assertUsageError([self.dump, "--out", self.png, "--field", "temperature"],
                              "--field", "'temperature'", "available: rho, h, mass, u, vx, vy, "
                              "vz, v")
        # a column the reader keeps out of the fields
        self.assertUsageError([self.dump, "--out", self.png, "--field", "id"],
                              "--field", "'id'", "available")

    def test_speed_and_vectors_without_velocities(self):
        self.assertUsageError([self.dump2d, "--out", self.png, "--field", "v"],
                              "--field", "'v'", "vx, vy")
        self.assertUsageError([self.dump2d, "--out", self.png, "--vectors"],
                              "--vectors", "vx, vy", self.dump2d)

    def test_column_and_slice_of_2d_data(self):
        self.assertUsageError([self.dump2d, "--out", self.png, "--column", "z"],
                              "--column", "2D", self.dump2d)
        self.assertUsageError([self.dump2d, "--out", self.png, "--slice", "z=0.1"],
                              "--slice", "2D", self.dump2d)

    def test_normalise_of_a_column_map(self):
        self.assertUsageError([self.dump, "--out", self.png, "--column", "z", "--normalise"],
                              "--normalise", "--column")

    def test_frame_that_does_not_exist(self):
        self.assertUsageError([self.dump, "--out", self.png, "--frame", "3"],
                              "--frame 3", self.dump, "1 frame", "-1 to 0")

    def test_frame_and_periodic_of_an_hdf5_snapshot(self):
        try:
            import h5py
        except ImportError:
            self.skipTest("h5py not installed")
        snap = self.path("snap.hdf5")
        pos = lattice()
        with h5py.File(snap, "w") as f:
            g = f.create_group("PartType0")
            g["Coordinates"] = pos
            g["Masses"] = np.full(len(pos), A ** 3)
            g["Density"] = np.ones(len(pos))
            g["SmoothingLengths"] = np.full(len(pos), 1.2 * A)
        self.assertUsageError([snap, "--out", self.png, "--frame", "2"],
                              "--frame 2", snap, "0 or -1")
        # no Header/BoxSize: no box to wrap
        self.assertUsageError([snap, "--out", self.png, "--periodic"], "--periodic", snap,
                              "BoxSize")


def write_snapshot(path, pos, **replace):
    """A SWIFT-layout HDF5 snapshot of particles at ``pos``; ``replace``: datasets of
    PartType0 (name -> array) to write instead, or None to leave out."""
    import h5py

    n = len(pos)
    data = {"Coordinates": pos + 0.6, "Masses": np.full(n, A ** 3), "Density": np.ones(n),
            "SmoothingLengths": np.full(n, 1.2 * A), "Velocities": np.zeros((n, 3))}
    data.update(replace)
    with h5py.File(path, "w") as f:
        f.create_group("Header").attrs.update({"BoxSize": [1.2] * 3, "Time": 0.5,
                                               "Dimension": 3})
        g = f.create_group("PartType0")
        for k, v in data.items():
            if v is not None:
                g[k] = v


class FileErrorTest(Case):
    """Files that cannot be read: one line naming the file and why, exit status 1."""

    def assertFileError(self, path, *words, argv=()):
        status, _, err = run(path, "--out", self.png, *argv)
        self.assertEqual(status, 1, (path, err))
        self.assertEqual(len(err.strip().splitlines()), 1, err)
        self.assertTrue(err.startswith(f"sphastro render: error: {path}"), err)
        for w in words:
            self.assertIn(w, err)
        self.assertFalse(os.path.exists(self.png), path)

    def test_missing_file_and_directory(self):
        self.assertFileError(self.path("nothing.here"), "no such file")
        self.assertFileError(self.dir, "directory")

    def test_empty_file(self):
        empty = self.path("empty")
        open(empty, "w").close()
        self.assertFileError(empty, "empty", "LAMMPS text dump", "HDF5")

    def test_text_and_binary_files_that_are_no_dumps(self):
        text = self.path("notes.txt")
        with open(text, "w") as f:
            f.write("a text file\nnot a dump\n")
        self.assertFileError(text, "not a LAMMPS text dump", "ITEM: TIMESTEP")
        self.assertFileError(text, "LAMMPS text dump", "a text file", argv=("--frame", "0"))
        binary = self.path("noise.bin")
        with open(binary, "wb") as f:
            f.write(bytes(range(256)) * 8)
        self.assertFileError(binary, "not a LAMMPS text dump")

    def test_truncated_dump(self):
        with open(self.dump) as f:
            text = f.read()
        half = self.path("dump.half")
        with open(half, "w") as f:
            f.write(text[:len(text) // 2])
        self.assertFileError(half, "ends inside its first frame")
        self.assertFileError(half, "ends inside its first frame", argv=("--frame", "0"))

    def test_dump_with_malformed_rows_or_columns(self):
        with open(self.dump) as f:
            lines = f.read().splitlines(keepends=True)
        short = self.path("dump.short")
        with open(short, "w") as f:
            f.write("".join(lines[:9]) + " ".join(lines[9].split()[:-1]) + "\n" +
                    "".join(lines[10:]))
        self.assertFileError(short, "not a readable LAMMPS text dump", "values")
        words = self.path("dump.words")
        with open(words, "w") as f:
            row = lines[9].split()
            row[2] = "abc"                                  # the y of the first particle
            f.write("".join(lines[:9]) + " ".join(row) + "\n" + "".join(lines[10:]))
        self.assertFileError(words, "column y", "not numeric")

    def test_dump_without_particles(self):
        empty = self.path("dump.none")
        write_dump(empty, np.zeros((0, 3)), 1.0, 0.1)
        self.assertFileError(empty, "no particles")

    def test_particles_with_values_that_cannot_be_rendered(self):
        pos = lattice(3)
        for name, (column, value) in {"nan_h": ("h", np.nan), "zero_h": ("h", 0.0),
                                      "negative_rho": ("rho", -1.0),
                                      "inf_x": ("x", np.inf)}.items():
            dump = self.path(f"dump.{name}")
            rho, h, p = np.ones(len(pos)), np.full(len(pos), 1.2 * A), pos.copy()
            {"h": h, "rho": rho, "x": p[:, 0]}[column][4] = value
            write_dump(dump, p, rho, h)
            self.assertFileError(dump, "1 of 27 particles", column, "id 5")

    def test_truncated_and_malformed_hdf5(self):
        try:
            import h5py                                     # noqa: F401
        except ImportError:
            self.skipTest("h5py not installed")
        pos = lattice()
        snap = self.path("snap.hdf5")
        write_snapshot(snap, pos)
        with open(snap, "rb") as f:
            data = f.read()
        half = self.path("snap.half.hdf5")
        with open(half, "wb") as f:
            f.write(data[:len(data) // 2])
        self.assertFileError(half, "not a readable HDF5 file", "truncated")
        bad = self.path("snap.shape.hdf5")
        write_snapshot(bad, pos, Masses=np.ones(len(pos) - 1))
        self.assertFileError(bad, "PartType0/Masses", f"{len(pos) - 1}", f"{len(pos)}")
        flat = self.path("snap.flat.hdf5")
        write_snapshot(flat, pos, Coordinates=pos[:, 0])
        self.assertFileError(flat, "PartType0/Coordinates")
        none = self.path("snap.none.hdf5")
        write_snapshot(none, np.zeros((0, 3)))
        self.assertFileError(none, "no particles")

    def test_picture_that_cannot_be_written(self):
        blocker = self.path("a_file")
        open(blocker, "w").close()
        out = os.path.join(blocker, "rho.png")
        status, _, err = run(self.dump, "--out", out, "--res", "16")
        self.assertEqual(status, 1, err)
        self.assertEqual(len(err.strip().splitlines()), 1, err)
        self.assertIn(f"--out {out}: cannot write", err)


class BlankPictureTest(Case):
    """A picture that comes out blank or of one colour is written (exit status 0: a series of
    frames stays complete), with a warning on stderr that says why."""

    def assertWarned(self, argv, *words):
        status, _, err = run(*argv, "--out", self.png, "--res", "16")
        self.assertEqual(status, 0, (argv, err))
        self.assertGreater(os.path.getsize(self.png), 1000)
        lines = err.strip().splitlines()
        self.assertEqual(len(lines), 1, (argv, err))
        self.assertTrue(lines[0].startswith("sphastro render: warning:"), (argv, err))
        for w in words:
            self.assertIn(w, lines[0], (argv, err))
        os.remove(self.png)

    def test_slice_outside_the_particles(self):
        self.assertWarned([self.dump, "--slice", "z=50"], "slice z = 50", "no particle",
                          "blank", "--slice")
        self.assertWarned([self.dump, "--slice", "x=-3", "--normalise"], "slice x = -3",
                          "blank")

    def test_window_away_from_the_particles(self):
        self.assertWarned([self.dump, "--extent=5,6,5,6"], "window", "no particle", "blank",
                          "--extent")
        self.assertWarned([self.dump, "--column", "x", "--extent=5,6,5,6"], "window",
                          "blank")

    def test_log_of_a_map_without_a_positive_pixel(self):
        self.assertWarned([self.dump, "--field", "vz", "--log"], "--log", "no pixel",
                          "positive", "blank")
        self.assertWarned([self.dump, "--field", "vz", "--log", "--column", "z"], "--log",
                          "blank")

    def test_uniform_map_and_range_outside_the_map(self):
        self.assertWarned([self.dump, "--field", "vz"], "vz is 0", "one colour")
        self.assertWarned([self.dump, "--range", "10,20"], "--range 10,20", "outside",
                          "one colour")
        self.assertWarned([self.dump, "--log", "--range=-9,-8"], "--range -9,-8", "log10",
                          "outside")

    def test_kernels_between_the_pixel_centres(self):
        # pixels 125 wide, kernels 0.5 across: no pixel centre within 2h of a particle
        self.assertWarned([self.dump, "--extent=-1e3,1e3,-1e3,1e3"], "between the pixel "
                          "centres", "blank", "--res")
        # absurd scales overflow in the sums; the warning says why, numpy's do not show
        self.assertWarned([self.dump, "--extent=-1e200,1e200,-1e200,1e200"], "between the "
                          "pixel centres")

    def test_field_with_values_that_are_not_finite(self):
        pos = lattice()
        u = np.full(len(pos), 1.5)
        u[7] = np.nan
        dump = self.path("dump.nan_u")
        write_dump(dump, pos, 1.0, 1.2 * A, {"u": u})
        self.assertWarned([dump, "--field", "u", "--slice", f"z={pos[7, 2]}"], "--field u",
                          "1 of 216", "not finite", "blank")

    def test_incomplete_last_frame_is_a_one_line_warning(self):
        with open(self.dump) as f:
            text = f.read()
        dump = self.path("dump.growing")
        with open(dump, "w") as f:
            f.write(text + text[:len(text) // 2])
        self.assertWarned([dump], dump, "last frame incomplete", "previous one")

    def test_a_good_picture_has_no_warning(self):
        # pixels beyond the particles are blank in --log, the rest of the picture is not
        status, _, err = run(self.dump, "--out", self.png, "--res", "16", "--log",
                             "--extent=-2,2,-2,2", "--vectors")
        self.assertEqual((status, err), (0, ""))


class AbsurdWindowTest(Case):
    """Windows and kernels far out of proportion to each other: a map, or an error naming the
    option, never an exhausted memory."""

    def test_window_far_smaller_than_a_kernel(self):
        # 2h / pixel ~ 10^7: the footprint of each particle is clipped to the image
        status, out, err = run(self.dump, "--out", self.png, "--res", "16",
                               "--extent=0,1e-6,0,1e-6", "--range", "0,2")
        self.assertEqual(status, 0, err)
        self.assertIn("map 16 x 16", out)

    def test_particle_far_larger_than_the_window(self):
        pos = lattice(3)
        h = np.full(len(pos), 1.2 * A)
        h[13] = 1e6                                   # the centre particle
        dump = self.path("dump.wide")
        write_dump(dump, pos, 1.0, h, {"mass": A ** 3})
        status, out, err = run(dump, "--out", self.png, "--res", "16")
        self.assertEqual(status, 0, err)

    def test_window_of_an_extreme_aspect_ratio(self):
        self.assertUsageError([self.dump, "--out", self.png, "--extent=0,1e-6,0,1"],
                              "--extent", "--res 256", "4096")

    def test_box_of_zero_width_without_extent(self):
        dump = self.path("dump.flatbox")
        write_dump(dump, lattice(3), 1.0, 1.2 * A, box=(0.0, 0.0))
        status, _, err = run(dump, "--out", self.png, "--res", "16")
        self.assertEqual(status, 1, err)
        self.assertIn(f"{dump}: the box is empty", err)
        self.assertIn("--extent", err)
        # the window given, the box is not needed
        status, _, err = run(dump, "--out", self.png, "--res", "16", "--extent=-1,1,-1,1")
        self.assertEqual(status, 0, err)


if __name__ == "__main__":
    unittest.main()
