"""Tests of the toy-star reference (python/sphastro/toystar.py).

Run from the repository root with::

    build/venv/bin/python -m pytest python/tests
"""

import math
import unittest

import numpy as np

from sphastro import toystar

CASES = ((2.0, 0.75, 0.1, 1.0), (1.0, 1.0, 0.4, 1.5), (3.0, 2.0, 1.0, 0.5), (0.5, 0.3, 0.05, 3.0))


class LambdaTest(unittest.TestCase):
    def test_closed_form_n1(self):
        # n = 1: Gamma(7/2) = 15 sqrt(pi)/8, so lambda = 15 k M / (2 pi R^5); for the
        # star of examples/toystar (Monaghan & Price 2006, MNRAS 365, 991),
        # M = 2, R = 0.75, k = 0.1: 2.01203
        for M, R, k in ((2.0, 0.75, 0.1), (1.0, 1.0, 1.0), (5.0, 0.3, 0.02)):
            with self.subTest(M=M, R=R, k=k):
                self.assertAlmostEqual(toystar.toystar_lambda(M, R, k, 1.0),
                                       15.0 * k * M / (2.0 * math.pi * R ** 5), delta=1e-12 *
                                       15.0 * k * M / (2.0 * math.pi * R ** 5))
        self.assertAlmostEqual(toystar.toystar_lambda(2.0, 0.75, 0.1, 1.0), 2.01203, delta=1e-5)

    def test_mass_integrates_to_M(self):
        # the pi exponent -3/(2n) matters for n != 1: pi^(-3/2) would miss M by pi^(3/2 (1-1/n))
        for M, R, k, n in CASES:
            with self.subTest(M=M, R=R, k=k, n=n):
                mass = toystar.enclosed_mass(R, M, R, k, n, npts=20001)
                self.assertLess(abs(mass / M - 1.0), 1e-6 if n >= 1 else 1e-4)

    def test_mass_2d(self):
        for M, R, k, n in CASES:
            with self.subTest(M=M, R=R, k=k, n=n):
                lam = toystar.toystar_lambda(M, R, k, n, dim=2)
                s = np.linspace(0.0, R, 200001)
                rho = (lam / (2 * k * (1 + n)) * (R * R - s * s)) ** n
                mass = np.trapz(2.0 * math.pi * s * rho, s)
                self.assertLess(abs(mass / M - 1.0), 1e-6)

    def test_scaling(self):
        # lambda ~ k, and doubling M at fixed R, k multiplies lambda by 2^(1/n)
        for M, R, k, n in CASES:
            lam = toystar.toystar_lambda(M, R, k, n)
            self.assertAlmostEqual(toystar.toystar_lambda(M, R, 3 * k, n) / lam, 3.0, places=12)
            self.assertAlmostEqual(toystar.toystar_lambda(2 * M, R, k, n) / lam, 2 ** (1 / n),
                                   places=12)

    def test_bad_input(self):
        for args in ((0.0, 1.0, 1.0, 1.0), (1.0, -1.0, 1.0, 1.0), (1.0, 1.0, 0.0, 1.0),
                     (1.0, 1.0, 1.0, 0.0)):
            with self.assertRaises(ValueError):
                toystar.toystar_lambda(*args)
        with self.assertRaises(ValueError):
            toystar.toystar_lambda(1.0, 1.0, 1.0, 1.0, dim=1)


class ProfileTest(unittest.TestCase):
    def test_hydrostatic_equilibrium(self):
        # -dP/dr / rho = lambda r with P = k rho^(1+1/n)
        for M, R, k, n in CASES:
            with self.subTest(n=n):
                lam = toystar.toystar_lambda(M, R, k, n)
                r = np.linspace(0.05 * R, 0.9 * R, 50)
                dr = 1e-6 * R
                p = lambda s: k * toystar.density(s, M, R, k, n) ** (1 + 1 / n)  # noqa: E731
                dpdr = (p(r + dr) - p(r - dr)) / (2 * dr)
                acc = -dpdr / toystar.density(r, M, R, k, n)
                np.testing.assert_allclose(acc, lam * r, rtol=1e-6)

    def test_zero_outside_and_edges(self):
        M, R, k, n = CASES[0]
        rho = toystar.density([0.0, R, 1.5 * R], M, R, k, n)
        self.assertGreater(rho[0], 0.0)
        self.assertEqual(rho[1], 0.0)
        self.assertEqual(rho[2], 0.0)
        self.assertAlmostEqual(toystar.central_density(M, R, k, n),
                               (toystar.toystar_lambda(M, R, k, n) / (4 * k) * R * R), places=12)

    def test_mean_square_radius(self):
        for M, R, k, n in CASES:
            with self.subTest(n=n):
                s = np.linspace(0.0, R, 200001)
                w = s ** 2 * toystar.density(s, M, R, k, n)
                msq = np.trapz(w * s * s, s) / np.trapz(w, s)
                self.assertAlmostEqual(msq / toystar.mean_square_radius(R, n), 1.0, delta=1e-6)


class ErrorsTest(unittest.TestCase):
    """toystar_errors on synthetic particle sets with a known answer."""

    def sample(self, M, R, k, n, npart=20000, seed=1):
        # positions drawn from the profile by inverting the enclosed mass on a table
        rng = np.random.default_rng(seed)
        s = np.linspace(0.0, R, 4001)
        cum = np.array([toystar.enclosed_mass(si, M, R, k, n, npts=201) for si in s]) / M
        r = np.interp(rng.random(npart), cum, s)
        d = rng.normal(size=(npart, 3))
        d /= np.linalg.norm(d, axis=1)[:, None]
        x = r[:, None] * d
        return {"x": x[:, 0], "y": x[:, 1], "z": x[:, 2]}, r

    def test_exact_density_gives_zero_error(self):
        M, R, k, n = 2.0, 0.75, 0.1, 1.0
        cols, r = self.sample(M, R, k, n)
        cols["rho"] = toystar.density(r, M, R, k, n)
        err = toystar.toystar_errors(cols, M, R, k, n)
        self.assertLess(err["l1"], 1e-12)
        self.assertAlmostEqual(err["r_fit"], R, delta=1e-9)
        self.assertAlmostEqual(err["err_lambda"], 0.0, delta=1e-9)
        # <r^2> of a sample of 20 000: a statistical 0.5 % at most
        self.assertLess(abs(err["err_r_rms"]), 5e-3)
        self.assertLess(err["r_max"], R)

    def test_scaled_star_is_detected(self):
        # a star 10 % larger (same n): the fit and the rms radius see +10 %, L1 is not zero
        M, R, k, n = 2.0, 0.75, 0.1, 1.0
        cols, r = self.sample(M, 1.1 * R, k, n)
        cols["rho"] = toystar.density(r, M, 1.1 * R, k, n)
        err = toystar.toystar_errors(cols, M, R, k, n)
        self.assertAlmostEqual(err["err_r_fit"], 0.1, delta=1e-6)
        self.assertAlmostEqual(err["err_r_rms"], 0.1, delta=1e-2)
        self.assertGreater(err["l1_rel"], 0.05)


if __name__ == "__main__":
    unittest.main()
