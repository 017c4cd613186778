/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO: astrophysical smoothed particle hydrodynamics for LAMMPS
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(sph/astro/switch,FixSPHAstroSwitch);
// clang-format on
#else

#ifndef LMP_FIX_SPH_ASTRO_SWITCH_H
#define LMP_FIX_SPH_ASTRO_SWITCH_H

#include "fix.h"
#include "sph_astro_state.h"

namespace LAMMPS_NS {

// Per-particle artificial viscosity alpha (Morris & Monaghan 1997, J. Comput. Phys. 136, 41;
// seed 000 "switch to reduce viscosity"):
//   d alpha_i/dt = -(alpha_i - alpha_min) / tau_i + S_i,  tau_i = h_i / (l c_i)
//   S_i = max(-div v_i, 0) (alpha_max - alpha_i)
// (the source term with the (alpha_max - alpha) factor of Rosswog et al. 2000, which keeps
// alpha below alpha_max). alpha lives in the custom per-atom property d_alpha of the fix
// SPH_ASTRO_ALPHA (restart, dump, set, Python like the rest of the state).
class FixSPHAstroSwitch : public Fix {
 public:
  FixSPHAstroSwitch(class LAMMPS *, int, char **);
  int setmask() override;
  void post_constructor() override;
  void init() override;
  void final_integrate() override;
  double compute_vector(int) override;

  double *alpha();    // d_alpha (owned + ghost)
  double alpha_min() const { return alpha_min_; }
  double alpha_max() const { return alpha_max_; }
  double decay() const { return ell_; }

 protected:
  double alpha_min_ = 0.1, alpha_max_ = 1.0, ell_ = 0.1;
  int alpha_index_ = -1;
  SPHAstro::StateIndex state_;
  class PairSPHAstro *pair_ = nullptr;
};

}    // namespace LAMMPS_NS

#endif
#endif
