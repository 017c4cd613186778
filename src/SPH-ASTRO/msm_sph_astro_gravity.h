/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: long-range self-gravity from LAMMPS' MSM
------------------------------------------------------------------------- */

#ifdef KSPACE_CLASS
// clang-format off
KSpaceStyle(msm/sph/astro/gravity,MSMSPHAstroGravity);
// clang-format on
#else

#ifndef LMP_MSM_SPH_ASTRO_GRAVITY_H
#define LMP_MSM_SPH_ASTRO_GRAVITY_H

#include "msm.h"
#include "sph_astro_active_set.h"

#include <vector>

namespace LAMMPS_NS {

class MSMSPHAstroGravity :
    public MSM,
    public SPHAstro::LongRangeClient,
    public SPHAstro::ContinuationClient {
 public:
  MSMSPHAstroGravity(class LAMMPS *);
  void settings(int, char **) override;
  void init() override;
  void setup() override;
  void compute(int, int) override;
  int modify_param(int, char **) override;
  // fix sph/astro longrange sync: compute where every particle ends its step (null: always)
  void set_long_range_schedule(SPHAstro::LongRangeSchedule *schedule) override
  {
    schedule_ = schedule;
  }

  // the split radius and grid in use, for a run that continues this one (fix sph/astro's
  // restart record): step, cutoff, the finest grid's points (3), the spacing kept (3)
  static constexpr int CONTINUATION_VALUES = 8;
  std::vector<double> continuation_state() const override;

 protected:
  double G_;
  SPHAstro::LongRangeSchedule *schedule_ = nullptr;
  double spacing_[3] = {0.0, 0.0, 0.0};    // finest grid spacing chosen at init (0: none)
  double points_init_ = 0.0;               // points of the finest grid chosen at init
  double growth_ = 128.0;    // kspace_modify mesh/growth: bound on points / points_init_
  bigint last_step_ = -1;    // the step of the last evaluation (-1: none)

  void check_levels_at_init();
  void check_direct_stencil();
  void refine_grid_to_box();
  void set_grid_local_corners();
};

}    // namespace LAMMPS_NS

#endif
#endif
