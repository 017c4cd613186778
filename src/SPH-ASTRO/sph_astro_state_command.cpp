/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: the sph/astro/state command
------------------------------------------------------------------------- */

#include "sph_astro_state_command.h"

#include "error.h"
#include "sph_astro_state.h"

using namespace LAMMPS_NS;

void SPHAstroStateCommand::command(int narg, char ** /*arg*/)
{
  if (narg != 0) error->all(FLERR, "sph/astro/state takes no arguments (got {})", narg);
  SPHAstro::ensure_state(lmp, "sph/astro/state");
}
