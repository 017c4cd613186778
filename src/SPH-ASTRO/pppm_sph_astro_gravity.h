/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: long-range self-gravity from LAMMPS' PPPM
------------------------------------------------------------------------- */

#ifdef KSPACE_CLASS
// clang-format off
KSpaceStyle(pppm/sph/astro/gravity,PPPMSPHAstroGravity);
// clang-format on
#else

#ifndef LMP_PPPM_SPH_ASTRO_GRAVITY_H
#define LMP_PPPM_SPH_ASTRO_GRAVITY_H

#include "pppm.h"
#include "sph_astro_active_set.h"

namespace LAMMPS_NS {

class PPPMSPHAstroGravity : public PPPM, public SPHAstro::LongRangeClient {
 public:
  PPPMSPHAstroGravity(class LAMMPS *);
  void settings(int, char **) override;
  void init() override;
  void compute(int, int) override;
  // the grid (as kspace_modify mesh), for the long range of kspace tree/sph/astro/gravity
  void set_grid(int nx, int ny, int nz)
  {
    gridflag = 1;
    nx_pppm = nx;
    ny_pppm = ny;
    nz_pppm = nz;
  }
  // fix sph/astro longrange sync: compute where every particle ends its step (null: always)
  void set_long_range_schedule(SPHAstro::LongRangeSchedule *schedule) override
  {
    schedule_ = schedule;
  }

 protected:
  double G_;
  SPHAstro::LongRangeSchedule *schedule_ = nullptr;
};

}    // namespace LAMMPS_NS

#endif
#endif
