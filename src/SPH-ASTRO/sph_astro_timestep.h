/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Timestep criteria of one particle (plain functions; fix sph/astro takes the minimum over
// particles). Each returns +infinity where the criterion does not constrain the step.
//   Courant   dt = C h / v, v = max_j v_sig,ij (signal viscosity; Monaghan 1997; Springel 2005,
//             MNRAS 364, 1105, eq. 16) or c + h|div v| + 1.2 (alpha c + beta h|div v|)
//             (Monaghan 1992, sec. 10.3, with the viscosity's signal speed)
//   force     dt = C_f sqrt(h / |a|)                              (Monaghan 1992, sec. 10.3)
//   energy    dt = C_u u / |du/dt| where du/dt < 0 (u stays positive)
//   conduction (physical) dt = C_k rho h^2 / kappa               (sph_astro_conduction.h)
//   conductivity (artificial) dt = C_a / sum_j k_ij: Gershgorin bound of its explicit
//             diffusion (sph_astro_pair_terms.h), stable for C_a <= 1

#ifndef LMP_SPH_ASTRO_TIMESTEP_H
#define LMP_SPH_ASTRO_TIMESTEP_H

#include <cmath>

namespace SPHAstro {

inline double viscous_signal_speed(double c, double h, double divv, double alpha, double beta)
{
  const double hdiv = h * std::fabs(divv);
  return c + hdiv + 1.2 * (alpha * c + beta * hdiv);
}

inline double dt_courant(double courant, double h, double vsig)
{
  return vsig > 0.0 ? courant * h / vsig : INFINITY;
}

inline double dt_force(double factor, double h, double accel)
{
  return accel > 0.0 ? factor * std::sqrt(h / accel) : INFINITY;
}

inline double dt_energy(double factor, double u, double dudt)
{
  return dudt < 0.0 ? factor * u / -dudt : INFINITY;
}

inline double dt_conductivity(double factor, double rate)
{
  return rate > 0.0 ? factor / rate : INFINITY;
}

}    // namespace SPHAstro

#endif
