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
class Pair;
}    // namespace LAMMPS_NS

namespace SPHAstro {
void set_type_pairs(LAMMPS_NS::LAMMPS *lmp, const char *style, int narg, char **arg, int **setflag);

// LAMMPS' hybrid pair styles write their sub-styles' settings to restart files but no pair_coeff
// (PairHybrid::write_restart), and a run after read_restart stops with "All pair coeffs are not
// set". A sub-style restored inside a hybrid style (read_restart_settings) warns, naming its
// pair_coeff; style: the sub-style's name
void warn_hybrid_restart(LAMMPS_NS::LAMMPS *lmp, const LAMMPS_NS::Pair *sub, const char *style);

// a hybrid pair style without the pair_coeff of a type (after read_restart): an error naming
// caller, before LAMMPS' own check
void check_hybrid_coeffs(LAMMPS_NS::LAMMPS *lmp, const char *caller);
}    // namespace SPHAstro

#endif
