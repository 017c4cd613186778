/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The stability sentinel of fix sph/astro (keywords sentinel, collapse, hshare): after every
// step it reports, once per run and with an atom ID, a timestep fallen below collapse x the
// run's first one, more than hshare of the particles of the latest h iteration not converged
// or held at the h cap, and more than hshare of the particles without a neighbour inside
// their kernel support; as a warning or, with sentinel stop, an error. It also stops a run at
// a velocity that is not finite.

#ifndef LMP_SPH_ASTRO_SENTINEL_H
#define LMP_SPH_ASTRO_SENTINEL_H

#include "pointers.h"

#include <functional>
#include <string>

namespace LAMMPS_NS {
class Fix;
class PairSPHAstro;
}    // namespace LAMMPS_NS

namespace SPHAstro {

class StabilitySentinel : protected LAMMPS_NS::Pointers {
 public:
  explicit StabilitySentinel(LAMMPS_NS::LAMMPS *lmp) : Pointers(lmp) {}
  // keywords sentinel, collapse, hshare: true if key is one of them (val checked)
  bool parse(const std::string &key, const char *val);
  // a run begins: each report once again
  void start_run();
  // the owned atoms of groupbit: the first whose velocity is not finite stops the run
  void check_velocities(int groupbit, const char *when);
  // after a step: adaptive, the timestep is the fix's (collapse checked); cause: what limits
  // it (called only for a report); iterate: the pair's h statistics belong to an h iteration
  void check(LAMMPS_NS::PairSPHAstro *pair, int groupbit, bool adaptive, bool iterate,
             const std::function<std::string()> &cause);
  // at init: minimize, another integrator or fix dt/reset on the particles of self (fix
  // sph/astro), an empty group
  void check_setting(LAMMPS_NS::Fix *self, bool adaptive);
  // dt fixed: false when off or reported already (then the criteria need not be taken)
  bool watches_fixed_step() const { return action_ != Action::OFF && !fixed_reported_; }
  // dt fixed: a step longer than the shortest criterion step (cause: what sets that one)
  void check_fixed_step(double dt, double stable, const std::function<std::string()> &cause);

 private:
  enum class Action { OFF, WARN, STOP } action_ = Action::WARN;
  double collapse_ = 1e-6, hshare_ = 0.05;
  double dt_run_start_ = 0.0;
  bool dt_reported_ = false, h_reported_ = false, isolated_reported_ = false;
  bool fixed_reported_ = false;
  void report(const std::string &message);
};

}    // namespace SPHAstro

#endif
