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
CommandStyle(sph/astro/state,SPHAstroStateCommand);
// clang-format on
#else

#ifndef LMP_SPH_ASTRO_STATE_COMMAND_H
#define LMP_SPH_ASTRO_STATE_COMMAND_H

#include "command.h"

namespace LAMMPS_NS {

// sph/astro/state: define the per-particle SPH state (fix SPH_ASTRO_STATE) now, for
// instance before read_data reads it back from a data file that write_data wrote.
class SPHAstroStateCommand : public Command {
 public:
  SPHAstroStateCommand(class LAMMPS *lmp) : Command(lmp) {}
  void command(int, char **) override;
};

}    // namespace LAMMPS_NS

#endif
#endif
