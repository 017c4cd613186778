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

#include "kspace.h"
#include "sph_astro_active_set.h"
#include "sph_astro_gravity_interactions.h"
#include "sph_astro_gravity_tree.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class TreeSPHAstroGravity : public KSpace, public SPHAstro::ActiveSetClient {
 public:
  TreeSPHAstroGravity(class LAMMPS *);

  void settings(int, char **) override;
  void init() override;
  void setup() override {}
  void compute(int, int) override;
  double memory_usage() override;

  void set_active_set(const SPHAstro::ActiveSet &set) override { active_ = set; }
  std::string run_summary() override;

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
  int group_size_ = 32;
  class PairSPHAstroGravity *pair_ = nullptr;
  SPHAstro::ActiveSet active_;

  SPHAstro::GravityTree local_;       // the rank's particles (built at re-neighbouring)
  SPHAstro::GravityTree imported_;    // what other ranks send (built at every evaluation)
  SPHAstro::GravityItems import_items_;
  SPHAstro::GravityInteractions lists_;
  std::vector<int> groups_, accepted_, leaves_;
  std::vector<tagint> built_tags_;    // tag of each local atom at the build
  bool built_ = false;
  std::vector<double> mass_, soft_, zo_;    // per local atom: mass, softening length, zeta/Omega
  std::vector<char> target_;                // per tree position: evaluated in this call
  int accel_index_ = -1;    // relative criterion: |a| of the last evaluation (custom property)

  // figures: of the latest evaluation, and sums over the run
  Statistics last_;
  double builds_ = 0.0, evaluations_ = 0.0, target_sum_ = 0.0, multipole_sum_ = 0.0,
         particle_sum_ = 0.0, imported_sum_ = 0.0;

  double parse_theta(const char *text);
  void build_local();
  // the locally essential items of the other ranks (Salmon & Warren 1994)
  void exchange();
  template <bool CUBIC, bool ZETA> void evaluate();
};

}    // namespace LAMMPS_NS

#endif
#endif
