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

namespace SPHAstro {

class NeighbourLists;

class Exchange {
 public:
  // owned -> ghost copies of these arrays; the ghosts' parts summed into their owners
  virtual void forward(std::initializer_list<CommField> fields) = 0;
  virtual void reverse(std::initializer_list<CommField> fields) = 0;

 protected:
  ~Exchange() = default;
};

// per-atom state arrays the stages read or write besides those of the PassContext
struct EvaluationArrays {
  double *h;                  // d_h (the ghosts' copy is sent where h changed)
  double *rhoest, *drhodt;    // density continuity, else null
  EntropyArrays entropy;      // thermal entropy (A null without it)
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

  void density(const GradhSettings &gradh, GradhStatistics &hstats, bool initialise,
               EvaluationResult &result);
  void equation_of_state(bool initialise_entropy);
  void gradients();
  void forward_state();
  void force();
  void conduction();
};

}    // namespace SPHAstro

#endif
