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
#include "memory.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "pair.h"

#include <cmath>

using namespace LAMMPS_NS;

namespace SPHAstro {

NeighbourLists::~NeighbourLists()
{
  memory->destroy(hprune_);
}

void NeighbourLists::set_lammps_lists(NeighList *half, NeighList *full)
{
  lammps_half_ = half;
  lammps_full_ = full;
}

void NeighbourLists::clear()
{
  pruned_half_.clear();
  pruned_full_.clear();
  fallback_half_.clear();
}

/* ----------------------------------------------------------------------
   made when LAMMPS has just built its lists: the atoms sit where the build saw them, so a pair
   that comes within a kernel support before the next build is now closer than that support
   plus the skin (fixed h: growth 1, h does not change during a run)
------------------------------------------------------------------------- */

void NeighbourLists::prune(const double *h, const double *hcap_type, double growth,
                           double kernel_radius)
{
  double **x = atom->x;
  const int *type = atom->type;
  const int nall = atom->nlocal + atom->nghost;
  if (atom->nmax > nmax_) {
    nmax_ = atom->nmax;
    memory->grow(hprune_, nmax_, "pair:sph/astro:hprune");
  }
  for (int i = 0; i < nall; i++) hprune_[i] = MIN(growth * h[i], hcap_type[type[i]]);
  const double skin = neighbor->skin;
  const double R = kernel_radius;
  const double *hl = hprune_;
  const HalfFromFull half_rule = half_from_full();
  fallback_half_.clear();
  pruned_full_.clear();
  if (!lammps_full_ && nothing_to_prune(kernel_radius)) {    // LAMMPS' half list as it is
    pruned_half_.clear();
    lengths_[0] = lengths_[1] = 0.0;
    return;
  }

  // one scan of LAMMPS' full list (grad-h) or half list
  NeighList *src = lammps_full_ ? lammps_full_ : lammps_half_;
  begin(pruned_half_, src);
  if (lammps_full_) {
    begin(pruned_full_, src);
    // LAMMPS' half-from-full rule compares positions: taken now, at the build, for every entry
    const std::size_t entries = list_entries(src);
    if (half_keep_.size() < entries) half_keep_.resize(entries + entries / 4);
  }
  std::size_t offset = 0;
  for (int ii = 0; ii < src->inum; ii++) {
    const int i = src->ilist[ii];
    const double xi = x[i][0], yi = x[i][1], zi = x[i][2];
    const double hli = hl[i];
    const double reach_full = R * hli + skin;
    const double reach_full2 = reach_full * reach_full;
    const int *jlist = src->firstneigh[i];
    const int jnum = src->numneigh[i];
    int *half = row(pruned_half_, i);
    int *full = lammps_full_ ? row(pruned_full_, i) : nullptr;
    int nhalf = 0, nfull = 0;
    // branch-free compaction: every entry is written at the next free place of its row and
    // kept by advancing the count (a row has room for neigh_modify one >= jnum entries)
    if (lammps_full_) {
      unsigned char *keep = half_keep_.data() + offset;
      for (int jj = 0; jj < jnum; jj++) {
        const int j = jlist[jj] & NEIGHMASK;
        const bool in_half = half_rule.keeps(x, i, j);
        keep[jj] = in_half;
        const double dx = xi - x[j][0], dy = yi - x[j][1], dz = zi - x[j][2];
        const double r2 = dx * dx + dy * dy + dz * dz;
        const double reach = R * MAX(hli, hl[j]) + skin;
        const bool within = r2 < reach * reach;    // reach >= reach_full
        half[nhalf] = jlist[jj];
        nhalf += in_half & within;
        full[nfull] = jlist[jj];
        nfull += within & (r2 < reach_full2);
      }
    } else {
      for (int jj = 0; jj < jnum; jj++) {
        const int j = jlist[jj] & NEIGHMASK;
        const double dx = xi - x[j][0], dy = yi - x[j][1], dz = zi - x[j][2];
        const double r2 = dx * dx + dy * dy + dz * dz;
        const double reach = R * MAX(hli, hl[j]) + skin;
        half[nhalf] = jlist[jj];
        nhalf += r2 < reach * reach;
      }
    }
    offset += jnum;
    pruned_half_.close(i, nhalf);
    if (lammps_full_) pruned_full_.close(i, nfull);
  }
  const double inum = MAX(src->inum, 1);
  lengths_[0] = pruned_half_.entries() / inum;
  lengths_[1] = lammps_full_ ? pruned_full_.entries() / inum : 0.0;
}

// whether the pruned half list would keep every entry of LAMMPS' half list: LAMMPS keeps the
// pairs of types (a, b) closer than its cutoff + skin, the pruned list those closer than
// R max(hl_i, hl_j) + skin, so nothing goes where R max(hl_a^min, hl_b^min) reaches the cutoff
// for every type pair (one h per type with fixed h). LAMMPS' list then saves the scan and the
// memory; the sums are the same either way (entries outside every support add nothing).
bool NeighbourLists::nothing_to_prune(double kernel_radius) const
{
  const int ntypes = atom->ntypes;
  const int nall = atom->nlocal + atom->nghost;
  const int *type = atom->type;
  double **cutsq = force->pair->cutsq;
  std::vector<double> hlmin(ntypes + 1, INFINITY);
  for (int i = 0; i < nall; i++) hlmin[type[i]] = MIN(hlmin[type[i]], hprune_[i]);
  for (int a = 1; a <= ntypes; a++)
    for (int b = a; b <= ntypes; b++) {
      if (hlmin[a] == INFINITY || hlmin[b] == INFINITY) continue;    // no such atoms here
      const double reach = kernel_radius * MAX(hlmin[a], hlmin[b]);
      if (reach * reach < cutsq[a][b]) return false;
    }
  return true;
}

// rows of at most neigh_modify one entries, in LAMMPS' page size
void NeighbourLists::begin(PrunedList &list, const NeighList *src)
{
  if (!list.begin(src->inum, src->ilist, atom->nmax, neighbor->oneatom, neighbor->pgsize))
    error->one(FLERR,
               "pair_style sph/astro prune: cannot set up list pages (neigh_modify one {}, page "
               "{})",
               neighbor->oneatom, neighbor->pgsize);
}

int *NeighbourLists::row(PrunedList &list, int i)
{
  int *r = list.row(i);
  if (!r)
    error->one(FLERR,
               "pair_style sph/astro prune: out of memory for the pruned neighbour lists; use "
               "prune no");
  return r;
}

HalfFromFull NeighbourLists::half_from_full() const
{
  return {atom->nlocal, force->newton_pair != 0, domain->triclinic != 0, 0.01 * force->angstrom};
}

// LAMMPS' half list, or with grad-h and prune the half list made from LAMMPS' full list by
// LAMMPS' rule (decided at the build), when a pass first needs it after a build
NeighView NeighbourLists::unpruned_half()
{
  if (lammps_half_) return view_of(lammps_half_);
  if (!pruned_half_.built())    // (a run's setup builds the lists, and they are pruned there)
    error->all(FLERR,
               "pair_style sph/astro prune yes: no neighbour list was built in this run's setup; "
               "run with pre yes after changing the pair style");
  if (!fallback_half_.built()) {
    begin(fallback_half_, lammps_full_);
    std::size_t offset = 0;
    for (int ii = 0; ii < lammps_full_->inum; ii++) {
      const int i = lammps_full_->ilist[ii];
      const int *jlist = lammps_full_->firstneigh[i];
      const int jnum = lammps_full_->numneigh[i];
      int *half = row(fallback_half_, i);
      int n = 0;
      for (int jj = 0; jj < jnum; jj++)
        if (half_keep_[offset + jj]) half[n++] = jlist[jj];
      fallback_half_.close(i, n);
      offset += jnum;
    }
  }
  return fallback_half_.view();
}

NeighView NeighbourLists::half(const double *h)
{
  if (!pruned_half_.built()) return unpruned_half();
  const int nall = atom->nlocal + atom->nghost;
  for (int i = 0; i < nall; i++)
    if (h[i] > hprune_[i]) {
      fallbacks_++;
      return unpruned_half();
    }
  return pruned_half_.view();
}

NeighView NeighbourLists::full() const
{
  return pruned_full_.built() ? pruned_full_.view() : view_of(lammps_full_);
}

double NeighbourLists::limit(int i) const
{
  return pruned_half_.built() ? hprune_[i] : INFINITY;
}

double NeighbourLists::memory_usage() const
{
  return nmax_ * sizeof(double) + pruned_half_.memory_usage() + pruned_full_.memory_usage() +
      fallback_half_.memory_usage() + half_keep_.capacity();
}

}    // namespace SPHAstro
