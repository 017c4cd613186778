/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: astrophysical smoothed particle hydrodynamics for LAMMPS
------------------------------------------------------------------------- */

#ifdef COMMAND_CLASS
// clang-format off
CommandStyle(sph/astro/run,SPHAstroRunCommand);
// clang-format on
#else

#ifndef LMP_SPH_ASTRO_RUN_COMMAND_H
#define LMP_SPH_ASTRO_RUN_COMMAND_H

#include "command.h"

namespace LAMMPS_NS {

// sph/astro/run N [upto]: LAMMPS' run, repeated while fix sph/astro/h ... rebuild ends a run
// early so that the neighbour-list cutoffs follow the smoothing lengths (each run sets the
// cutoffs anew), until step N (upto) or N steps later, or until fix sph/astro's tend.
class SPHAstroRunCommand : public Command {
 public:
  SPHAstroRunCommand(class LAMMPS *lmp) : Command(lmp) {}
  void command(int, char **) override;
};

}    // namespace LAMMPS_NS

#endif
#endif
