/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Equations of state: pressure, sound speed and the energy used for
// bookkeeping.

#include "sph_astro_eos.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace SPHAstro;

TEST(EOS, IdealGas)
{
  EOS eos;
  eos.type = EOSType::IDEAL;
  eos.gamma = 5.0 / 3.0;
  double P, c;
  // Sod left state: rho 1, P 1 -> u = P / ((gamma-1) rho) = 1.5
  eos.pressure_soundspeed(1.0, 1.5, P, c);
  EXPECT_NEAR(P, 1.0, 1e-15);
  EXPECT_NEAR(c, std::sqrt(5.0 / 3.0), 1e-15);
  eos.pressure_soundspeed(0.125, 0.1 / (0.125 * 2.0 / 3.0), P, c);
  EXPECT_NEAR(P, 0.1, 1e-15);
  EXPECT_NEAR(c, std::sqrt(5.0 / 3.0 * 0.1 / 0.125), 1e-14);
  EXPECT_TRUE(eos.uses_energy());
  EXPECT_DOUBLE_EQ(eos.energy_of(0.3, 2.0), 2.0);
  // cold gas: zero pressure and sound speed, never NaN
  eos.pressure_soundspeed(1.0, 0.0, P, c);
  EXPECT_EQ(P, 0.0);
  EXPECT_EQ(c, 0.0);
}

TEST(EOS, Isothermal)
{
  EOS eos;
  eos.type = EOSType::ISOTHERMAL;
  eos.cs = 0.5;
  double P, c;
  eos.pressure_soundspeed(2.0, 123.0, P, c);    // u does not enter
  EXPECT_DOUBLE_EQ(P, 0.5);
  EXPECT_DOUBLE_EQ(c, 0.5);
  EXPECT_FALSE(eos.uses_energy());
}

TEST(EOS, Polytropic)
{
  // toy star (Monaghan & Price 2006): P = k rho^(1+1/n), n = 1 -> gamma = 2
  EOS eos;
  eos.type = EOSType::POLYTROPIC;
  eos.K = 0.1;
  eos.gamma = 2.0;
  double P, c;
  eos.pressure_soundspeed(3.0, 0.0, P, c);
  EXPECT_NEAR(P, 0.9, 1e-15);
  EXPECT_NEAR(c, std::sqrt(2.0 * 0.9 / 3.0), 1e-15);
  EXPECT_FALSE(eos.uses_energy());
  // u = P / ((gamma - 1) rho), the energy whose sum with the kinetic energy is
  // conserved
  EXPECT_NEAR(eos.energy_of(3.0, 0.0), 0.9 / 3.0, 1e-15);
  // c_s^2 = dP/drho
  const double d = 1e-6;
  double Pp, Pm, cdum;
  eos.pressure_soundspeed(3.0 + d, 0.0, Pp, cdum);
  eos.pressure_soundspeed(3.0 - d, 0.0, Pm, cdum);
  EXPECT_NEAR(c * c, (Pp - Pm) / (2 * d), 1e-8);
}

// barotropic gas of collapse calculations (Bate, Bonnell & Price 1995; Bate & Burkert 1997):
// P = c_s^2 rho [1 + (rho/rho_crit)^(gamma-1)], isothermal below rho_crit, adiabatic above
TEST(EOS, Barotropic)
{
  EOS eos;
  eos.type = EOSType::BAROTROPIC;
  eos.cs = 0.3;
  eos.rho_crit = 2.0;
  eos.gamma = 1.4;
  EXPECT_FALSE(eos.uses_energy());
  double P, c;
  // the formula at rho_crit: P = 2 c_s^2 rho_crit, c^2 = c_s^2 (1 + gamma)
  eos.pressure_soundspeed(2.0, 99.0, P, c);    // u does not enter
  EXPECT_NEAR(P, 2.0 * 0.09 * 2.0, 1e-15);
  EXPECT_NEAR(c * c, 0.09 * 2.4, 1e-15);
  // and at another density, written out
  const double rho = 7.5, s = std::pow(rho / 2.0, 0.4);
  eos.pressure_soundspeed(rho, 0.0, P, c);
  EXPECT_NEAR(P, 0.09 * rho * (1.0 + s), 1e-14);
  EXPECT_NEAR(c, 0.3 * std::sqrt(1.0 + 1.4 * s), 1e-15);

  // isothermal limit rho << rho_crit: P -> c_s^2 rho, c -> c_s (relative deviation
  // (rho/rho_crit)^(gamma-1) = 1e-4 at rho = 1e-10 rho_crit)
  double Pi, ci;
  EOS iso;
  iso.type = EOSType::ISOTHERMAL;
  iso.cs = 0.3;
  eos.pressure_soundspeed(2e-10, 0.0, P, c);
  iso.pressure_soundspeed(2e-10, 0.0, Pi, ci);
  EXPECT_NEAR(P / Pi - 1.0, 1e-4, 1e-9);
  EXPECT_GT(P, Pi);
  EXPECT_NEAR(c / ci - 1.0, 0.5 * 1.4e-4, 1e-8);
  // adiabatic limit rho >> rho_crit: P -> K rho^gamma with K = c_s^2 rho_crit^(1-gamma),
  // c^2 -> gamma P / rho
  EOS poly;
  poly.type = EOSType::POLYTROPIC;
  poly.gamma = 1.4;
  poly.K = 0.09 * std::pow(2.0, -0.4);
  double Pp, cp;
  eos.pressure_soundspeed(2e10, 0.0, P, c);
  poly.pressure_soundspeed(2e10, 0.0, Pp, cp);
  EXPECT_NEAR(P / Pp - 1.0, 1e-4, 1e-9);    // (rho/rho_crit)^(1-gamma) = 1e-4
  EXPECT_NEAR(c / cp - 1.0, 0.5e-4 / 1.4, 1e-8);

  // c^2 = dP/drho (central differences, step 1e-5 rho) across the transition
  for (double r : {1e-3, 0.5, 2.0, 3.0, 40.0, 1e4}) {
    const double d = 1e-5 * r;
    double Pplus, Pminus, cdum;
    eos.pressure_soundspeed(r + d, 0.0, Pplus, cdum);
    eos.pressure_soundspeed(r - d, 0.0, Pminus, cdum);
    eos.pressure_soundspeed(r, 0.0, P, c);
    EXPECT_NEAR((Pplus - Pminus) / (2.0 * d) / (c * c), 1.0, 1e-8) << "rho = " << r;
  }

  // the energy of the adiabatic part: du/drho = P_ad / rho^2, P_ad = P - c_s^2 rho; -> 0 in
  // the isothermal limit
  for (double r : {0.5, 2.0, 40.0}) {
    const double d = 1e-5 * r;
    eos.pressure_soundspeed(r, 0.0, P, c);
    const double dudrho = (eos.energy_of(r + d, 0.0) - eos.energy_of(r - d, 0.0)) / (2.0 * d);
    EXPECT_NEAR(dudrho, (P - 0.09 * r) / (r * r), 1e-9 * P / (r * r)) << "rho = " << r;
  }
  EXPECT_NEAR(eos.energy_of(2e-10, 0.0), 0.09 * 1e-4 / 0.4, 1e-15);    // c_s^2 1e-4 / (gamma-1)
}
