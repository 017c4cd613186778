"""Tests of the Sedov-Taylor solution (python/sphastro/sedov.py).

Run from the repository root with::

    build/venv/bin/python -m pytest python/tests
"""

import math
import unittest

import numpy as np

from sphastro import sedov

GAMMAS = (1.1, 1.2, 1.4, 5.0 / 3.0, 2.0, 2.5, 3.0)


class Xi0Test(unittest.TestCase):
    def test_published_values(self):
        # Kamm & Timmes (2007): xi0 = 1.15167 for gamma = 5/3; 1.03275 (brief's value,
        # 1.0328 to the quoted accuracy; Landau & Lifshitz: 1.033) for gamma = 1.4.
        self.assertAlmostEqual(sedov.xi0(5.0 / 3.0), 1.15167, delta=1e-4)
        self.assertAlmostEqual(sedov.xi0(1.4), 1.03275, delta=1e-4)

    def test_energy_constant_alpha(self):
        # E = alpha rho0 R^5 / t^2 with alpha = (16 pi / 25) I = xi0^-5; Kamm & Timmes
        # (2007) table 1 lists alpha(j = 3, gamma = 1.4) = 0.851072
        alpha = 16.0 * math.pi / 25.0 * sedov.energy_integral(1.4)
        self.assertAlmostEqual(alpha, 0.851072, delta=2e-6)
        self.assertAlmostEqual(sedov.xi0(1.4) ** -5, alpha, delta=1e-12)

    def test_quadrature_converged(self):
        for gamma in GAMMAS:
            with self.subTest(gamma=gamma):
                a = sedov.energy_integral(gamma, n=200)
                b = sedov.energy_integral(gamma, n=2000)
                self.assertLess(abs(a - b), 1e-9 * b)

    def test_shock_radius_scaling(self):
        r1 = sedov.shock_radius(1.0, 1.0, 0.1, 5.0 / 3.0)
        self.assertAlmostEqual(r1, 1.15167 * 0.01 ** 0.2, delta=1e-4)
        self.assertAlmostEqual(sedov.shock_radius(32.0, 1.0, 0.1, 5.0 / 3.0), 2.0 * r1,
                               delta=1e-12)
        self.assertAlmostEqual(sedov.shock_radius(1.0, 1.0, 0.1 * 2.0 ** 2.5, 5.0 / 3.0),
                               2.0 * r1, delta=1e-12)
        self.assertAlmostEqual(sedov.shock_radius(1.0, 1.0 / 32.0, 0.1, 5.0 / 3.0), 2.0 * r1,
                               delta=1e-12)

    def test_gamma_out_of_range(self):
        for gamma in (1.0, 0.5, 7.0, 8.0):
            with self.assertRaises(ValueError):
                sedov.xi0(gamma)


class ProfileTest(unittest.TestCase):
    E, RHO0, T = 1.0, 1.0, 0.1

    def test_post_shock_density(self):
        for gamma in GAMMAS:
            rs = sedov.shock_radius(self.E, self.RHO0, self.T, gamma)
            prof = sedov.profile(np.array([rs, rs * (1 + 1e-9)]), self.E, self.RHO0, self.T,
                                 gamma)
            jump = sedov.post_shock(self.E, self.RHO0, self.T, gamma)
            with self.subTest(gamma=gamma):
                self.assertAlmostEqual(prof["rho"][0], (gamma + 1) / (gamma - 1) * self.RHO0,
                                       delta=1e-9)
                for key in ("rho", "v", "p", "u"):
                    self.assertAlmostEqual(prof[key][0], jump[key], delta=1e-9 * jump[key])
                # ahead of the shock: the undisturbed cold medium
                self.assertEqual(prof["rho"][1], self.RHO0)
                self.assertEqual(prof["v"][1], 0.0)
                self.assertEqual(prof["p"][1], 0.0)

    def test_rankine_hugoniot(self):
        gamma = 5.0 / 3.0
        d = sedov.shock_velocity(self.E, self.RHO0, self.T, gamma)
        s = sedov.post_shock(self.E, self.RHO0, self.T, gamma)
        # mass and momentum fluxes through the shock (cold, resting upstream gas)
        self.assertAlmostEqual(s["rho"] * (d - s["v"]), self.RHO0 * d, delta=1e-12)
        self.assertAlmostEqual(s["p"] + s["rho"] * (d - s["v"]) ** 2, self.RHO0 * d * d,
                               delta=1e-10)

    def _energy_and_mass(self, gamma, panels=16, n=48):
        # composite Gauss-Legendre over r in [0, R_s], independent of sedov's own quadrature
        rs = sedov.shock_radius(self.E, self.RHO0, self.T, gamma)
        x, w = np.polynomial.legendre.leggauss(n)
        edges = np.linspace(0.0, rs, panels + 1)
        half = 0.5 * np.diff(edges)[:, None]
        r = (edges[:-1, None] + half * (x + 1.0)).ravel()
        w = (half * w).ravel()
        prof = sedov.profile(r, self.E, self.RHO0, self.T, gamma)
        shell = 4.0 * math.pi * r * r * w
        energy = np.sum(shell * (0.5 * prof["rho"] * prof["v"] ** 2
                                 + prof["p"] / (gamma - 1.0)))
        mass = np.sum(shell * prof["rho"])
        return energy, mass, rs

    def test_total_energy_and_mass(self):
        for gamma in GAMMAS:
            energy, mass, rs = self._energy_and_mass(gamma)
            with self.subTest(gamma=gamma):
                self.assertAlmostEqual(energy, self.E, delta=1e-7)
                # all swept-up mass sits inside the shock (independent of the xi0 integral)
                self.assertAlmostEqual(mass, 4.0 / 3.0 * math.pi * rs ** 3 * self.RHO0,
                                       delta=1e-7 * mass)
                self.assertAlmostEqual(sedov.mass_integral(gamma), 1.0 / 3.0, delta=1e-9)

    def test_euler_equations(self):
        # the profile solves the self-similar continuity and momentum equations:
        #   -xi G' + xi^-2 (xi^3 G V)' = 0,   -(3/2) xi V - xi (xi V)' + xi V (xi V)' + P'/G = 0
        for gamma in (1.4, 5.0 / 3.0, 3.0):
            xi = np.linspace(0.3, 0.98, 35)
            h = 1e-5

            def f(x):
                return sedov.similarity_profile(x, gamma)

            v0, g0, _ = f(xi)
            vp, gp, pp = f(xi + h)
            vm, gm, pm = f(xi - h)
            dg = (gp - gm) / (2 * h)
            dmass = ((xi + h) ** 3 * gp * vp - (xi - h) ** 3 * gm * vm) / (2 * h)
            dw = ((xi + h) * vp - (xi - h) * vm) / (2 * h)
            dp = (pp - pm) / (2 * h)
            w = xi * v0
            with self.subTest(gamma=gamma):
                np.testing.assert_allclose(-xi * dg + dmass / xi ** 2, 0.0, atol=1e-6 * g0.max())
                np.testing.assert_allclose(-1.5 * w - xi * dw + w * dw + dp / g0, 0.0, atol=1e-5)

    def test_centre(self):
        gamma = 5.0 / 3.0
        prof = sedov.profile(np.array([0.0, 1e-6, 1e-3]), self.E, self.RHO0, self.T, gamma)
        self.assertEqual(prof["rho"][0], 0.0)
        self.assertEqual(prof["v"][0], 0.0)
        self.assertTrue(np.isinf(prof["u"][0]))
        # the pressure is finite and flat at the centre (about 0.306 of the post-shock value)
        p2 = sedov.post_shock(self.E, self.RHO0, self.T, gamma)["p"]
        self.assertTrue(np.all(np.isfinite(prof["p"])))
        self.assertLess(abs(prof["p"][2] / prof["p"][0] - 1.0), 1e-6)
        self.assertAlmostEqual(prof["p"][0] / p2, 0.3063, delta=5e-3)
        self.assertTrue(np.all(np.diff(sedov.profile(np.linspace(0, 0.45, 200), self.E,
                                                     self.RHO0, self.T, gamma)["rho"]) >= 0))

    def test_gamma_two_continuous(self):
        # gamma = 2 is the singular case of the closed form; the solution must be continuous
        xi = np.linspace(0.0, 1.0, 11)
        a = np.array(sedov.similarity_profile(xi, 2.0))
        for other in (2.0 - 1e-3, 2.0 + 1e-3):
            b = np.array(sedov.similarity_profile(xi, other))
            np.testing.assert_allclose(a, b, atol=1e-2)
        self.assertLess(abs(sedov.xi0(2.0) - 0.5 * (sedov.xi0(1.999) + sedov.xi0(2.001))), 1e-7)


class ShockMeasuresTest(unittest.TestCase):
    def test_half_height_across_an_empty_bin(self):
        # a step from 2 to 1 at r = 0.5, sampled with a gap between 0.48 and 0.52: the bin
        # that holds the gap is empty, the crossing of 1.5 lies across it
        r = np.concatenate([np.linspace(0.01, 0.479, 200), np.linspace(0.521, 0.59, 40)])
        rho = np.where(r < 0.5, 2.0, 1.0)
        res = sedov.shock_measures(r, rho, rs=0.5, rho0=1.0, nbins=60)
        self.assertEqual(res["rho_peak"], 2.0)
        self.assertTrue(np.any(res["counts"] == 0))
        self.assertTrue(math.isfinite(res["r_half"]))
        self.assertGreater(res["r_half"], 0.47)
        self.assertLess(res["r_half"], 0.53)


if __name__ == "__main__":
    unittest.main()
