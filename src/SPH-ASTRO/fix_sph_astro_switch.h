/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(sph/astro/switch,FixSPHAstroSwitch);
// clang-format on
#else

#ifndef LMP_FIX_SPH_ASTRO_SWITCH_H
#define LMP_FIX_SPH_ASTRO_SWITCH_H

#include "fix.h"

namespace LAMMPS_NS {

// Per-particle artificial viscosity alpha, two switches:
// morris-monaghan (Morris & Monaghan 1997, J. Comput. Phys. 136, 41):
//   d alpha_i/dt = -(alpha_i - alpha_min) / tau_i + S_i,  tau_i = h_i / (l c_i)
//   S_i = max(-div v_i, 0) (alpha_max - alpha_i)
// (the source term with the (alpha_max - alpha) factor of Rosswog et al. 2000, which keeps
// alpha below alpha_max);
// cullen-dehnen (Cullen & Dehnen 2010, MNRAS 408, 669; switch_cullen_dehnen() in
// sph_astro_pair_terms.h): alpha jumps to a local value set by the growth of compression,
// -d(div v)/dt, limited by the shear, and decays on tau_i = h_i / (l c_i) elsewhere.
// d(div v)/dt is the change of div v over the last step; the previous div v is the custom
// property d_divv_prev of the fix SPH_ASTRO_DIVV_PREV.
// alpha lives in the custom per-atom property d_alpha of the fix SPH_ASTRO_ALPHA (restart,
// dump, set, Python like the rest of the state).
class FixSPHAstroSwitch : public Fix {
 public:
  FixSPHAstroSwitch(class LAMMPS *, int, char **);
  int setmask() override;
  void post_constructor() override;
  void init() override;
  void setup_pre_force(int) override;
  void setup(int) override;
  void pre_force(int) override;
  void final_integrate() override;
  void set_arrays(int) override;
  double compute_vector(int) override;

  double *alpha();    // d_alpha (owned + ghost)
  double alpha_min() const { return alpha_min_; }
  double alpha_max() const { return alpha_max_; }
  double decay() const { return ell_; }
  // "needs_curl" (int): pair sph/astro computes curl v for this switch
  void *extract(const char *, int &) override;

 protected:
  enum class Form { MORRIS_MONAGHAN, CULLEN_DEHNEN };
  Form form_;
  double alpha_min_, alpha_max_, ell_;
  int alpha_index_;
  double *alpha_force();      // d_alpha_force: the alpha of the last force evaluation
  bool alpha_force_valid_;    // d_alpha_force holds that value for every particle
  double *divv_prev();        // d_divv_prev (Cullen-Dehnen)
  int needs_curl_;
  int h_index_;    // d_h
  class PairSPHAstro *pair_;
  class FixSPHAstro *integrator_;    // fix sph/astro: each particle's step
};

}    // namespace LAMMPS_NS

#endif
#endif
