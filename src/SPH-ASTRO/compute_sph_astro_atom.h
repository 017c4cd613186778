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
ComputeStyle(sph/astro/atom,ComputeSPHAstroAtom);
// clang-format on
#else

#ifndef LMP_COMPUTE_SPH_ASTRO_ATOM_H
#define LMP_COMPUTE_SPH_ASTRO_ATOM_H

#include "compute.h"
#include "sph_astro_state.h"

#include <vector>

namespace LAMMPS_NS {

class ComputeSPHAstroAtom : public Compute {
 public:
  ComputeSPHAstroAtom(class LAMMPS *, int, char **);
  ~ComputeSPHAstroAtom() override;
  void init() override;
  void compute_peratom() override;
  double memory_usage() override;

 private:
  enum Field { RHO, H, PRESSURE, SOUNDSPEED, U, NNEIGH, DIVV, DUDT, OMEGA, ALPHA, BIN, DT };
  std::vector<Field> fields_;
  int nmax_;
  double *vector_;
  double **array_;
  SPHAstro::StateIndex *state_;
  SPHAstro::StepIndex steps_;    // time bins (fix sph/astro steps individual), if any
  class PairSPHAstro *pair_;
  class FixSPHAstro *fix_;    // the timestep criteria (field dt)
  std::vector<double> dt_;
};

}    // namespace LAMMPS_NS

#endif
#endif
