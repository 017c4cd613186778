/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

#include "sph_astro_due_pairs.h"

namespace SPHAstro {

void DuePairs::index(const NeighView &half, int nall)
{
  col_start_.assign(nall + 1, 0);
  for (int ii = 0; ii < half.inum; ii++) {
    const int i = half.ilist[ii];
    const int *row = half.firstneigh[i];
    for (int k = 0; k < half.numneigh[i]; k++) col_start_[(row[k] & NEIGHMASK) + 1]++;
  }
  for (int j = 0; j < nall; j++) col_start_[j + 1] += col_start_[j];
  col_rows_.resize(col_start_[nall]);
  std::vector<int> fill(col_start_.begin(), col_start_.end() - 1);
  for (int ii = 0; ii < half.inum; ii++) {
    const int i = half.ilist[ii];
    const int *row = half.firstneigh[i];
    for (int k = 0; k < half.numneigh[i]; k++) col_rows_[fill[row[k] & NEIGHMASK]++] = i;
  }
}

NeighView DuePairs::select(const NeighView &half, int nlocal, int nall, const char *active)
{
  if (static_cast<int>(numneigh_.size()) < nlocal) {
    numneigh_.resize(nlocal);
    firstneigh_.resize(nlocal);
    offset_.resize(nlocal);
  }
  // the inactive rows' active partners: count, then fill in increasing j (the rows' order)
  for (int ii = 0; ii < half.inum; ii++) numneigh_[half.ilist[ii]] = 0;
  for (int j = 0; j < nall; j++) {
    if (!active[j]) continue;
    for (int c = col_start_[j]; c < col_start_[j + 1]; c++) {
      const int i = col_rows_[c];
      if (!active[i]) numneigh_[i]++;
    }
  }
  int total = 0;
  for (int ii = 0; ii < half.inum; ii++) {
    const int i = half.ilist[ii];
    offset_[i] = total;
    if (!active[i]) total += numneigh_[i];
  }
  entries_.resize(total > 0 ? total : 1);
  for (int j = 0; j < nall; j++) {
    if (!active[j]) continue;
    for (int c = col_start_[j]; c < col_start_[j + 1]; c++) {
      const int i = col_rows_[c];
      if (!active[i]) entries_[offset_[i]++] = j;
    }
  }
  ilist_.clear();
  for (int ii = 0; ii < half.inum; ii++) {
    const int i = half.ilist[ii];
    if (active[i]) {
      numneigh_[i] = half.numneigh[i];
      firstneigh_[i] = half.firstneigh[i];
      ilist_.push_back(i);
    } else if (numneigh_[i] > 0) {
      firstneigh_[i] = entries_.data() + offset_[i] - numneigh_[i];
      ilist_.push_back(i);
    }
  }
  return {static_cast<int>(ilist_.size()), ilist_.data(), numneigh_.data(), firstneigh_.data()};
}

double DuePairs::memory_usage() const
{
  return static_cast<double>(col_start_.capacity() + col_rows_.capacity() + ilist_.capacity() +
                             numneigh_.capacity() + offset_.capacity() + entries_.capacity()) *
      sizeof(int) +
      static_cast<double>(firstneigh_.capacity()) * sizeof(int *);
}

}    // namespace SPHAstro
