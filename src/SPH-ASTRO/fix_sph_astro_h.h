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

#include "comm_sph_astro.h"
#include "fix.h"

namespace SPHAstro {
struct StateIndex;
struct GradhStatistics;
}    // namespace SPHAstro

namespace LAMMPS_NS {

// Variable smoothing length for pair sph/astro (the pair reads the mode and settings):
//   dhdt:    dh/dt = (h/d) div v                     (Benz 1990; Monaghan 1992)
//   iterate: h = hfact (m/rho)^(1/d) solved with rho(h) by Newton-Raphson with bisection,
//            grad-h factor Omega in force and energy (Springel & Hernquist 2002; Price 2012)
class FixSPHAstroH : public Fix, public GhostWidthSource {
 public:
  enum class Mode { DHDT, ITERATE };

  FixSPHAstroH(class LAMMPS *, int, char **);
  ~FixSPHAstroH() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void end_of_step() override;
  void pre_exchange() override;
  void post_run() override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  // h <- h exp(dt div v / d) for the group, capped; called by fix sph/astro in its drift once
  // the step's dt is final
  void advance_h(double dt);
  // dhdt: count the particles of the group held at the h cap by the latest drift
  void count_capped();
  // the latest h iteration (iterate) or drift (dhdt: particles and capped only), this rank
  const SPHAstro::GradhStatistics &h_statistics() const;
  double compute_vector(int) override;

  Mode mode() const { return mode_; }
  double hfact() const { return hfact_; }
  double tolerance() const { return tolerance_; }
  int max_iterations() const { return max_iterations_; }
  double margin() const { return margin_; }
  // settings pair sph/astro reads at its init: "iterate" (int), "hfact", "tolerance",
  // "maxiter" (int), "margin"
  void *extract(const char *, int &) override;
  // ghosts narrow: what the ghost shell at each sub-domain face must hold (CommSPHAstro)
  bool ghost_reaches(double *reach, double &floor) override;

 protected:
  Mode mode_;
  double hfact_;
  double tolerance_;
  int max_iterations_;
  double margin_;    // a run's ghost cutoff serves h up to margin x the largest h
  double h_max_;     // no h beyond it (keyword hmax; infinite by default)
  static constexpr double WIDEN = 1.2;    // a widened cap serves >= WIDEN x the largest h
  double user_cutghost_;                  // comm_modify cutoff when the run began
  double pending_cutoff_;                 // ghost cutoff for the next reneighbouring step (0: none)
  bigint ghost_widenings_;                // ghost cutoffs widened since the fix was defined
  // what a run that continues this one keeps (restart file, or the next run): the pair's h cap
  // at the start and now, the ghost cutoff this fix set (0: the user's), the pending one
  double carried_[4];
  bool in_run_ = false;    // between setup and post_run (carry() reads the run's state)
  bool raised_ = false;    // init raised comm_modify cutoff to the carried one (no run since)
  // ghosts narrow (default) or full: the shell at each sub-domain face as wide as the reach of
  // the particles near it (set at every reneighbouring from the run's first one on)
  bool narrow_ghosts_ = true;
  bool narrow_ready_ = false;    // from a run's setup to the next init: h may set the shells
  class CommSPHAstro *ghost_comm_ = nullptr;
  bigint ghost_remakes_ = 0;    // reneighbourings asked for by the shells
  bool shells_overrun();
  void carry();
  void check_limits();
  SPHAstro::GradhStatistics *drift_stats_;    // dhdt: the latest drift's capped particles

  SPHAstro::StateIndex *state_;
  class PairSPHAstro *pair_;
  int iterate_flag_;    // extract("iterate")
};

}    // namespace LAMMPS_NS

#endif
#endif
