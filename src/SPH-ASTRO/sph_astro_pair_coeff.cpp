/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: pair_coeff of the package's pair styles
------------------------------------------------------------------------- */

#include "sph_astro_pair_coeff.h"

#include "atom.h"
#include "error.h"
#include "lammps.h"
#include "utils.h"

#include <algorithm>

using namespace LAMMPS_NS;

void SPHAstro::set_type_pairs(LAMMPS *lmp, const char *style, int narg, char **arg, int **setflag)
{
  if (narg != 2)
    lmp->error->all(FLERR,
                    "pair_coeff for pair_style {} takes only two type ranges (got {} "
                    "arguments): the physics is set by pair_style",
                    style, narg);
  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, lmp->atom->ntypes, ilo, ihi, lmp->error);
  utils::bounds(FLERR, arg[1], 1, lmp->atom->ntypes, jlo, jhi, lmp->error);
  int count = 0;
  for (int i = ilo; i <= ihi; i++)
    for (int j = std::max(jlo, i); j <= jhi; j++) {
      setflag[i][j] = 1;
      count++;
    }
  if (count == 0)
    lmp->error->all(FLERR, "pair_coeff {}: type ranges {} {} select no pair", style, arg[0],
                    arg[1]);
}
