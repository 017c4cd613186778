/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The stability sentinel of fix sph/astro (keywords sentinel, collapse, hshare): after every
// step it reports, once per run and with an atom ID, a timestep fallen below collapse x the
// run's first one, more than hshare of the particles of the latest h iteration not converged
// or held at the h cap, and more than hshare of the particles without a neighbour inside
// their kernel support, a kernel support longer than a periodic box length, and a particle
// whose speed alone sets the timestep; as a warning or, with sentinel stop, an error. It also
// stops a run at a velocity that is not finite.

#ifndef LMP_SPH_ASTRO_SENTINEL_H
#define LMP_SPH_ASTRO_SENTINEL_H

#include "pointers.h"

#include <functional>
#include <string>

namespace LAMMPS_NS {
class Fix;
class FixSPHAstroH;
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
  // the owned atoms of groupbit: the first whose velocity (or its square) is not finite stops
  // the run
  void check_velocities(int groupbit, const char *when);
  // dimension 2: the first owned atom off the plane z = 0 or moving out of it stops the run (pair
  // sph/astro takes the 2d kernel of distances that include z)
  void check_plane(const char *when);
  // after the setup forces: a particle whose speed |v| exceeds 1/collapse times the group's
  // typical signal speed |v| + c_s (geometric mean) sets the timestep alone; reported with its ID
  void check_speed_outlier(LAMMPS_NS::PairSPHAstro *pair, int igroup);
  // after a step: adaptive, the timestep is the fix's (collapse checked); cause: what limits
  // it (called only for a report); hfix: variable h (null: fixed h)
  void check(LAMMPS_NS::PairSPHAstro *pair, LAMMPS_NS::FixSPHAstroH *hfix, int groupbit,
             bool adaptive, const std::function<std::string()> &cause);
  // the latest density pass (the setup's, or a step's): more than hshare of the particles
  // failing or capped in the h iteration, or without a neighbour inside their support
  void check_particles(LAMMPS_NS::PairSPHAstro *pair, LAMMPS_NS::FixSPHAstroH *hfix, int groupbit);
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
  bool fixed_reported_ = false, images_reported_ = false;
  void report(const std::string &message);
  // a kernel support longer than a periodic box length (the particle meets its own images)
  void check_support(LAMMPS_NS::PairSPHAstro *pair, int groupbit);
  // the run's first timestep, adaptive: below collapse x the shortest time scale of a
  // particle's own (h over |v| + c_s, or sqrt(h / |a|)), a setting drives the criteria
  void check_first_step(LAMMPS_NS::PairSPHAstro *pair, int groupbit,
                        const std::function<std::string()> &cause);
};

}    // namespace SPHAstro

#endif
