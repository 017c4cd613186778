/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: reference self-gravity by direct (or Ewald) summation
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(sph/astro/gravity/direct,ComputeSPHAstroGravityDirect);
// clang-format on
#else

#ifndef LMP_COMPUTE_SPH_ASTRO_GRAVITY_DIRECT_H
#define LMP_COMPUTE_SPH_ASTRO_GRAVITY_DIRECT_H

#include "compute.h"

#include <vector>

namespace LAMMPS_NS {

class ComputeSPHAstroGravityDirect : public Compute {
 public:
  ComputeSPHAstroGravityDirect(class LAMMPS *, int, char **);
  ~ComputeSPHAstroGravityDirect() override;
  void init() override;
  double compute_scalar() override;
  void compute_peratom() override;
  double memory_usage() override;

 private:
  class PairSPHAstroGravity *pair_;
  int nmax_;
  double **result_;    // fx fy fz phi of the owned atoms
  double energy_;      // 1/2 sum_i m_i phi_i over all atoms

  // all atoms of all ranks
  std::vector<double> x_, m_, h_;
  std::vector<tagint> tag_;

  void gather();
  void evaluate();
  void direct_sum();
  void ewald_sum();
};

}    // namespace LAMMPS_NS

#endif
#endif
