/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: astrophysical smoothed particle hydrodynamics for LAMMPS
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(sph/astro/global,ComputeSPHAstroGlobal);
// clang-format on
#else

#ifndef LMP_COMPUTE_SPH_ASTRO_GLOBAL_H
#define LMP_COMPUTE_SPH_ASTRO_GLOBAL_H

#include "compute.h"

namespace SPHAstro {
struct StateIndex;
}    // namespace SPHAstro

namespace LAMMPS_NS {

class ComputeSPHAstroGlobal : public Compute {
 public:
  ComputeSPHAstroGlobal(class LAMMPS *, int, char **);
  ~ComputeSPHAstroGlobal() override;
  void init() override;
  void compute_vector() override;

  enum Index {
    MASS,
    PX,
    PY,
    PZ,
    LX,
    LY,
    LZ,
    EKIN,
    ETHERM,
    EPOT,
    ETOT,
    DEREL,
    HMIN,
    HMAX,
    HITER_MEAN,
    HITER_MAX,
    HITER_FAILED,
    HCAPPED,
    NVALUES
  };

 private:
  SPHAstro::StateIndex *state_;
  class PairSPHAstro *pair_;
  class FixSPHAstro *fix_;
  class Fix *hfix_;    // fix sph/astro/h, for the h-iteration statistics
  bool own_reference_set_;
  double own_reference_;
};

}    // namespace LAMMPS_NS

#endif
#endif
