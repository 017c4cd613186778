/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// What the passes of pair sph/astro read of a neighbour list (NeighView), and LAMMPS' rule for
// which of a pair's two entries a half list keeps (HalfFromFull), shared by the package's own
// lists (sph_astro_neighbour_lists.h) and the passes (sph_astro_pair_loop.h).

#ifndef LMP_SPH_ASTRO_NEIGH_VIEW_H
#define LMP_SPH_ASTRO_NEIGH_VIEW_H

#include "lmptype.h"

#include <cmath>

namespace SPHAstro {

// the fields of a neighbour list (in LAMMPS' layout) that the pair passes read
struct NeighView {
  int inum;
  const int *ilist;
  const int *numneigh;
  int *const *firstneigh;
};

// the rule by which LAMMPS derives a half list from a full one (npair_halffull.cpp), so that
// each pair is summed once on one rank and ghost pairs agree between ranks:
// newton off: j > i; newton on: owned pairs once (i < j), a ghost j only if it lies "above"
// atom i (z, then y, then x; with a 0.01 Angstrom tolerance for triclinic boxes)
struct HalfFromFull {
  int nlocal;
  bool newton, triclinic;
  double delta;    // 0.01 x force->angstrom
  // (without data-dependent branches in an orthogonal box: bitwise operations on the
  // comparisons; test NeighbourSearch.BranchFreeHalfRuleIsLAMMPSRule checks them against
  // npair_halffull.cpp's early returns)
  bool keeps(double **x, int i, int j) const { return keeps_at(x[i], x[j], i, j); }
  // the same with the positions given (the lists decide pairs they add inside a step at the
  // positions of their build, as the build did)
  bool keeps_at(const double *xi, const double *xj, int i, int j) const
  {
    if (!newton) return j > i;
    if (triclinic) {
      if (j < nlocal) return i < j;
      if (std::fabs(xj[2] - xi[2]) > delta) return xj[2] >= xi[2];
      if (std::fabs(xj[1] - xi[1]) > delta) return xj[1] >= xi[1];
      return xj[0] >= xi[0];
    }
    const bool owned = j < nlocal;
    return (owned & (i < j)) | (!owned & above(xi, xj));
  }
  // not below: z, then y, then x (npair_halffull.cpp, newton on, orthogonal box)
  static bool above(const double *xi, const double *xj)
  {
    return (xj[2] > xi[2]) |
        ((xj[2] == xi[2]) & ((xj[1] > xi[1]) | ((xj[1] == xi[1]) & (xj[0] >= xi[0]))));
  }
};

}    // namespace SPHAstro

#endif
