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

#include <cstdint>

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
  // E0: taken at the first evaluation (or from fix sph/astro's restart record), kept while the
  // state continues, set anew at the first evaluation after v or u changed between runs
  bool own_reference_set_;
  double own_reference_;
  bool check_state_ = false;    // at the first evaluation after init()
  // the state read at the last evaluation: its hash (atom_state_hash()) and step
  uint64_t read_hash_ = 0;
  bigint read_step_ = -1;
};

}    // namespace LAMMPS_NS

#endif
#endif
