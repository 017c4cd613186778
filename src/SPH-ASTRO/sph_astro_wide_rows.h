/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Rows wider than the neighbour lists: what an h iteration asks of the neighbour search when a
// particle's h goes past the largest h its row serves. The search (sph_astro_neighbour_lists.h)
// provides them, the density pass (sph_astro_passes.h) uses them; neither knows the other.

#ifndef LMP_SPH_ASTRO_WIDE_ROWS_H
#define LMP_SPH_ASTRO_WIDE_ROWS_H

namespace SPHAstro {

// the rows of an h iteration that went past its list's limit: every j with r_ij < R h_row,
// h_row = min(WIDE_ROW x h, h_cap) (returned)
struct WideRows {
  static constexpr double WIDE_ROW = 1.5;
  virtual const int *row(int i, double h, double &h_row, int &n) = 0;
  virtual ~WideRows() = default;
};

}    // namespace SPHAstro

#endif
