/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The pairs of a half list that a step of individual timesteps evaluates with newton off
// (with newton on they come from the rows made for the active atoms,
// sph_astro_neighbour_lists.h): those with at least one active atom. A row of an active atom
// is its whole row; a row of an inactive atom keeps its active partners. Rows stay in the half
// list's order and each row's entries in theirs, so every active atom adds the same terms in
// the same order as over the whole list (a step with all atoms active gives the same numbers
// as global stepping). The inactive rows are found through the half list's transposed index
// (which rows hold atom j), so a step costs the active atoms' pairs, not the whole list.

#ifndef LMP_SPH_ASTRO_DUE_PAIRS_H
#define LMP_SPH_ASTRO_DUE_PAIRS_H

#include "sph_astro_neigh_view.h"

#include <vector>

namespace SPHAstro {

class DuePairs {
 public:
  // the transposed index of a half list over nall atoms (made again for each new half list)
  void index(const NeighView &half, int nall);
  // the due pairs of a half list whose index() is current; active: one flag per owned and
  // ghost atom
  NeighView select(const NeighView &half, int nlocal, int nall, const char *active);
  double memory_usage() const;

 private:
  std::vector<int> col_start_, col_rows_;    // rows that hold atom j: col_rows_[col_start_[j]..]
  std::vector<int> ilist_, numneigh_, offset_, entries_;
  std::vector<int *> firstneigh_;
};

}    // namespace SPHAstro

#endif
