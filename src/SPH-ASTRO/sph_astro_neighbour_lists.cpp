/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

#include "sph_astro_neighbour_lists.h"

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "neighbor.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

namespace SPHAstro {

void RowStore::reset()
{
  current_ = 0;
  used_ = 0;
  entries_ = 0;
}

int *RowStore::append(const int *row, int n)
{
  const std::size_t need = static_cast<std::size_t>(n);
  while (current_ < chunks_.size() && used_ + need > sizes_[current_]) {
    current_++;
    used_ = 0;
  }
  if (current_ == chunks_.size()) {
    const std::size_t size = std::max(CHUNK, need);
    chunks_.emplace_back(new int[size]);
    sizes_.push_back(size);
    used_ = 0;
  }
  int *out = chunks_[current_].get() + used_;
  if (n) std::memcpy(out, row, need * sizeof(int));
  used_ += need;
  entries_ += need;
  return out;
}

double RowStore::memory_usage() const
{
  double bytes = 0.0;
  for (std::size_t size : sizes_) bytes += static_cast<double>(size * sizeof(int));
  return bytes;
}

/* ----------------------------------------------------------------------
   after LAMMPS' build (reneighbouring) the atoms sit where LAMMPS saw them: a pair that comes
   inside a kernel support before the next build is now closer than that support + skin
------------------------------------------------------------------------- */

void NeighbourLists::update(const double *h, const SearchSettings &s)
{
  settings_ = s;
  // LAMMPS built in this step (ago 0) and not yet for these lists: a new step, or a new run
  // (its setup builds at the step the previous run ended on)
  if (built_ && !(neighbor->ago == 0 && (stale_ || lmp->update->ntimestep != build_step_))) return;
  stale_ = false;
  build_step_ = lmp->update->ntimestep;
  build(h, neighbor->skin);
  motion_ = 0.5 * neighbor->skin;
  stats_.builds++;
}

NeighView NeighbourLists::half(const double *h)
{
  const int nall = atom->nlocal + atom->nghost;
  const double *hl = hl_.data();
  bool outgrown = false;
  for (int i = 0; i < nall; i++) outgrown |= h[i] > hl[i];
  if (outgrown) {
    // atoms are up to skin/2 from LAMMPS' last build and go up to skin/2 from it before the
    // next one: up to skin from here, pairs up to 2 skin closer
    build(h, 2.0 * neighbor->skin);
    motion_ = neighbor->skin;
    stats_.step_builds++;
  }
  return half_.view(inum_, ilist_.data());
}

void NeighbourLists::build(const double *h, double pad)
{
  double **x = atom->x;
  const int *type = atom->type;
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const SearchSettings &s = settings_;
  const double R = s.kernel_radius;
  // (rows for the owned atoms only; h limits and radii for the ghosts too)
  if (static_cast<int>(hl_.size()) < atom->nmax) {
    hl_.resize(atom->nmax);
    radius_.resize(atom->nmax);
  }
  if (static_cast<int>(half_.numneigh.size()) < nlocal) {
    half_.numneigh.resize(nlocal);
    half_.firstneigh.resize(nlocal);
  }
  if (s.full && static_cast<int>(full_.numneigh.size()) < nlocal) {
    full_.numneigh.resize(nlocal);
    full_.firstneigh.resize(nlocal);
  }
  members_.clear();
  ilist_.clear();
  for (int i = 0; i < nall; i++) {
    hl_[i] = std::min(s.growth * h[i], s.h_cap);
    radius_[i] = R * hl_[i];
    if (!s.sph_type[type[i]]) continue;
    members_.push_back(i);
    if (i < nlocal) ilist_.push_back(i);
  }
  inum_ = static_cast<int>(ilist_.size());
  tree_.build(x, radius_.data(), members_.data(), static_cast<int>(members_.size()));

  const HalfFromFull half_rule{nlocal, s.newton, domain->triclinic != 0, 0.01 * force->angstrom};
  half_.rows.reset();
  full_.rows.reset();
  due_indexed_ = false;
  // leaf by leaf: one traversal per leaf collects its candidates (sph_astro_neighbour_tree.h)
  const int leaves = tree_.leaves();
  for (int l = 0; l < leaves; l++) {
    bool owned = false;
    for (int k = tree_.leaf_begin(l); k < tree_.leaf_end(l); k++) owned |= tree_.point(k) < nlocal;
    if (!owned) continue;
    tree_.query_leaf(l, pad, [&](int k, const int *found, int n) {
      const int i = tree_.point(k);
      if (i >= nlocal) return;
      scratch_.resize(n);
      int m = 0;
      for (int c = 0; c < n; c++) {
        const int j = tree_.point(found[c]);
        scratch_[m] = j;
        m += j != i;
      }
      // (rows in atom order: every sum over a row then runs in an order that does not depend
      // on the tree, so a run continued from a restart, or with lists made at other steps,
      // adds the same terms in the same order)
      if (s.full) {    // the gather rows: r < R hl_i + pad
        const double reach = radius_[i] + pad;
        const double reach2 = reach * reach;
        const double xi = x[i][0], yi = x[i][1], zi = x[i][2];
        full_scratch_.resize(m);
        int nfull = 0;
        for (int c = 0; c < m; c++) {
          const int j = scratch_[c];
          const double dx = xi - x[j][0], dy = yi - x[j][1], dz = zi - x[j][2];
          full_scratch_[nfull] = j;
          nfull += dx * dx + dy * dy + dz * dz < reach2;
        }
        full_.firstneigh[i] = full_.rows.append(full_scratch_.data(), nfull);
        full_.numneigh[i] = nfull;
      }
      int nhalf = 0;
      for (int c = 0; c < m; c++) {
        const int j = scratch_[c];
        scratch_[nhalf] = j;
        nhalf += half_rule.keeps(x, i, j);
      }
      half_.firstneigh[i] = half_.rows.append(scratch_.data(), nhalf);
      half_.numneigh[i] = nhalf;
    });
  }
  built_ = true;
  const double atoms = std::max(inum_, 1);
  stats_.atoms = inum_;
  stats_.half_entries = half_.rows.entries() / atoms;
  stats_.full_entries = s.full ? full_.rows.entries() / atoms : 0.0;
}

NeighView NeighbourLists::due(const NeighView &half, const char *active)
{
  const int nall = atom->nlocal + atom->nghost;
  if (!due_indexed_) {
    due_.index(half, nall);
    due_indexed_ = true;
  }
  due_view_ = due_.select(half, atom->nlocal, nall, active);
  return due_view_;
}

// a gather row searched at the current positions (the tree knows how far atoms may have moved)
const int *NeighbourLists::row(int i, double h, double &h_row, int &n)
{
  double **x = atom->x;
  h_row = std::min(WideRows::WIDE_ROW * h, settings_.h_cap);
  // (an h at the cap: the row serves any h the iteration may try, which it caps)
  if (h_row >= settings_.h_cap) h_row = INFINITY;
  const double reach = settings_.kernel_radius * std::min(h_row, settings_.h_cap);
  scratch_.clear();
  tree_.query(x, radius_.data(), x[i], reach, 0.0, motion_, [&](int j, double) {
    if (j != i) scratch_.push_back(j);
  });
  std::sort(scratch_.begin(), scratch_.end());
  stats_.wide_rows++;
  n = static_cast<int>(scratch_.size());
  return scratch_.data();
}

double NeighbourLists::memory_usage() const
{
  const double per_atom = hl_.capacity() * sizeof(double) + radius_.capacity() * sizeof(double) +
      half_.numneigh.capacity() * (sizeof(int) + sizeof(int *)) +
      full_.numneigh.capacity() * (sizeof(int) + sizeof(int *)) +
      (ilist_.capacity() + members_.capacity()) * sizeof(int);
  return per_atom + due_.memory_usage() + tree_.memory_usage() + half_.rows.memory_usage() +
      full_.rows.memory_usage() + (scratch_.capacity() + full_scratch_.capacity()) * sizeof(int);
}

}    // namespace SPHAstro
