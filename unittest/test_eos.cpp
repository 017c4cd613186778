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
