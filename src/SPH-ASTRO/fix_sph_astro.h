/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO: astrophysical smoothed particle hydrodynamics for LAMMPS
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(sph/astro,FixSPHAstro);
// clang-format on
#else

#ifndef LMP_FIX_SPH_ASTRO_H
#define LMP_FIX_SPH_ASTRO_H

#include "fix.h"
#include "sph_astro_state.h"

namespace LAMMPS_NS {

class FixSPHAstro : public Fix {
 public:
  FixSPHAstro(class LAMMPS *, int, char **);

  int setmask() override;
  void post_constructor() override;
  void init() override;
  void setup(int) override;
  void initial_integrate(int) override;
  void final_integrate() override;
  void end_of_step() override;
  void post_run() override;
  double compute_scalar() override;
  double compute_vector(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

  // reference total energy for compute sph/astro/global: set once, kept across restarts
  double reference_energy(double current);

 protected:
  double courant_ = 0.3;         // C in dt = C h / (c + h|div v| + 1.2 (alpha c + beta h|div v|))
  double force_factor_ = 0.3;    // C_f in dt = C_f sqrt(h / |a|)
  double dtmax_ = 0.0;           // 0: no upper bound
  double dtmin_ = 0.0;           // 0: no lower bound (a step below it is an error)
  double tend_ = -1.0;           // < 0: no end time
  bool adaptive_ = true;
  bool stopped_at_tend_ = false;

  SPHAstro::StateIndex state_;
  class PairSPHAstro *pair_ = nullptr;
  bool evolve_u_ = true;

  // restart state
  bigint predicted_step_ = -1;    // step at which d2_vest/d_uest hold predictions
  int have_reference_ = 0;
  double reference_energy_ = 0.0;

  double last_dt_cv_ = 0.0, last_dt_force_ = 0.0;
  tagint last_limiting_atom_ = 0;

  void next_timestep();
  void set_timestep(double dt);
  double current_time() const;
};

}    // namespace LAMMPS_NS

#endif
#endif
