/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The record of one pair's force that the force pass keeps with individual timesteps, so that
// fix sph/astro can kick both atoms of the pair with the same impulse (momentum conserved to
// round-off; sph_astro_individual_steps.h).

#ifndef LMP_SPH_ASTRO_PAIR_FORCE_H
#define LMP_SPH_ASTRO_PAIR_FORCE_H

namespace SPHAstro {

// the pressure and viscous force on i is F_ij = fpair (x_i - x_j) (the positions of the force
// evaluation); -F_ij acts on j. j < 0 stands for ~j, a ghost this rank does not update (newton
// off: the pair is recorded on both ranks, each for its own atom)
struct PairForce {
  int i, j;
  double fpair;
};

}    // namespace SPHAstro

#endif
