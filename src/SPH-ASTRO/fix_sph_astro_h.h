/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(sph/astro/h,FixSPHAstroH);
// clang-format on
#else

#ifndef LMP_FIX_SPH_ASTRO_H_H
#define LMP_FIX_SPH_ASTRO_H_H

#include "fix.h"

namespace SPHAstro {
struct StateIndex;
}

namespace LAMMPS_NS {

// Variable smoothing length for pair sph/astro (the pair reads the mode and settings):
//   dhdt:    dh/dt = (h/d) div v                     (Benz 1990; Monaghan 1992)
//   iterate: h = hfact (m/rho)^(1/d) solved with rho(h) by Newton-Raphson with bisection,
//            grad-h factor Omega in force and energy (Springel & Hernquist 2002; Price 2012)
class FixSPHAstroH : public Fix {
 public:
  enum class Mode { DHDT, ITERATE };

  FixSPHAstroH(class LAMMPS *, int, char **);
  ~FixSPHAstroH() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void end_of_step() override;
  void post_run() override;
  // h <- h exp(dt div v / d) for the group, capped; called by fix sph/astro in its drift once
  // the step's dt is final
  void advance_h(double dt);
  double compute_vector(int) override;

  Mode mode() const { return mode_; }
  double hfact() const { return hfact_; }
  double tolerance() const { return tolerance_; }
  int max_iterations() const { return max_iterations_; }
  double margin() const { return margin_; }
  // the run ended early so that the neighbour lists are rebuilt for the current h
  // (rebuild keyword); sph/astro/run then starts the next run, which sets new caps
  bool rebuild_requested() const { return rebuild_requested_; }
  void clear_rebuild_request() { rebuild_requested_ = false; }

  // settings pair sph/astro reads at its init: "iterate" (int), "hfact", "tolerance",
  // "maxiter" (int), "margin"
  void *extract(const char *, int &) override;

 protected:
  Mode mode_;
  double hfact_;
  double tolerance_;
  int max_iterations_;
  double margin_;     // neighbour cutoffs allow h up to margin x the largest h at init
  double rebuild_;    // stop the run when h > rebuild x cap (or < cap / margin^2); 0: off
  bool rebuild_requested_;
  bigint rebuilds_;    // runs stopped for a rebuild since the fix was defined
  // h collections for neighbor multi: 0 off, -1 auto (factor ~2 apart), else their number
  int collections_;
  bigint collection_rebuilds_;    // list builds forced because h outgrew its collection
  bigint prune_rebuilds_;         // list builds forced because h neared its pruned list's limit
  int outgrown_lists() const;
  void setup_collections();

  SPHAstro::StateIndex *state_;
  class PairSPHAstro *pair_;
  int iterate_flag_;    // extract("iterate")
};

}    // namespace LAMMPS_NS

#endif
#endif
