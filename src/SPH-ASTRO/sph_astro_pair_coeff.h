/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: astrophysical smoothed particle hydrodynamics for LAMMPS
------------------------------------------------------------------------- */

// pair_coeff I J of the package's pair styles: no coefficients, the physics is set by
// pair_style; marks every type pair (i <= j) of the two ranges as set.

#ifndef LMP_SPH_ASTRO_PAIR_COEFF_H
#define LMP_SPH_ASTRO_PAIR_COEFF_H

namespace LAMMPS_NS {
class LAMMPS;
}

namespace SPHAstro {
void set_type_pairs(LAMMPS_NS::LAMMPS *lmp, const char *style, int narg, char **arg, int **setflag);
}

#endif
