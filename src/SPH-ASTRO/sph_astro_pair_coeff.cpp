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
#include "comm.h"
#include "error.h"
#include "force.h"
#include "lammps.h"
#include "pair.h"
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

void SPHAstro::warn_hybrid_restart(LAMMPS *lmp, const Pair *sub, const char *style)
{
  const Force *force = lmp->force;
  if (!force->pair || force->pair == sub || !force->pair_style ||
      !utils::strmatch(force->pair_style, "^hybrid"))
    return;
  if (lmp->comm->me == 0) {
    lmp->error->warning(
        FLERR,
        "pair_style {}: sub-style {} restored from the restart file without "
        "pair_coeff (LAMMPS keeps none for hybrid styles); give its pair_coeff again "
        "before the run, e.g. pair_coeff * * {}",
        force->pair_style, style, style);
    utils::flush_buffers(lmp);
  }
}

void SPHAstro::check_hybrid_coeffs(LAMMPS *lmp, const char *caller)
{
  const Force *force = lmp->force;
  Pair *pair = force->pair;
  if (!pair || !force->pair_style || !utils::strmatch(force->pair_style, "^hybrid")) return;
  for (int i = 1; i <= lmp->atom->ntypes; i++)
    if (!pair->allocated || !pair->setflag[i][i])
      lmp->error->all(FLERR,
                      "{}: pair_style {} has no pair_coeff for type {} (read_restart restores "
                      "none for hybrid styles): give the pair_coeff commands again, e.g. "
                      "pair_coeff * * sph/astro/gravity",
                      caller, force->pair_style, i);
}
