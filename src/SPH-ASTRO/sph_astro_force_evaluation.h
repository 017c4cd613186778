/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// One force evaluation of pair sph/astro: the stages in their order (doc/architecture.md),
// each a pass of sph_astro_passes.h with the communication it needs before and after:
//   density    summation (+ reverse), the h-rho iteration, or none (density continuity)
//   EOS        P, c_s (and A from u when scheduled)
//   gradients  velocity sums (+ reverse): div v, |curl v|, Balsara factors, grad v
//   state      forward: what the force pass reads of the ghosts
//   force      force pass (+ reverse): accelerations, du/dt (dA/dt), div v, drho/dt
//   conduction physical heat conduction (+ reverse), when kappa > 0
// The communication goes through an Exchange, which pair sph/astro implements with LAMMPS'
// forward and reverse communication of its own arrays.

#ifndef LMP_SPH_ASTRO_FORCE_EVALUATION_H
#define LMP_SPH_ASTRO_FORCE_EVALUATION_H

#include "sph_astro_comm_table.h"
#include "sph_astro_passes.h"
#include "sph_astro_scheme.h"

#include <initializer_list>
#include <vector>

namespace SPHAstro {

class NeighbourLists;

class Exchange {
 public:
  // owned -> ghost copies of these arrays; the ghosts' parts summed into their owners
  virtual void forward(std::initializer_list<CommField> fields) = 0;
  virtual void reverse(std::initializer_list<CommField> fields) = 0;
  // the same for the atoms marked in chosen only (sph_astro_comm_table.h)
  virtual void forward_chosen(std::initializer_list<CommField> fields, const char *chosen) = 0;
  virtual void reverse_chosen(std::initializer_list<CommField> fields, const char *chosen) = 0;
  // marks (per owned and ghost atom) of the ghosts to their owners, and to the ghosts that a
  // later swap passes on: then a chosen stage reaches every marked ghost
  virtual void gather_marks(char *marks) = 0;

 protected:
  ~Exchange() = default;
};

// Individual timesteps (fix sph/astro steps individual): only the pairs with an active atom
// are evaluated (sph_astro_due_pairs.h) and only active atoms get a new density, h, Omega,
// Balsara factor and div v; an inactive atom keeps what its last evaluation left (its rho and
// h drifted by fix sph/astro), which the force pass reads through the ghosts
struct ActiveSet {
  const char *active = nullptr;    // per owned and ghost atom; null: global stepping
  // the last evaluation's values of owned atoms (d_step_omega, d_step_balsara, d_step_divv,
  // d_step_nneigh; d_step_dphidh: h_i^2 times the sum of zeta_i)
  double *omega = nullptr, *balsara = nullptr, *divv = nullptr, *nneigh = nullptr,
         *dphidh = nullptr;
};

// per-atom state arrays the stages read or write besides those of the PassContext
struct EvaluationArrays {
  double *h;                  // d_h (the ghosts' copy is sent where h changed)
  double *rhoest, *drhodt;    // density continuity, else null
  EntropyArrays entropy;      // thermal entropy (A null without it)
  ActiveSet steps;            // individual timesteps
};

// what an evaluation leaves for the pair to report
struct EvaluationResult {
  bool counted = false;    // the density pass counted the neighbours
  LAMMPS_NS::bigint h_failures = 0;
};

class ForceEvaluation {
 public:
  ForceEvaluation(PassContext &ctx, const PairOptions &options, const Scheme &scheme,
                  const EvaluationArrays &arrays, Exchange &exchange) :
      ctx_(ctx),
      o_(options), scheme_(scheme), a_(arrays), exchange_(exchange)
  {
  }
  // gradh: the h-rho iteration's settings (lists, caps); h_cap: the largest h the ghosts allow;
  // initialise_density: one summation for density continuity; initialise_entropy: A from u
  EvaluationResult run(NeighbourLists &lists, const GradhSettings &gradh, GradhStatistics &hstats,
                       double h_cap, bool initialise_density, bool initialise_entropy);

 private:
  PassContext &ctx_;
  const PairOptions &o_;
  const Scheme &scheme_;
  const EvaluationArrays &a_;
  Exchange &exchange_;
  double h_cap_ = 0.0;
  std::vector<int> active_owned_;
  std::vector<double> rho_kept_;
  bool vest_sent_ = false;    // the ghosts have this evaluation's v_est
  // individual steps: the ghosts in this evaluation's pairs, and their owners (the marks of
  // ctx_.ghosts_in_pairs)
  std::vector<char> in_pairs_;

  bool individual() const { return a_.steps.active != nullptr; }
  // individual steps: the half list's pairs with an active atom
  NeighView evaluated_pairs(NeighbourLists &lists);
  // ctx_.half = evaluated_pairs(); with individual steps the ghosts in them are marked
  void select_pairs(NeighbourLists &lists);
  // individual steps: inactive owned atoms take back their kept values of field (restore), or
  // active ones keep this evaluation's (keep)
  void restore(double *field, const double *kept);
  void keep(const double *field, double *kept);
  // adaptive softening: the active atoms' sums of zeta kept, the others' from what was kept
  void keep_softening_sums(double *sums);

  void density(const GradhSettings &gradh, GradhStatistics &hstats, bool initialise,
               EvaluationResult &result);
  void equation_of_state(bool initialise_entropy);
  void gradients();
  void forward_vest();
  void forward_state();
  void force();
  void conduction();
};

}    // namespace SPHAstro

#endif
