"""The shock-radius measures of sphastro.noh (examples/noh/analyse.py) on a synthetic smeared
shock."""

import math
import unittest

import numpy as np

from sphastro import noh


class ShockRadiusTest(unittest.TestCase):
    def setUp(self):
        self.noh = noh
        # Noh at t = 0.6: 64 inside R_s = 0.2, (1 + t/r)^2 outside, smeared symmetrically
        # (error function of width w) and sampled at the centres of 0.01 wide bins
        self.t, self.rs, self.w = 0.6, 0.2, 0.006
        self.centres = np.arange(0.005, 0.4, 0.01)
        step = 0.5 * np.array([math.erfc((r - self.rs) / self.w) for r in self.centres])
        self.pre = (1.0 + self.t / self.centres) ** 2
        self.rho = 64.0 * step + self.pre * (1.0 - step)

    def test_midpoint_finds_the_centre_of_the_smeared_step(self):
        r_mid = self.noh.shock_radius(self.centres, self.rho, 0.5 * (64.0 + self.pre), 0.05)
        self.assertLess(abs(r_mid / self.rs - 1.0), 0.002)

    def test_half_the_post_shock_density_lies_outside_it(self):
        # the headline measure ignores the pre-shock 16: it sits outside R_s by a fraction of
        # the smearing width (here 1.0 % of R_s, 0.35 w; the midpoint is 0.03 % inside)
        r_half = self.noh.shock_radius(self.centres, self.rho, 32.0, 0.05)
        self.assertGreater(r_half / self.rs - 1.0, 0.005)
        self.assertLess(r_half / self.rs - 1.0, 0.03)

    def test_scalar_and_array_thresholds_agree(self):
        a = self.noh.shock_radius(self.centres, self.rho, 40.0, 0.05)
        b = self.noh.shock_radius(self.centres, self.rho, np.full_like(self.rho, 40.0), 0.05)
        self.assertEqual(a, b)

    def test_no_crossing_gives_nan(self):
        self.assertTrue(math.isnan(self.noh.shock_radius(self.centres, self.rho, 1000.0, 0.05)))


if __name__ == "__main__":
    unittest.main()
