/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: self-gravity on a tree (open boundaries)
------------------------------------------------------------------------- */

#ifdef KSPACE_CLASS
// clang-format off
KSpaceStyle(tree/sph/astro/gravity,TreeSPHAstroGravity);
// clang-format on
#else

#ifndef LMP_TREE_SPH_ASTRO_GRAVITY_H
#define LMP_TREE_SPH_ASTRO_GRAVITY_H

#include "atom.h"
#include "kspace.h"
#include "sph_astro_active_set.h"
#include "sph_astro_gravity_interactions.h"
#include "sph_astro_gravity_tree.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class TreeSPHAstroGravity :
    public KSpace,
    public SPHAstro::ActiveSetClient,
    public SPHAstro::LongRangeClient {
 public:
  TreeSPHAstroGravity(class LAMMPS *);
  ~TreeSPHAstroGravity() override;

  void settings(int, char **) override;
  void init() override;
  void setup() override;
  void compute(int, int) override;
  double memory_usage() override;

  void set_active_set(const SPHAstro::ActiveSet &set) override { active_ = set; }
  std::string run_summary() override;
  // periodic boxes: PPPM's long range may follow fix sph/astro longrange sync
  void set_long_range_schedule(SPHAstro::LongRangeSchedule *schedule) override;
  bool periodic() const { return periodic_; }

  // figures of the latest evaluation (tests and benchmarks): targets, their mean multipole and
  // particle interactions, items imported from other ranks, tree depth
  struct Statistics {
    double targets = 0.0, multipoles = 0.0, particles = 0.0, imported = 0.0;
    int depth = 0;
  };
  const Statistics &last_evaluation() const { return last_; }
  // this rank's mean targets per evaluation since the run began
  double targets_per_evaluation() const
  {
    return evaluations_ > 0.0 ? target_sum_ / evaluations_ : 0.0;
  }

 protected:
  SPHAstro::OpeningCriterion crit_;
  int leaf_size_ = SPHAstro::GravityTree::DEFAULT_LEAF_SIZE;
  int group_size_ = 64;
  class PairSPHAstroGravity *pair_ = nullptr;
  SPHAstro::ActiveSet active_;
  // periodic boxes (TreePM): PPPM for the long range, the tree over owned and ghost atoms for
  // the short range within the pair style's cutoff
  bool periodic_ = false;
  class PPPMSPHAstroGravity *pm_ = nullptr;
  std::string pm_accuracy_ = "1e-4";

  SPHAstro::GravityTree local_;       // the rank's particles (built at re-neighbouring)
  SPHAstro::GravityTree imported_;    // what other ranks send (built at every evaluation)
  SPHAstro::GravityItems import_items_;
  SPHAstro::GravityInteractions lists_;
  std::vector<int> groups_, accepted_, leaves_, box_nodes_;
  std::vector<tagint> built_tags_;    // tag of each local atom at the build
  bool built_ = false;
  std::vector<char> target_;    // per tree position: evaluated in this call
  int accel_index_ = -1;        // relative criterion: |a| of the last evaluation (custom property)

  // figures: of the latest evaluation, and sums over the run
  Statistics last_;
  double builds_ = 0.0, evaluations_ = 0.0, target_sum_ = 0.0, multipole_sum_ = 0.0,
         particle_sum_ = 0.0, imported_sum_ = 0.0;
  // seconds spent in the builds, the moments, the exchange and the walks with their sums
  double time_build_ = 0.0, time_moments_ = 0.0, time_exchange_ = 0.0, time_walks_ = 0.0;

  double parse_theta(const char *text);
  // the tree's atoms: the owned ones, and in a periodic box their ghosts too
  int sources() const { return atom->nlocal + (periodic_ ? atom->nghost : 0); }
  void build_local();
  // the locally essential items of the other ranks (Salmon & Warren 1994)
  void exchange();
  template <bool CUBIC, bool ZETA> void evaluate();
};

}    // namespace LAMMPS_NS

#endif
#endif
