/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO: neighbour lists pruned to the kernel supports
------------------------------------------------------------------------- */

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
#include "neigh_list.h"

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

class PrunedList {
 public:
  // keep(i, j): whether entry j (special bits masked off) of atom i stays; entries keep
  // their special bits and their order
  template <class Keep> void build(const LAMMPS_NS::NeighList *src, int nmax, Keep keep)
  {
    if (static_cast<int>(numneigh_.size()) < nmax) {
      numneigh_.resize(nmax);
      offset_.resize(nmax);
      firstneigh_.resize(nmax);
    }
    inum_ = src->inum;
    ilist_ = src->ilist;
    entries_.clear();
    for (int ii = 0; ii < inum_; ii++) {
      const int i = ilist_[ii];
      const int *jlist = src->firstneigh[i];
      const int jnum = src->numneigh[i];
      offset_[i] = entries_.size();
      for (int jj = 0; jj < jnum; jj++)
        if (keep(i, jlist[jj] & NEIGHMASK)) entries_.push_back(jlist[jj]);
      numneigh_[i] = static_cast<int>(entries_.size() - offset_[i]);
    }
    for (int ii = 0; ii < inum_; ii++) {
      const int i = ilist_[ii];
      firstneigh_[i] = entries_.data() + offset_[i];
    }
    built_ = true;
  }

  bool built() const { return built_; }
  void clear() { built_ = false; }
  NeighView view() const { return {inum_, ilist_, numneigh_.data(), firstneigh_.data()}; }
  std::size_t entries() const { return entries_.size(); }
  double memory_usage() const
  {
    return static_cast<double>(
        entries_.capacity() * sizeof(int) + numneigh_.capacity() * sizeof(int) +
        offset_.capacity() * sizeof(std::size_t) + firstneigh_.capacity() * sizeof(int *));
  }

 private:
  bool built_ = false;
  int inum_ = 0;
  const int *ilist_ = nullptr;
  std::vector<int> entries_;
  std::vector<int> numneigh_;
  std::vector<std::size_t> offset_;
  std::vector<int *> firstneigh_;
};

}    // namespace SPHAstro

#endif
