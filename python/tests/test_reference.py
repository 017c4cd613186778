"""Tests of the SPH-ASTRO Python reference tools.

Run from the repository root with::

    build/venv/bin/python -m pytest python/tests
"""

import math
import os
import tempfile
import unittest

import numpy as np

from sphastro import dump, riemann, sod

# Toro, Riemann Solvers and Numerical Methods for Fluid Dynamics, 3rd ed.: the five
# test problems (Table 4.1, with discontinuity positions and output times) and
# their exact star states for gamma = 1.4 (Table 4.2): p*, u*, rho*L, rho*R.
TORO_TESTS = {
    1: dict(left=(1.0, 0.0, 1.0), right=(0.125, 0.0, 0.1), x0=0.5, t=0.25,
            star=(0.30313, 0.92745, 0.42632, 0.26557)),
    2: dict(left=(1.0, -2.0, 0.4), right=(1.0, 2.0, 0.4), x0=0.5, t=0.15,
            star=(0.00189, 0.0, 0.02185, 0.02185)),
    3: dict(left=(1.0, 0.0, 1000.0), right=(1.0, 0.0, 0.01), x0=0.5, t=0.012,
            star=(460.894, 19.5975, 0.57506, 5.99924)),
    4: dict(left=(1.0, 0.0, 0.01), right=(1.0, 0.0, 100.0), x0=0.4, t=0.035,
            star=(46.0950, -6.19633, 5.99242, 0.57511)),
    5: dict(left=(5.99924, 19.5975, 460.894), right=(5.99242, -6.19633, 46.0950), x0=0.4,
            t=0.035, star=(1691.64, 8.68975, 14.2823, 31.0426)),
}
GAMMA_TORO = 1.4
SOD_LEFT, SOD_RIGHT = (1.0, 0.0, 1.0), (0.125, 0.0, 0.1)


def conserved(state, gamma):
    """Densities of mass, momentum, total energy and their fluxes for (rho, v, p)."""
    rho, v, p = (np.asarray(q, dtype=float) for q in state)
    energy = 0.5 * rho * v * v + p / (gamma - 1.0)
    return (rho, rho * v, energy), (rho * v, rho * v * v + p, v * (energy + p))


class StarStateTest(unittest.TestCase):
    def test_toro_table_4_2(self):
        names = ("p*", "u*", "rho*L", "rho*R")
        for number, case in TORO_TESTS.items():
            got = riemann.star_state(case["left"], case["right"], GAMMA_TORO)
            for name, value, ref in zip(names, got, case["star"]):
                if number == 2:
                    # Quoted to 5 decimals (3 significant figures): half a unit in the last place.
                    tol = 5e-6 if ref else 1e-12
                else:
                    tol = 1e-4 * abs(ref)
                with self.subTest(test=number, quantity=name):
                    self.assertAlmostEqual(value, ref, delta=tol)

    def test_sod_gamma_five_thirds_root(self):
        gamma = 5.0 / 3.0
        p_star, v_star, _, _ = riemann.star_state(SOD_LEFT, SOD_RIGHT, gamma)
        self.assertAlmostEqual(p_star, 0.29395, delta=5e-5)
        f_l, _ = riemann.pressure_function(p_star, SOD_LEFT[0], SOD_LEFT[2], gamma)
        f_r, _ = riemann.pressure_function(p_star, SOD_RIGHT[0], SOD_RIGHT[2], gamma)
        self.assertLess(abs(f_l + f_r + (SOD_RIGHT[1] - SOD_LEFT[1])), 1e-10)
        self.assertAlmostEqual(v_star, 0.5 * (f_r - f_l), delta=1e-12)

    def test_vacuum_and_invalid_states_raise(self):
        with self.assertRaises(ValueError):
            riemann.star_state((1.0, -20.0, 0.4), (1.0, 20.0, 0.4), GAMMA_TORO)
        with self.assertRaises(ValueError):
            riemann.sample([0.0], 0.1, (1.0, -20.0, 0.4), (1.0, 20.0, 0.4), GAMMA_TORO)
        with self.assertRaises(ValueError):
            riemann.star_state((0.0, 0.0, 1.0), SOD_RIGHT, GAMMA_TORO)


class SampleTest(unittest.TestCase):
    CASES = [(GAMMA_TORO, c["left"], c["right"], c["x0"], c["t"]) for c in TORO_TESTS.values()]
    CASES.append((5.0 / 3.0, SOD_LEFT, SOD_RIGHT, 0.0, 0.2))

    @staticmethod
    def integrate(t, left, right, gamma, x0, a, b, per_segment=20000):
        """Integrals of the conserved densities over [a, b] at time t.

        Midpoint rule on a fine grid whose segments end at the wave fronts, so
        the piecewise-constant parts are integrated exactly and the smooth
        rarefaction fans to O(h^2).
        """
        edges = sorted({a, b, *riemann.wave_positions(t, left, right, gamma, x0).values()})
        totals = np.zeros(3)
        for lo, hi in zip(edges[:-1], edges[1:]):
            h = (hi - lo) / per_segment
            xm = lo + h * (np.arange(per_segment) + 0.5)
            s = riemann.sample(xm, t, left, right, gamma, x0)
            dens, _ = conserved((s["rho"], s["vx"], s["p"]), gamma)
            totals += [h * np.sum(q) for q in dens]
        return totals

    def test_conservation(self):
        for gamma, left, right, x0, t in self.CASES:
            a, b = x0 - 1.0, x0 + 1.0
            pos = riemann.wave_positions(t, left, right, gamma, x0)
            self.assertTrue(a < min(pos.values()) and max(pos.values()) < b)
            (ql, fl), (qr, fr) = conserved(left, gamma), conserved(right, gamma)
            for k, name in enumerate(("mass", "momentum", "energy")):
                initial = ql[k] * (x0 - a) + qr[k] * (b - x0)
                expected = initial + t * (fl[k] - fr[k])          # boundary fluxes
                got = self.integrate(t, left, right, gamma, x0, a, b)[k]
                with self.subTest(left=left, right=right, quantity=name):
                    self.assertLess(abs(got - expected), 1e-6 * max(abs(initial), 1.0))

    def test_mass_on_uniform_grid(self):
        # The plain uniform grid (no knowledge of wave positions) also conserves mass.
        gamma, t = 5.0 / 3.0, 0.2
        x = np.linspace(-1.0, 1.0, 4_000_001)
        h = x[1] - x[0]
        xm = 0.5 * (x[1:] + x[:-1])
        mass = h * np.sum(riemann.sample(xm, t, SOD_LEFT, SOD_RIGHT, gamma)["rho"])
        self.assertLess(abs(mass - 1.125) / 1.125, 1e-6)

    def test_far_states_and_internal_energy(self):
        for gamma, left, right, x0, t in self.CASES:
            s = riemann.sample(np.array([x0 - 1.0, x0 + 1.0]), t, left, right, gamma, x0)
            with self.subTest(left=left, right=right):
                np.testing.assert_allclose([s["rho"][0], s["vx"][0], s["p"][0]], left, rtol=1e-14)
                np.testing.assert_allclose([s["rho"][1], s["vx"][1], s["p"][1]], right,
                                           rtol=1e-14)
                np.testing.assert_allclose(s["u"], s["p"] / ((gamma - 1.0) * s["rho"]))

    def test_star_region_and_wave_positions(self):
        gamma, t, eps = 5.0 / 3.0, 0.2, 1e-9
        p_star, v_star, rho_sl, rho_sr = riemann.star_state(SOD_LEFT, SOD_RIGHT, gamma)
        pos = riemann.wave_positions(t, SOD_LEFT, SOD_RIGHT, gamma)
        self.assertEqual(pos["rarefaction_head"], pos["left_head"])
        self.assertAlmostEqual(pos["rarefaction_head"], -math.sqrt(gamma) * t)
        self.assertAlmostEqual(pos["contact"], v_star * t)
        probe = np.array([pos["rarefaction_head"] - eps, pos["rarefaction_tail"] + eps,
                          pos["contact"] - eps, pos["contact"] + eps,
                          pos["shock"] - eps, pos["shock"] + eps])
        s = riemann.sample(probe, t, SOD_LEFT, SOD_RIGHT, gamma)
        np.testing.assert_allclose(s["rho"], [1.0, rho_sl, rho_sl, rho_sr, rho_sr, 0.125],
                                   rtol=1e-7)
        np.testing.assert_allclose(s["p"][1:5], p_star, rtol=1e-7)
        np.testing.assert_allclose(s["vx"][1:5], v_star, rtol=1e-7)
        # Continuity across the rarefaction tail: fan value just inside equals the star state.
        inside = riemann.sample(np.array([pos["rarefaction_tail"] - eps]), t, SOD_LEFT,
                                SOD_RIGHT, gamma)
        self.assertAlmostEqual(inside["p"][0], p_star, delta=1e-6)
        # Toro test 2 (two rarefactions) has no Sod aliases.
        case = TORO_TESTS[2]
        self.assertNotIn("shock", riemann.wave_positions(case["t"], case["left"], case["right"],
                                                         GAMMA_TORO))


def write_dump(path, frames, units=False, truncate_tail=None):
    """Write frames [(time, step, {col: values})] in LAMMPS 'dump custom' text format."""
    with open(path, "w") as f:
        for k, (time, step, cols) in enumerate(frames):
            names = list(cols)
            n = len(cols[names[0]])
            if units and k == 0:
                f.write("ITEM: UNITS\nlj\n")
            f.write(f"ITEM: TIME\n{time:.16}\nITEM: TIMESTEP\n{step}\n")
            f.write(f"ITEM: NUMBER OF ATOMS\n{n}\nITEM: BOX BOUNDS pp pp pp\n")
            f.write("-1.0000000000000000e+00 1.0000000000000000e+00\n"
                    "-5.0000000000000000e-02 5.0000000000000000e-02\n"
                    "-5.0000000000000000e-02 5.0000000000000000e-02\n")
            f.write(f"ITEM: ATOMS {' '.join(names)}\n")
            for i in range(n):
                f.write(" ".join(repr(v) if isinstance(v, float) else str(v)
                                 for v in (cols[c][i] for c in names)) + "\n")
        if truncate_tail:
            f.write(truncate_tail)


class DumpAndErrorTest(unittest.TestCase):
    GAMMA, T = 5.0 / 3.0, 0.2

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)

    def exact_columns(self, x):
        s = riemann.sample(x, self.T, SOD_LEFT, SOD_RIGHT, self.GAMMA)
        return {"id": list(range(1, len(x) + 1)), "type": [1] * len(x),
                "x": [float(v) for v in x], "y": [0.0] * len(x), "z": [0.0] * len(x),
                "vx": [float(v) for v in s["vx"]], "rho": [float(v) for v in s["rho"]],
                "pressure": [float(v) for v in s["p"]], "u": [float(v) for v in s["u"]]}

    def test_read_dump_frames(self):
        path = os.path.join(self.tmp.name, "sod.dump")
        x1 = np.linspace(-0.9, 0.9, 7)
        x2 = np.linspace(-0.95, 0.95, 11)
        write_dump(path, [(0.1, 500, self.exact_columns(x1)), (0.2, 1000, self.exact_columns(x2))],
                   units=True)
        last = dump.read_last_frame(path)
        self.assertIsInstance(last, dump.Frame)
        self.assertEqual(last.timestep, 1000)
        self.assertEqual(last.time, 0.2)
        np.testing.assert_array_equal(last.box, [[-1.0, 1.0], [-0.05, 0.05], [-0.05, 0.05]])
        self.assertEqual(list(last.columns), ["id", "type", "x", "y", "z", "vx", "rho",
                                              "pressure", "u"])
        self.assertEqual(last.columns["id"].dtype, np.int64)
        np.testing.assert_array_equal(last.columns["id"], np.arange(1, 12))
        np.testing.assert_array_equal(last.columns["x"], x2)

        frames = list(dump.read_frames(path))
        self.assertEqual([(f.timestep, f.time) for f in frames], [(500, 0.1), (1000, 0.2)])
        np.testing.assert_array_equal(frames[0].columns["x"], x1)

        # A frame still being written is skipped with a warning.
        with open(path, "a") as f:
            f.write("ITEM: TIME\n0.3\nITEM: TIMESTEP\n1500\nITEM: NUMBER OF ATOMS\n11\n"
                    "ITEM: BOX BOUNDS pp pp pp\n-1 1\n-0.05 0.05\n-0.05 0.05\n"
                    "ITEM: ATOMS id type x y z vx rho pressure u\n1 1 0.0 0 0 0 1 1 1\n2 1 0.")
        with self.assertWarns(RuntimeWarning):
            self.assertEqual(dump.read_last_frame(path).timestep, 1000)
        with self.assertWarns(RuntimeWarning):
            self.assertEqual(len(list(dump.read_frames(path))), 2)

    def test_dump_without_time(self):
        path = os.path.join(self.tmp.name, "notime.dump")
        with open(path, "w") as f:
            f.write("ITEM: TIMESTEP\n7\nITEM: NUMBER OF ATOMS\n2\n"
                    "ITEM: BOX BOUNDS xy xz yz pp pp pp\n0 2 0.1\n0 1 0\n0 1 0\n"
                    "ITEM: ATOMS id element x\n1 H 0.5\n2 He 1.5\n")
        frame = dump.read_last_frame(path)
        self.assertIsNone(frame.time)
        self.assertEqual(frame.timestep, 7)
        np.testing.assert_array_equal(frame.box, [[0, 2], [0, 1], [0, 1]])
        self.assertEqual(list(frame.columns["element"]), ["H", "He"])
        np.testing.assert_array_equal(frame.columns["x"], [0.5, 1.5])

    def test_sod_errors(self):
        x = np.linspace(-0.7, 0.7, 1401)
        path = os.path.join(self.tmp.name, "exact.dump")
        write_dump(path, [(self.T, 100, self.exact_columns(x))])
        frame = dump.read_last_frame(path)
        err = sod.sod_errors(frame, self.GAMMA, frame.time)
        inside = int(np.count_nonzero(np.abs(x) <= 0.5))
        self.assertEqual(err["n"], inside)
        for key in ("rho", "vx", "p", "u"):
            self.assertLess(err[key], 1e-13, key)

        # Known perturbations: constant offset in rho, alternating +-0.03 in vx,
        # +0.05 in P on the left half of the window only; particles outside the
        # window get large errors that must be ignored.
        cols = {k: np.array(v) for k, v in frame.columns.items()}
        window = np.abs(x) <= 0.5
        cols["rho"] = cols["rho"] + 0.01
        cols["vx"] = cols["vx"] + 0.03 * (-1.0) ** np.arange(x.size)
        cols["pressure"] = cols["pressure"] + np.where(x < 0.0, 0.05, 0.0)
        cols["u"] = np.where(window, cols["u"], 1e3)
        err = sod.sod_errors(dump.Frame(100, self.T, frame.box, cols), self.GAMMA, self.T)
        self.assertAlmostEqual(err["rho"], 0.01, delta=1e-12)
        self.assertAlmostEqual(err["vx"], 0.03, delta=1e-12)
        self.assertAlmostEqual(err["p"], 0.05 * np.count_nonzero(window & (x < 0)) / inside,
                               delta=1e-12)
        self.assertLess(err["u"], 1e-13)

        png = os.path.join(self.tmp.name, "profiles.png")
        sod.plot_profiles(frame, self.GAMMA, self.T, SOD_LEFT, SOD_RIGHT, 0.0, png,
                          xlim=(-0.5, 0.5), title="test")
        with open(png, "rb") as f:
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")

    def test_periodic_mirror(self):
        # In the periodic box [-1, 1) the discontinuity at the boundary xb = +-1 is the
        # Sod problem reflected: q(xb + d) = q_Sod(-d) for rho, P and v(xb + d) = -v_Sod(-d).
        d = np.linspace(-0.45, 0.45, 91)
        ref = riemann.sample(-d, self.T, SOD_LEFT, SOD_RIGHT, self.GAMMA)
        got = sod.exact_profile(1.0 + d, self.GAMMA, self.T, SOD_LEFT, SOD_RIGHT, 0.0, (-1.0, 1.0))
        np.testing.assert_allclose(got["rho"], ref["rho"], rtol=1e-13)
        np.testing.assert_allclose(got["p"], ref["p"], rtol=1e-13)
        np.testing.assert_allclose(got["vx"], -ref["vx"], atol=1e-13)
        with self.assertRaises(ValueError):
            sod.exact_profile(d, self.GAMMA, 0.6, SOD_LEFT, SOD_RIGHT, 0.0, (-1.0, 1.0))


if __name__ == "__main__":
    unittest.main()
