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

#include <cstdint>
#include <map>
#include <string>

namespace LAMMPS_NS {

class FixSPHAstro : public Fix {
 public:
  FixSPHAstro(class LAMMPS *, int, char **);
  ~FixSPHAstro() override;

  int setmask() override;
  void post_constructor() override;
  void init() override;
  void setup(int) override;
  void initial_integrate(int) override;
  void final_integrate() override;
  void post_force(int) override;
  void init_list(int, class NeighList *) override;
  void end_of_step() override;
  void post_run() override;
  double compute_scalar() override;
  double compute_vector(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

  // thermal variable: specific energy u, or entropic function A (P = A rho^gamma)
  bool entropy() const { return entropy_; }
  // entropy formulation: A must be (re)derived from u and rho at the next density pass
  bool entropy_needs_init() const { return entropy_needs_init_; }
  void entropy_initialised() { entropy_needs_init_ = false; }
  // pair sph/astro density continuity: rho still needs its one summation (the first force
  // evaluation after this fix was defined; not after read_restart)
  bool density_needs_init() const { return density_needs_init_; }
  void density_initialised() { density_needs_init_ = false; }

  // reference total energy of a compute sph/astro/global (by compute ID): set at its first
  // evaluation, kept across restarts
  double reference_energy(const std::string &compute_id, double current);

 protected:
  double courant_ = 0.3;          // C in dt = C h / (c + h|div v| + 1.2 (alpha c + beta h|div v|))
  double force_factor_ = 0.3;     // C_f in dt = C_f sqrt(h / |a|)
  double energy_factor_ = 0.3;    // C_u in dt = C_u u / |du/dt| (where du/dt < 0)
  double cond_factor_ = 0.1;      // C_k in dt = C_k rho h^2 / kappa (pair conduction KAPPA)
  // C_a in dt = C_a / sum_j k_ij, the rate of the artificial conductivity (pair conductivity)
  double condu_factor_ = 0.5;
  double dtmax_ = 0.0;    // 0: no upper bound
  double dtmin_ = 0.0;    // 0: no lower bound (a step below it is an error)
  double tend_ = -1.0;    // < 0: no end time
  bool adaptive_ = true;
  bool stopped_at_tend_ = false;

  SPHAstro::StateIndex state_;
  class PairSPHAstro *pair_ = nullptr;
  class FixSPHAstroH *hfix_ = nullptr;    // variable h: advanced in the drift
  bool evolve_u_ = true;
  bool entropy_ = false;
  bool entropy_needs_init_ = true;
  SPHAstro::EntropyIndex entropy_index_;
  // pair sph/astro density continuity: rho is integrated like u, with the prediction d_rhoest
  bool continuity_ = false;
  bool density_needs_init_ = true;
  SPHAstro::ContinuityIndex continuity_index_;
  bool pair_has_continuity() const;

  // restart state
  bigint predicted_step_ = -1;    // step at which d2_vest/d_uest hold predictions
  uint64_t state_hash_ = 0;       // hash of v and u (and rho with density continuity) when
                                  // the last run ended
  std::map<std::string, double> reference_energy_;
  bool dt_pending_ = false;    // first dt of a run: set once all setup forces are in
  double user_dt_ = 0.0;       // with dt fixed: the step to restore after a tend clip

  // XSPH (fix_sph_astro_xsph.cpp): positions drift with v + eps sum_j m_j / rho_ij (v_j - v_i)
  // W_ij; the correction is computed after each force evaluation over a full neighbour list
  double xsph_eps_ = 0.0;      // 0: off (no list, no pass)
  double **xsph_ = nullptr;    // per-atom correction (owned atoms), also the fix's per-atom output
  int xsph_nmax_ = 0;
  class NeighList *xsph_list_ = nullptr;
  void xsph_correction();
  template <class KERNEL, int DIM> void xsph_loop();

  double last_dt_cv_ = 0.0, last_dt_force_ = 0.0, last_dt_energy_ = 0.0, last_dt_cond_ = 0.0;
  tagint last_limiting_atom_ = 0;

  void next_timestep(bool from_end_of_step = false);
  void set_timestep(double dt);
  double current_time() const;
  uint64_t hash_velocity_energy() const;
  void schedule_output(bigint step);
};

}    // namespace LAMMPS_NS

#endif
#endif
