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
  settings_.active_only = s.active_only && s.newton;
  // LAMMPS built in this step (ago 0) and not yet for these lists: a new step, or a new run
  // (its setup builds at the step the previous run ended on). The kind of step (active_only)
  // is that of the build: it changes only with a new run, whose init() invalidates the lists
  if (built_ && !(neighbor->ago == 0 && (stale_ || lmp->update->ntimestep != build_step_))) return;
  stale_ = false;
  build_step_ = lmp->update->ntimestep;
  build(h, neighbor->skin);
  motion_ = 0.5 * neighbor->skin;
  stats_.builds++;
}

NeighView NeighbourLists::half(const double *h)
{
  if (active_only_)
    error->one(FLERR, "pair_style sph/astro: the half list is not made with individual steps");
  follow_growth(h);
  return half_.view(inum_, ilist_.data());
}

void NeighbourLists::follow_growth(const double *h)
{
  const int nall = atom->nlocal + atom->nghost;
  const double *hl = hl_.data();
  int outgrown = 0;
  for (int i = 0; i < nall; i++) outgrown += h[i] > hl[i];
  // (collective: a pair two ranks share is decided alike on both)
  double share = nall > 0 ? static_cast<double>(outgrown) / nall : 0.0, largest;
  MPI_Allreduce(&share, &largest, 1, MPI_DOUBLE, MPI_MAX, world);
  if (largest > 0.0) {
    // atoms are up to skin/2 from LAMMPS' last build and go up to skin/2 from it before the
    // next one: up to skin from here, pairs up to 2 skin closer
    if (largest > EXTEND_LIMIT) {
      build(h, 2.0 * neighbor->skin);
      motion_ = neighbor->skin;
      stats_.step_builds++;
    } else
      extend(h, 2.0 * neighbor->skin);
  }
}

bool NeighbourLists::row_of_pair(int a, int b, int &row, int &partner) const
{
  const int nlocal = atom->nlocal;
  if (a < nlocal && b < nlocal) {    // owned pairs: in the row of the lower index
    row = a < b ? a : b;
    partner = a < b ? b : a;
    return true;
  }
  if (a >= nlocal && b >= nlocal) return false;    // two ghosts: not on this rank
  const int owned = a < nlocal ? a : b, ghost = a < nlocal ? b : a;
  if (!half_rule_.keeps_at(tree_.build_position(tree_.slot(owned)),
                           tree_.build_position(tree_.slot(ghost)), owned, ghost))
    return false;
  row = owned;
  partner = ghost;
  return true;
}

// the atoms whose h outgrew hl get hl = growth h; every pair their wider reach finds (at the
// current positions, the tree's bound on how far atoms moved since its build) that the lists
// lack is added to its row, and their gather rows are made anew
void NeighbourLists::extend(const double *h, double pad)
{
  double **x = atom->x;
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const SearchSettings &s = settings_;
  const double R = s.kernel_radius;
  grown_.clear();
  for (int i = 0; i < nall; i++) {
    if (!(h[i] > hl_[i])) continue;
    if (tree_.slot(i) < 0) {    // not an SPH atom: no pairs
      hl_[i] = h[i];
      continue;
    }
    hl_[i] = std::min(s.growth * h[i], s.h_cap);
    radius_[i] = R * hl_[i];
    grown_.push_back(i);
  }
  tree_.update_radii(radius_.data());
  inserts_.clear();
  for (int p : grown_)
    tree_.query(x, radius_.data(), x[p], radius_[p], pad, motion_, [&](int j, double) {
      if (j == p) return;
      if (active_only_) {    // both reach rows, where made (the others will use the new radii)
        if (p < nlocal && row_made(p)) inserts_.emplace_back(p, j);
        if (j < nlocal && row_made(j)) inserts_.emplace_back(j, p);
        return;
      }
      int row, partner;
      if (row_of_pair(p, j, row, partner)) inserts_.emplace_back(row, partner);
    });
  std::sort(inserts_.begin(), inserts_.end());
  inserts_.erase(std::unique(inserts_.begin(), inserts_.end()), inserts_.end());
  // each row with new partners: merged in atom order, stored anew
  for (std::size_t k = 0; k < inserts_.size();) {
    const int i = inserts_[k].first;
    std::size_t end = k;
    while (end < inserts_.size() && inserts_[end].first == i) end++;
    const int *row = half_.firstneigh[i];
    const int n = half_.numneigh[i];
    merged_.clear();
    int a = 0;
    for (std::size_t b = k; b < end; b++) {
      const int j = inserts_[b].second;
      while (a < n && row[a] < j) merged_.push_back(row[a++]);
      if (a < n && row[a] == j) continue;    // already held
      merged_.push_back(j);
    }
    while (a < n) merged_.push_back(row[a++]);
    stats_.extension_pairs += static_cast<LAMMPS_NS::bigint>(merged_.size()) - n;
    if (static_cast<int>(merged_.size()) > n) {
      half_.firstneigh[i] = half_.rows.append(merged_.data(), static_cast<int>(merged_.size()));
      half_.numneigh[i] = static_cast<int>(merged_.size());
    }
    k = end;
  }
  // gather rows of the grown owned atoms: r < R hl_i + pad
  if (s.full)
    for (int p : grown_) {
      if (p >= nlocal || !row_made(p)) continue;
      const double reach = radius_[p] + pad;
      merged_.clear();
      tree_.query(x, radius_.data(), x[p], radius_[p], pad, motion_, [&](int j, double r2) {
        if (j != p && r2 < reach * reach) merged_.push_back(j);
      });
      std::sort(merged_.begin(), merged_.end());
      full_.firstneigh[p] = full_.rows.append(merged_.data(), static_cast<int>(merged_.size()));
      full_.numneigh[p] = static_cast<int>(merged_.size());
    }
  due_indexed_ = false;
  stats_.extensions++;
  stats_.extended_atoms += static_cast<LAMMPS_NS::bigint>(grown_.size());
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

  pad_ = pad;
  active_only_ = s.active_only;
  half_rule_ = {nlocal, s.newton, domain->triclinic != 0, 0.01 * force->angstrom};
  half_.rows.reset();
  full_.rows.reset();
  due_indexed_ = false;
  const int leaves = tree_.leaves();
  leaf_made_.assign(leaves, 0);
  if (active_only_) {    // rows when their atoms are first active (prepare())
    if (static_cast<int>(leaf_of_.size()) < nlocal) leaf_of_.resize(nlocal);
    for (int l = 0; l < leaves; l++)
      for (int k = tree_.leaf_begin(l); k < tree_.leaf_end(l); k++)
        if (tree_.point(k) < nlocal) leaf_of_[tree_.point(k)] = l;
    stats_.rows_eager += inum_;
  } else
    for (int l = 0; l < leaves; l++) make_leaf_rows(l);
  built_ = true;
  const double atoms = std::max(inum_, 1);
  stats_.atoms = inum_;
  stats_.half_entries = active_only_ ? 0.0 : half_.rows.entries() / atoms;
  stats_.full_entries = s.full && !active_only_ ? full_.rows.entries() / atoms : 0.0;
  stats_.reach_entries = 0.0;
  rows_since_build_ = 0;
}

// one traversal collects the leaf's candidates (sph_astro_neighbour_tree.h); the rows hold the
// pairs at the build's positions, as the build saw them
void NeighbourLists::make_leaf_rows(int l)
{
  leaf_made_[l] = 1;
  const int nlocal = atom->nlocal;
  bool owned = false;
  for (int k = tree_.leaf_begin(l); k < tree_.leaf_end(l); k++) owned |= tree_.point(k) < nlocal;
  if (!owned) return;
  const SearchSettings &s = settings_;
  const HalfFromFull &half_rule = half_rule_;
  const bool reach_rows = active_only_;
  const double pad = pad_;
  int made = 0;
  tree_.query_leaf(l, pad, [&](int k, const int *found, int n) {
    const int i = tree_.point(k);
    if (i >= nlocal) return;
    made++;
    const double *xi = tree_.build_position(k);
    // (rows in atom order: every sum over a row then runs in an order that does not depend
    // on the tree, so a run continued from a restart, or with lists made at other steps,
    // adds the same terms in the same order)
    if (s.full) {    // the gather rows: r < R hl_i + pad
      const double reach = radius_[i] + pad;
      const double reach2 = reach * reach;
      full_scratch_.resize(n);
      int nfull = 0;
      for (int c = 0; c < n; c++) {
        const double *xj = tree_.build_position(found[c]);
        const double dx = xi[0] - xj[0], dy = xi[1] - xj[1], dz = xi[2] - xj[2];
        full_scratch_[nfull] = tree_.point(found[c]);
        nfull += (found[c] != k) & (dx * dx + dy * dy + dz * dz < reach2);
      }
      full_.firstneigh[i] = full_.rows.append(full_scratch_.data(), nfull);
      full_.numneigh[i] = nfull;
    }
    scratch_.resize(n);
    int nrow = 0;
    for (int c = 0; c < n; c++) {
      const int j = tree_.point(found[c]);
      scratch_[nrow] = j;
      nrow += (found[c] != k) &
          (reach_rows || half_rule.keeps_at(xi, tree_.build_position(found[c]), i, j));
    }
    half_.firstneigh[i] = half_.rows.append(scratch_.data(), nrow);
    half_.numneigh[i] = nrow;
  });
  if (reach_rows) {
    stats_.rows_made += made;
    rows_since_build_ += made;
    stats_.reach_entries = static_cast<double>(half_.rows.entries()) / rows_since_build_;
    if (s.full) stats_.full_entries = static_cast<double>(full_.rows.entries()) / rows_since_build_;
  }
}

void NeighbourLists::prepare(const char *active)
{
  if (!active_only_) return;
  for (int ii = 0; ii < inum_; ii++) {
    const int i = ilist_[ii];
    if (active[i] && !leaf_made_[leaf_of_[i]]) make_leaf_rows(leaf_of_[i]);
  }
}

NeighView NeighbourLists::due(const double *h, const char *active)
{
  follow_growth(h);
  if (active_only_) return due_from_reach_rows(active);
  const NeighView half = half_.view(inum_, ilist_.data());
  if (!due_indexed_) {
    due_.index(half, atom->nlocal + atom->nghost);
    due_indexed_ = true;
  }
  return due_.select(half, atom->nlocal, atom->nlocal + atom->nghost, active);
}

NeighView NeighbourLists::due_from_reach_rows(const char *active)
{
  prepare(active);
  double **x = atom->x;
  const int nlocal = atom->nlocal;
  if (static_cast<int>(due_numneigh_.size()) < nlocal) {
    due_numneigh_.resize(nlocal);
    due_firstneigh_.resize(nlocal);
  }
  due_ilist_.clear();
  std::size_t total = 0;
  for (int ii = 0; ii < inum_; ii++)
    if (active[ilist_[ii]]) total += half_.numneigh[ilist_[ii]];
  if (due_entries_.size() < total) due_entries_.resize(total);
  std::size_t offset = 0;
  for (int ii = 0; ii < inum_; ii++) {
    const int i = ilist_[ii];
    if (!active[i]) continue;
    const int *row = half_.firstneigh[i];
    const int n = half_.numneigh[i];
    int *out = due_entries_.data() + offset;
    int m = 0;
    // the row in atom order: owned j < i, owned j > i, ghosts. An inactive partner is always
    // evaluated here; an active one by the half rule: an owned j once, in the lower index's row;
    // a ghost on the rank the rule chooses at the current positions (both ranks hold them: the
    // owner's and the ghost's copy, which LAMMPS sends every step)
    const int *owned_end = std::lower_bound(row, row + n, nlocal);
    const int *above_i = std::upper_bound(row, owned_end, i);
    for (const int *e = row; e < above_i; e++) {
      out[m] = *e;
      m += !active[*e];
    }
    for (const int *e = above_i; e < owned_end; e++) out[m++] = *e;
    for (const int *e = owned_end; e < row + n; e++) {
      const int j = *e;
      out[m] = j;
      m += !active[j] || half_rule_.keeps(x, i, j);
    }
    due_numneigh_[i] = m;
    due_firstneigh_[i] = out;
    due_ilist_.push_back(i);
    offset += m;
  }
  return {static_cast<int>(due_ilist_.size()), due_ilist_.data(), due_numneigh_.data(),
          due_firstneigh_.data()};
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
  // (individual steps with newton on: the leaves' flags, the atoms' leaves, the due pairs)
  const double due_pairs = leaf_made_.capacity() * sizeof(char) +
      (leaf_of_.capacity() + due_ilist_.capacity() + due_numneigh_.capacity() +
       due_entries_.capacity()) *
          sizeof(int) +
      due_firstneigh_.capacity() * sizeof(int *);
  return per_atom + due_pairs + due_.memory_usage() + tree_.memory_usage() +
      half_.rows.memory_usage() + full_.rows.memory_usage() +
      (scratch_.capacity() + full_scratch_.capacity()) * sizeof(int);
}

}    // namespace SPHAstro
