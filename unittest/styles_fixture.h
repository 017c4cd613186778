/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// What the LAMMPS-driven tests of the styles share: the default pair style, the columns of
// compute sph/astro/global and the energy error of an expanding ball.

#ifndef SPH_ASTRO_STYLES_FIXTURE_H
#define SPH_ASTRO_STYLES_FIXTURE_H

#include "lammps_fixture.h"

#include <cmath>
#include <string>

namespace sph_astro_test {

inline const char *PAIR = "sph/astro kernel m4 eos ideal $(5.0/3.0) viscosity classic 1.0 2.0";
enum { MASS, PX, PY, PZ, LX, LY, LZ, EKIN, ETHERM, EPOT, ETOT, DEREL };

// relative total energy error of an expanding ball after t = 0.4 with fixed dt; second order:
// halving dt cuts it by 4. pair: the pair_style arguments; extra: a further command or ""
inline double energy_error(double dt, const std::string &pair = PAIR, const std::string &extra = "")
{
  auto lmp = open_lammps();
  gas(lmp, "ball", 6, pair, "sph/astro dt fixed");
  if (!extra.empty()) commands(lmp, {extra});
  const int nsteps = static_cast<int>(std::lround(0.4 / dt));
  commands(lmp,
           {"timestep " + std::to_string(dt), "thermo " + std::to_string(nsteps),
            "run " + std::to_string(nsteps)});
  const auto end = global_vector(lmp, "sum", 12);
  return std::fabs(end[DEREL]);
}

}    // namespace sph_astro_test

#endif
