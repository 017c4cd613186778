/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(sph/astro,FixSPHAstro);
// clang-format on
#else

#ifndef LMP_FIX_SPH_ASTRO_H
#define LMP_FIX_SPH_ASTRO_H

#include "fix.h"
#include "sph_astro_active_set.h"
#include "sph_astro_restart_time.h"

#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace SPHAstro {
class ActiveSetClient;
struct StateIndex;
struct EntropyIndex;
struct ContinuityIndex;
class IndividualSteps;
class StabilitySentinel;
class SyncEnergy;
}    // namespace SPHAstro

namespace LAMMPS_NS {

class FixSPHAstro : public Fix, public SPHAstro::ContinuationStore {
 public:
  FixSPHAstro(class LAMMPS *, int, char **);
  ~FixSPHAstro() override;

  int setmask() override;
  void post_constructor() override;
  void init() override;
  void setup_pre_force(int) override;
  void setup(int) override;
  void initial_integrate(int) override;
  void post_integrate() override;
  void pre_force(int) override;
  void final_integrate() override;
  void post_force(int) override;
  void end_of_step() override;
  void post_run() override;
  double compute_scalar() override;
  double compute_vector(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  // a particle created during the simulation (create_atoms, fix deposit, ...) starts with an
  // empty SPH state (h = 0 is reported by pair sph/astro), not with values left in its slot
  void set_arrays(int) override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;

  // "entropy": 1 when the thermal variable is the entropic function A (P = A rho^gamma)
  void *extract(const char *, int &) override;

  // the step of owned atom i that ends with this step: true if i was evaluated at this step
  // (always with global steps), with its length dt (update->dt with global steps, its own with
  // steps individual); for fixes that integrate per-particle state (fix sph/astro/switch)
  bool own_step(int i, double &dt) const;
  // with steps individual: owned atom i is inside its step now (v and u are those of the middle
  // of its step; d2_vest and d_uest hold them at the current time)
  bool mid_step(int i) const;

  // steps individual: the particles' bins and steps (fix SPH_ASTRO_STEPS) are this fix's
  bool individual_steps() const { return steps_ != nullptr; }

  // the step owned atom i's own timestep criteria allow (the smallest of them, at most dtmax;
  // infinite where none applies), at its latest force evaluation
  double own_timestep(int i) const;

  // the kspace solver's choices of the run that wrote the restart file read (msm/sph/astro/gravity:
  // split radius and grid; null if none)
  const std::vector<double> *restart_continuation() const override
  {
    return kspace_state_.empty() ? nullptr : &kspace_state_;
  }

  // reference total energy of a compute sph/astro/global (by compute ID): set at its first
  // evaluation, kept across restarts
  double reference_energy(const std::string &compute_id, double current);
  // have v or u changed since the last run of this fix ended or its restart file was written
  // (1), or not (0), or does it not know (-1: defined since); from its latest init()
  int state_changed() const { return state_changed_; }

 protected:
  // C in dt = C h / v_sig with v_sig = max_j (c_i + c_j - beta w_ij) (vsig pairs, or signal
  // viscosity) or c + h|div v| + 1.2 (alpha c + beta h|div v|) (classic viscosity)
  double courant_ = 0.3;
  bool courant_pairs_ = false;    // vsig pairs
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
  bool box_check_ = false;    // shrink-wrapped box with a kspace solver (post_integrate)

  SPHAstro::StateIndex *state_;
  class PairSPHAstro *pair_ = nullptr;
  class FixSPHAstroH *hfix_ = nullptr;    // variable h: advanced in the drift
  bool evolve_u_ = true;
  bool entropy_ = false;
  int entropy_flag_ = 0;    // extract("entropy")
  // A from u (entropy), rho from one summation (density continuity) at the next force
  // evaluation: pair sph/astro is told at init, and has done it by setup
  bool entropy_needs_init_ = true;
  SPHAstro::EntropyIndex *entropy_index_;
  // pair sph/astro density continuity: rho is integrated like u, with the prediction d_rhoest
  bool continuity_ = false;
  bool density_needs_init_ = true;
  SPHAstro::ContinuityIndex *continuity_index_;
  bool pair_has_continuity() const;

  // restart state
  bigint predicted_step_ = -1;    // step at which d2_vest/d_uest hold predictions
  uint64_t state_hash_ = 0;       // hash of v and u (and rho with density continuity) when
                                  // the last run ended
  bool hash_taken_ = false;       // (by a run of this fix, or from a restart file)
  // steps individual: this rank's part of the hash at the last run's end (for the hand-over of
  // the particles inside their steps when this fix goes)
  uint64_t steps_local_hash_ = 0;
  bool steps_local_hash_taken_ = false;
  int state_changed_ = -1;    // state_changed()
  std::map<std::string, double> reference_energy_;
  // the simulation time at the last run's end or of the restart file read (put back at init:
  // sph_astro_restart_time.h)
  SPHAstro::RestartTime restart_time_;
  std::vector<double> kspace_state_;
  bool dt_pending_ = false;    // first dt of a run: set once all setup forces are in
  double user_dt_ = 0.0;       // with dt fixed: the step to restore after a tend clip

  // XSPH: positions drift with v + eps sum_j m_j / rho_ij (v_j - v_i) W_ij; the correction is
  // computed after each force evaluation over a full neighbour list
  double xsph_eps_ = 0.0;      // 0: off (no list, no pass)
  double **xsph_ = nullptr;    // per-atom correction (owned atoms), also the fix's per-atom output
  int xsph_nmax_ = 0;
  void xsph_correction();

  double last_dt_cv_ = 0.0, last_dt_force_ = 0.0, last_dt_energy_ = 0.0, last_dt_cond_ = 0.0;
  tagint last_limiting_atom_ = 0;
  std::string limits() const;    // the limiting atom and its criteria, for messages

  // individual timesteps (steps individual; sph_astro_individual_steps.h), null: global
  SPHAstro::IndividualSteps *steps_ = nullptr;
  // the force styles that evaluate the active particles only (gravity; found at init)
  std::vector<SPHAstro::ActiveSetClient *> active_clients_;
  // fixes that bound the global step by their own criteria (fix sph/astro/sink; found at init)
  std::vector<SPHAstro::TimestepLimiter *> limiters_;
  double last_dt_limiter_ = INFINITY;
  void tell_active_set();
  SPHAstro::SyncEnergy *sync_energy_ = nullptr;    // individual steps: E at synchronisation
  bool pair_kicks_ = true;    // individual steps: pair forces and du/dt integrated pair by pair
  // individual steps: the kspace gravity only where all particles end their step (longrange
  // sync), with at most long_displacement_ x its split scale of displacement in between
  bool long_range_sync_ = false;
  double long_displacement_ = 0.02;
  // the limiter: no step more than 2^levels x a neighbour's (0: off; -1: not given, then 2 with
  // pair kicks and 1 with particle kicks)
  int limiter_levels_ = -1;
  std::vector<double> wanted_;
  // the timestep criteria of atom i: Courant, force, energy, conduction (infinite where one
  // does not limit it)
  void criteria(int i, double dts[4]) const;
  // each active particle's (all: every particle's) step from its criteria and dtmax
  void wanted_steps(bool all);
  void next_individual_timestep();

  SPHAstro::StabilitySentinel *sentinel_;    // sph_astro_sentinel.h

  void next_timestep(bool from_end_of_step = false);
  void set_timestep(double dt);
  double current_time() const;
  // the simulation time after a step of dt must be finite (an error naming dtmax otherwise)
  void check_time_after(double dt) const;
  void schedule_output(bigint step);
};

}    // namespace LAMMPS_NS

#endif
#endif
