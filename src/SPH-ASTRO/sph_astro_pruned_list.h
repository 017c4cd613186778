/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Neighbour lists pruned to the kernel supports

// LAMMPS' lists of pair sph/astro reach kernel_radius x the h cap of a type (margin x its
// largest h) plus the skin, for every particle of the type: with margin 1.5 they hold about
// five times the kernel neighbours (3D Sod, M6 at hfact 1.0: 553 entries for 113 neighbours),
// and every density and force pass scans them all. A pruned list keeps, when LAMMPS has just
// built its list, the entries j of atom i with
//     r_ij < R max(hl_i, hl_j) + skin    (half list: W(h_ij), W(h_i) and W(h_j))
//     r_ij < R hl_i + skin               (full list of the h iteration: W(h_i) only)
// with hl = growth x h, the largest h the pruned list allows (R the kernel radius). Until
// LAMMPS builds again no atom moves more than skin/2 from where it was, so no pair comes
// closer by more than the skin: while every h <= hl, every pair inside a kernel support is
// in the pruned list, in the order of LAMMPS' list, and each sum over it is the sum over
// LAMMPS' list bit for bit. pair sph/astro falls back to LAMMPS' list where an h has
// outgrown hl, and fix sph/astro/h has the lists rebuilt before that is needed.

#ifndef LMP_SPH_ASTRO_PRUNED_LIST_H
#define LMP_SPH_ASTRO_PRUNED_LIST_H

#include "lmptype.h"
#include "my_page.h"
#include "neigh_list.h"

#include <cmath>
#include <cstddef>
#include <vector>

namespace SPHAstro {

// the fields of a LAMMPS neighbour list that the pair passes read
struct NeighView {
  int inum;
  const int *ilist;
  const int *numneigh;
  int *const *firstneigh;
};

inline NeighView view_of(const LAMMPS_NS::NeighList *list)
{
  return {list->inum, list->ilist, list->numneigh, list->firstneigh};
}

// the rule by which LAMMPS derives a half list from a full one (npair_halffull.cpp), so that
// a half list made here from LAMMPS' full list holds LAMMPS' half list's pairs in its order:
// newton off: j > i; newton on: owned pairs once (i < j), a ghost j only if it lies "above"
// atom i (z, then y, then x; with a 0.01 Angstrom tolerance for triclinic boxes)
struct HalfFromFull {
  int nlocal;
  bool newton, triclinic;
  double delta;    // 0.01 x force->angstrom
  // (without data-dependent branches in an orthogonal box: the prune scan's hot loop takes
  // bitwise operations on the comparisons; test PrunedLists.BranchFreeHalfRuleIsLAMMPSRule
  // checks them against npair_halffull.cpp's early returns)
  bool keeps(double **x, int i, int j) const
  {
    if (!newton) return j > i;
    if (triclinic) {
      if (j < nlocal) return i < j;
      const double *xi = x[i], *xj = x[j];
      if (std::fabs(xj[2] - xi[2]) > delta) return xj[2] >= xi[2];
      if (std::fabs(xj[1] - xi[1]) > delta) return xj[1] >= xi[1];
      return xj[0] >= xi[0];
    }
    const bool owned = j < nlocal;
    return (owned & (i < j)) | (!owned & above(x[i], x[j]));
  }
  // not below: z, then y, then x (npair_halffull.cpp, newton on, orthogonal box)
  static bool above(const double *xi, const double *xj)
  {
    return (xj[2] > xi[2]) |
        ((xj[2] == xi[2]) & ((xj[1] > xi[1]) | ((xj[1] == xi[1]) & (xj[0] >= xi[0]))));
  }
};

// rows in LAMMPS' page allocator (my_page.h), as LAMMPS' own lists: memory grows with the
// entries kept, and a row never moves once written
class PrunedList {
 public:
  // start a list for the atoms ilist[0..inum) (nmax: atom arrays) whose rows hold at most
  // maxrow entries (LAMMPS' neigh_modify one), in pages of pagesize entries (page); false if
  // the pages cannot be set up
  bool begin(int inum, const int *ilist, int nmax, int maxrow, int pagesize)
  {
    if (static_cast<int>(numneigh_.size()) < nmax) {
      numneigh_.resize(nmax);
      firstneigh_.resize(nmax);
    }
    if (maxrow != maxrow_ || pagesize != pagesize_) {
      if (pages_.init(maxrow, pagesize) != 0) return false;
      maxrow_ = maxrow;
      pagesize_ = pagesize;
    } else
      pages_.reset();
    inum_ = inum;
    ilist_ = ilist;
    built_ = true;
    return true;
  }
  // the next row, for atom i, with room for maxrow entries (nullptr if memory ran out): write
  // its entries there, then close it with its count
  int *row(int i)
  {
    firstneigh_[i] = pages_.vget();
    return firstneigh_[i];
  }
  void close(int i, int n)
  {
    numneigh_[i] = n;
    pages_.vgot(n);
  }

  bool built() const { return built_; }
  void clear() { built_ = false; }
  NeighView view() const { return {inum_, ilist_, numneigh_.data(), firstneigh_.data()}; }
  std::size_t entries() const { return static_cast<std::size_t>(pages_.ndatum); }
  double memory_usage() const
  {
    return pages_.size() +
        static_cast<double>(numneigh_.capacity() * sizeof(int) +
                            firstneigh_.capacity() * sizeof(int *));
  }

 private:
  bool built_ = false;
  int inum_ = 0;
  const int *ilist_ = nullptr;
  int maxrow_ = 0, pagesize_ = 0;
  LAMMPS_NS::MyPage<int> pages_;
  std::vector<int> numneigh_;
  std::vector<int *> firstneigh_;
};

// the entries of a LAMMPS list, summed over its atoms
inline std::size_t list_entries(const LAMMPS_NS::NeighList *list)
{
  std::size_t n = 0;
  for (int ii = 0; ii < list->inum; ii++) n += list->numneigh[list->ilist[ii]];
  return n;
}

}    // namespace SPHAstro

#endif
