/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Variable smoothing length

// fix ID group sph/astro/h dhdt [margin M] [rebuild F] [collections auto|N|no]
// fix ID group sph/astro/h iterate [hfact F] [tol T] [maxiter N] [margin M] [rebuild F]
//                                   [collections auto|N|no]
//
// In both modes h is advanced with the drift of fix sph/astro, h <- h exp(dt div v / d), the
// integral of dh/dt = (h/d) div v at fixed div v (Benz 1990; Monaghan 1992). In dhdt mode that is the
// evolution; in iterate mode it is the starting guess of the Newton-Raphson iteration that
// pair sph/astro runs in its density pass. Smoothing lengths are capped at margin x the
// largest h of their type when the run began (the neighbour list cutoffs are set for it).
//
// rebuild F: LAMMPS sets neighbour-list cutoffs when a run starts. At the end of a step in
// which some particle's h exceeds F x the cap of its type, or the largest h of a type fell
// below cap / margin^2 (lists far wider than needed), the run ends (like fix halt) so that
// the next run sets the cutoffs for the current h; the command sph/astro/run starts that
// next run by itself. No particle then reaches the cap as long as h grows by less than a
// factor 1/F per step.
//
// collections: per-particle neighbour cutoffs with neighbor multi. At every run start the fix
// divides the cutoffs kernel_radius x [1.2 h_min, cap] into N intervals ("auto": a factor
// sqrt(2) apart) and hands them to LAMMPS as neigh_modify collection/interval would; pair sph/astro
// puts each atom in the collection covering kernel_radius x 1.2 h_i (atom2cut), so small-h
// particles search small stencils. When an h grows to within 1/1.1 of its collection's
// cutoff the fix makes LAMMPS rebuild the lists at the next step (atoms change collection).
//
// Pruned lists (pair sph/astro prune yes, the default): when an h comes within 1/1.05 of the
// largest h its pruned neighbour list serves (1.1 x its h at the list build), the fix makes
// LAMMPS rebuild the lists at the next step, so the pruned lists are made anew before an h
// outgrows them.
//
// Global vector: 1 mean Newton iterations per particle of the latest density pass,
// 2 largest number of iterations, 3 particles that did not converge since the run began,
// 4 particles held at the h cap in the latest pass, 5 runs ended for a list rebuild,
// 6 list builds forced because an h outgrew its collection, 7 list builds forced because an
// h came near the limit of its pruned list, 8 pair passes (summed over ranks) and 9 atoms'
// h iterations that went past the pruned lists' limit and used LAMMPS' full lists instead.

#include "fix_sph_astro_h.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "memory.h"
#include "modify.h"
#include "neigh_request.h"
#include "neighbor.h"
#include "pair_sph_astro.h"
#include "sph_astro_options.h"
#include "sph_astro_passes.h"
#include "sph_astro_state.h"
#include "timer.h"
#include "update.h"
#include "utils.h"

#include <cmath>
#include <cstring>
#include <vector>

using namespace LAMMPS_NS;
using namespace FixConst;

FixSPHAstroH::FixSPHAstroH(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), state_(new SPHAstro::StateIndex())
{
  mode_ = Mode::ITERATE;
  hfact_ = 1.2;
  tolerance_ = 1e-4;
  max_iterations_ = 30;
  margin_ = 1.5;
  rebuild_ = 0.0;
  rebuild_requested_ = false;
  rebuilds_ = 0;
  collections_ = 0;
  collection_rebuilds_ = 0;
  prune_rebuilds_ = 0;
  pair_ = nullptr;
  iterate_flag_ = 1;

  vector_flag = 1;
  size_vector = 9;
  global_freq = 1;
  extvector = 0;

  if (narg < 4) utils::missing_cmd_args(FLERR, "fix sph/astro/h", error);
  if (strcmp(arg[3], "dhdt") == 0)
    mode_ = Mode::DHDT;
  else if (strcmp(arg[3], "iterate") == 0)
    mode_ = Mode::ITERATE;
  else
    error->all(FLERR, "fix sph/astro/h: mode '{}' is not one of: dhdt, iterate", arg[3]);

  int iarg = 4;
  while (iarg < narg) {
    const std::string key = arg[iarg];
    if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix sph/astro/h " + key, error);
    const char *val = arg[iarg + 1];
    if (key == "margin") {
      margin_ = utils::numeric(FLERR, val, false, lmp);
      if (!(margin_ >= 1.0)) error->all(FLERR, "fix sph/astro/h: margin = {} must be >= 1", val);
    } else if (key == "rebuild") {
      rebuild_ = utils::numeric(FLERR, val, false, lmp);
      if (rebuild_ != 0.0 && !(rebuild_ > 0.0 && rebuild_ <= 1.0))
        error->all(FLERR, "fix sph/astro/h: rebuild = {} must be in (1/margin, 1], or 0 (off)",
                   val);
    } else if (key == "collections") {
      if (strcmp(val, "auto") == 0)
        collections_ = -1;
      else if (strcmp(val, "no") == 0)
        collections_ = 0;
      else {
        collections_ = utils::inumeric(FLERR, val, false, lmp);
        if (collections_ < 1 || collections_ > 16)
          error->all(FLERR,
                     "fix sph/astro/h: collections = {} must be auto, no or a number in 1..16",
                     val);
      }
    } else if (mode_ == Mode::ITERATE && key == "hfact") {
      hfact_ = utils::numeric(FLERR, val, false, lmp);
      if (!(hfact_ > 0.0)) error->all(FLERR, "fix sph/astro/h: hfact = {} must be > 0", val);
    } else if (mode_ == Mode::ITERATE && key == "tol") {
      tolerance_ = utils::numeric(FLERR, val, false, lmp);
      if (!(tolerance_ > 0.0) || tolerance_ >= 0.1)
        error->all(FLERR, "fix sph/astro/h: tol = {} must be in (0, 0.1)", val);
    } else if (mode_ == Mode::ITERATE && key == "maxiter") {
      max_iterations_ = utils::inumeric(FLERR, val, false, lmp);
      if (max_iterations_ < 1) error->all(FLERR, "fix sph/astro/h: maxiter = {} must be >= 1", val);
    } else
      error->all(FLERR, "fix sph/astro/h {}: unknown keyword '{}'; allowed: {}", arg[3], key,
                 mode_ == Mode::ITERATE ? "hfact, tol, maxiter, margin, rebuild, collections"
                                        : "margin, rebuild, collections");
    iarg += 2;
  }
  // a new run's cap is margin x the largest h: the trigger must lie above it
  if (rebuild_ > 0.0 && !(rebuild_ * margin_ > 1.0))
    error->all(FLERR,
               "fix sph/astro/h: rebuild = {} must exceed 1/margin = {} (a new run starts with h "
               "at 1/margin of the cap)",
               rebuild_, 1.0 / margin_);
  // collections, and the pruned lists of pair sph/astro, ask for list builds
  force_reneighbor = 1;
  next_reneighbor = -1;
}

FixSPHAstroH::~FixSPHAstroH()
{
  delete state_;
}

void *FixSPHAstroH::extract(const char *name, int &dim)
{
  dim = 1;
  if (strcmp(name, "hfact") == 0) return &hfact_;
  if (strcmp(name, "tolerance") == 0) return &tolerance_;
  if (strcmp(name, "margin") == 0) return &margin_;
  dim = 0;
  iterate_flag_ = mode_ == Mode::ITERATE ? 1 : 0;
  if (strcmp(name, "iterate") == 0) return &iterate_flag_;
  if (strcmp(name, "maxiter") == 0) return &max_iterations_;
  return nullptr;
}

int FixSPHAstroH::setmask()
{
  // fix sph/astro calls advance_h() in its drift; end_of_step checks h against the caps,
  // the collections' cutoffs and the limits of the pruned lists
  return END_OF_STEP | POST_RUN;
}

void FixSPHAstroH::init()
{
  pair_ = dynamic_cast<PairSPHAstro *>(force->pair_match("^sph/astro$", 0, 0));
  if (!pair_) error->all(FLERR, "fix sph/astro/h requires pair_style sph/astro");
  if (!SPHAstro::find_state(lmp, *state_) || modify->get_fix_by_style("^sph/astro$").empty())
    error->all(FLERR, "fix sph/astro/h requires fix sph/astro (integrator and per-particle state)");
  if (modify->get_fix_by_style("^sph/astro/h$").size() > 1)
    error->all(FLERR, "fix sph/astro/h: only one instance is allowed");
  if (group->count(igroup) != atom->natoms) {
    if (mode_ == Mode::ITERATE)
      error->all(FLERR,
                 "fix sph/astro/h iterate: group {} must hold all particles (the density "
                 "iteration sets h for every SPH particle)",
                 group->names[igroup]);
    else if (comm->me == 0)
      error->warning(FLERR, "fix sph/astro/h dhdt: particles outside group {} keep their h",
                     group->names[igroup]);
  }
  rebuild_requested_ = false;
  if (collections_) setup_collections();
}

// geometric cutoff intervals from kernel_radius x 1.2 h_min to kernel_radius x the largest
// cap, handed to Neighbor as neigh_modify collection/interval does (read by neighbor->init(),
// which LAMMPS calls after the fixes' init)
void FixSPHAstroH::setup_collections()
{
  if (neighbor->style != Neighbor::MULTI)
    error->all(FLERR,
               "fix sph/astro/h collections needs neighbor style multi (e.g. neighbor 0.1 "
               "multi), got another neighbor style");
  // the collections size the neighbour lists of every pair style by h: other pair styles may
  // only join (hybrid/overlay) if they use no list, as sph/astro/gravity without kspace
  for (const auto *request : neighbor->get_pair_requests())
    if (request->get_requestor() != (void *) pair_)
      error->all(FLERR,
                 "fix sph/astro/h collections: pair_style sph/astro must be the only pair style "
                 "with a neighbour list (the collections size the lists of every pair style by "
                 "h); sph/astro/gravity qualifies only without kspace (direct summation)");
  const double *h = atom->dvector[state_->h];
  double hmin_local = INFINITY, hmin;
  for (int i = 0; i < atom->nlocal; i++) hmin_local = MIN(hmin_local, h[i]);
  MPI_Allreduce(&hmin_local, &hmin, 1, MPI_DOUBLE, MPI_MIN, world);
  double capmax = 0.0;
  for (int t = 1; t <= atom->ntypes; t++) capmax = MAX(capmax, pair_->h_cap(t));
  const double R = pair_->options().kernel_radius();
  const double cmax = R * capmax;
  double cmin = std::isfinite(hmin) ? MIN(R * hmin * PairSPHAstro::COLLECTION_GROWTH, cmax) : cmax;
  // LAMMPS bins every collection over the subdomain and its ghost shell with bins of half its
  // cutoff: keep the smallest collection at most ~200 bins across (8e6 bins), else a wide
  // range of h in a large box costs gigabytes of bins
  double extent = 0.0;
  for (int d = 0; d < domain->dimension; d++)
    extent = MAX(extent, domain->subhi[d] - domain->sublo[d] + 2.0 * (cmax + neighbor->skin));
  double extent_all;
  MPI_Allreduce(&extent, &extent_all, 1, MPI_DOUBLE, MPI_MAX, world);
  const double floor_cut = 2.0 * extent_all / 200.0;
  if (cmin < floor_cut) cmin = MIN(floor_cut, cmax);
  int n = collections_;
  // auto: cutoffs a factor sqrt(2) apart, so that an atom's stencil reaches at most
  // 1.2 sqrt(2) = 1.7 times its kernel support
  if (n < 0) n = 1 + static_cast<int>(std::ceil(2.0 * std::log2(cmax / cmin) - 1e-9));
  n = MAX(1, MIN(n, 16));
  if (cmax <= cmin) n = 1;
  neighbor->ncollections = n;
  memory->grow(neighbor->collection2cut, n, "neigh:collection2cut");
  for (int k = 0; k < n; k++)
    neighbor->collection2cut[k] = k == n - 1 ? cmax : cmin * std::pow(cmax / cmin, k / (n - 1.0));
  neighbor->interval_collection_flag = 1;
  neighbor->custom_collection_flag = 1;
  comm->ncollections_cutoff = 0;
  if (comm->me == 0) {
    std::string cuts;
    for (int k = 0; k < n; k++) cuts += fmt::format(" {:.4g}", neighbor->collection2cut[k]);
    utils::logmesg(lmp, "fix sph/astro/h: {} neighbour collections, cutoffs{}\n", n, cuts);
  }
}

// the setup lists allow every h up to its type's cap (PairSPHAstro::atom2cut): tight ones
// are built at step 1. With rebuild, particles held at the cap by the setup's h iteration
// (h far from its start value) end the run before its first step.
void FixSPHAstroH::setup(int /*vflag*/)
{
  if (collections_) next_reneighbor = update->ntimestep + 1;
  // the setup's h iteration may take h near or past the pruned lists' limit
  if (outgrown_lists() & 2) {
    next_reneighbor = update->ntimestep + 1;
    prune_rebuilds_++;
  }
  if (rebuild_ <= 0.0 || mode_ != Mode::ITERATE) return;
  int capped;
  MPI_Allreduce(&pair_->h_statistics().capped, &capped, 1, MPI_INT, MPI_SUM, world);
  if (capped == 0) return;
  rebuild_requested_ = true;
  rebuilds_++;
  timer->force_timeout();
  if (comm->me == 0)
    utils::logmesg(lmp,
                   "fix sph/astro/h: {} particles need h beyond the neighbour-list cap at the "
                   "setup of step {}: the run ends before its first step so that the lists are "
                   "rebuilt\n",
                   capped, update->ntimestep);
}

// bit 1: an h within 1/1.1 of its collection's cutoff; bit 2: an h within 1/PRUNE_REBUILD of
// its pruned list's limit, where that limit is below the h cap (a limit held at the cap does
// not grow with a new list); 0 when neither is in use (collective)
int FixSPHAstroH::outgrown_lists() const
{
  if (!collections_ && !pair_->pruning()) return 0;
  const double *h = atom->dvector[state_->h];
  const double grow = PairSPHAstro::PRUNE_REBUILD;
  int outgrown_local = 0, outgrown;
  for (int i = 0; i < atom->nlocal; i++) {
    if (collections_ && 1.1 * h[i] > pair_->h_limit(i)) outgrown_local |= 1;
    const double limit = pair_->prune_limit(i);
    if (grow * h[i] > limit && limit < pair_->h_cap(atom->type[i])) outgrown_local |= 2;
  }
  MPI_Allreduce(&outgrown_local, &outgrown, 1, MPI_INT, MPI_BOR, world);
  return outgrown;
}

void FixSPHAstroH::end_of_step()
{
  // rebuild the lists at the next step so that atoms change collection or get new pruned lists
  const int outgrown = outgrown_lists();
  if (outgrown) next_reneighbor = update->ntimestep + 1;
  if (outgrown & 1)
    collection_rebuilds_++;
  else if (outgrown & 2)
    prune_rebuilds_++;
  if (rebuild_ <= 0.0 || rebuild_requested_) return;
  const int ntypes = atom->ntypes;
  const double *h = atom->dvector[state_->h];
  const int *type = atom->type;
  // largest h per type and largest h / cap with the atom that has it
  std::vector<double> hmax_local(ntypes + 1, 0.0), hmax(ntypes + 1, 0.0);
  struct {
    double value;
    int tag;
  } worst_local = {0.0, 0}, worst;
  for (int i = 0; i < atom->nlocal; i++) {
    hmax_local[type[i]] = MAX(hmax_local[type[i]], h[i]);
    const double ratio = h[i] / pair_->h_cap(type[i]);
    if (ratio > worst_local.value) worst_local = {ratio, static_cast<int>(atom->tag[i])};
  }
  MPI_Allreduce(hmax_local.data(), hmax.data(), ntypes + 1, MPI_DOUBLE, MPI_MAX, world);
  MPI_Allreduce(&worst_local, &worst, 1, MPI_DOUBLE_INT, MPI_MAXLOC, world);
  int shrink_type = 0;
  for (int t = 1; t <= ntypes && margin_ > 1.0; t++)
    if (hmax[t] > 0.0 && hmax[t] * margin_ * margin_ < pair_->h_cap(t)) shrink_type = t;
  if (worst.value <= rebuild_ && !shrink_type) return;

  rebuild_requested_ = true;
  rebuilds_++;
  timer->force_timeout();
  if (comm->me == 0) {
    if (worst.value > rebuild_)
      utils::logmesg(lmp,
                     "fix sph/astro/h: h of atom {} reached {:.3g} of its neighbour-list cap at "
                     "step {}: the run ends so that the lists are rebuilt for the current h\n",
                     worst.tag, worst.value, update->ntimestep);
    else
      utils::logmesg(lmp,
                     "fix sph/astro/h: the largest h of type {} fell to {:.3g} of its "
                     "neighbour-list cap at step {}: the run ends so that the lists are rebuilt "
                     "narrower\n",
                     shrink_type, hmax[shrink_type] / pair_->h_cap(shrink_type), update->ntimestep);
  }
}

void FixSPHAstroH::post_run()
{
  // the stop for a rebuild ends this run only; later runs get the user's timeout back
  if (rebuild_requested_) timer->reset_timeout();
}

void FixSPHAstroH::advance_h(double dt)
{
  const double *divv = pair_->fields().divv;
  if (!divv || pair_->computed_nlocal() != atom->nlocal) return;
  double *h = atom->dvector[state_->h];
  const int *mask = atom->mask;
  const double dt_over_d = dt / domain->dimension;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    h[i] *= std::exp(dt_over_d * divv[i]);
    h[i] = MIN(h[i], pair_->h_limit(i));
  }
}

double FixSPHAstroH::compute_vector(int n)
{
  const SPHAstro::GradhStatistics &stats = pair_->h_statistics();
  if (n == 0) {
    double local[2] = {stats.iterations_sum, static_cast<double>(stats.particles)}, all[2];
    MPI_Allreduce(local, all, 2, MPI_DOUBLE, MPI_SUM, world);
    return all[1] > 0.0 ? all[0] / all[1] : 0.0;
  }
  if (n == 1) {
    int all;
    MPI_Allreduce(&stats.iterations_max, &all, 1, MPI_INT, MPI_MAX, world);
    return all;
  }
  if (n == 4) return static_cast<double>(rebuilds_);
  if (n == 5) return static_cast<double>(collection_rebuilds_);
  if (n == 6) return static_cast<double>(prune_rebuilds_);
  if (n == 7 || n == 8) {
    bigint local = n == 7 ? pair_->prune_fallbacks() : pair_->prune_atom_fallbacks(), all = 0;
    MPI_Allreduce(&local, &all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
    return static_cast<double>(all);
  }
  if (n == 2) {
    bigint local = pair_->h_failures(), all = 0;
    MPI_Allreduce(&local, &all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
    return static_cast<double>(all);
  }
  int all;
  MPI_Allreduce(&stats.capped, &all, 1, MPI_INT, MPI_SUM, world);
  return all;
}
