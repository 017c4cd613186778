/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Variable smoothing length

// fix ID group sph/astro/h dhdt [margin M] [hmax H]
// fix ID group sph/astro/h iterate [hfact F] [tol T] [maxiter N] [margin M] [hmax H]
//
// In both modes h is advanced with the drift of fix sph/astro, h <- h exp(dt div v / d), the
// integral of dh/dt = (h/d) div v at fixed div v (Benz 1990; Monaghan 1992). In dhdt mode that is the
// evolution; in iterate mode it is the starting guess of the Newton-Raphson iteration that
// pair sph/astro runs in its density pass.
//
// Neighbour search (pair sph/astro, sph_astro_neighbour_lists.h): smoothing lengths are capped
// at h_cap = (ghost cutoff - skin) / kernel radius. A run starts with the ghost cutoff set for
// h_cap = margin x the largest h (at most hmax; a margin above the default at most what the box
// allows, SPHAstro::box_h_cap). At the end of a step in which LIST_REBUILD x the largest h
// exceeds h_cap, the fix widens LAMMPS' ghost cutoff (as comm_modify cutoff would) to kernel
// radius x h_new + skin at the next step, which it makes a reneighbouring step: h_new =
// max(margin, 1.2) x the largest h, at most hmax and at most what half the shortest periodic
// box side, or the diagonal of a box periodic in none, allows. The user's comm_modify cutoff
// comes back at the end of the run. When an
// h comes within 1/LIST_REBUILD of the largest h its neighbour lists serve, the fix likewise
// has LAMMPS reneighbour at the next step, so that the lists are made anew before any h
// outgrows them (pair sph/astro would otherwise make them again inside the step).
//
// Global vector: 1 mean Newton iterations per particle of the latest density pass,
// 2 largest number of iterations, 3 particles that did not converge since the run began,
// 4 particles held at the h cap in the latest pass, 5 ghost-cutoff widenings, 6 reneighbourings
// asked for because an h neared its lists' limit, 7 list builds inside a step because an h
// outgrew its lists, 8 h iterations that went past their list's limit (summed over ranks) and
// 9 reneighbourings asked for because an h neared its face's ghost shell (ghosts narrow);
// 5-9 since the fix was defined.

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
#include "pair_hybrid.h"
#include "pair_sph_astro.h"
#include "pair_sph_astro_gravity.h"
#include "sph_astro_neighbour_lists.h"
#include "sph_astro_options.h"
#include "sph_astro_passes.h"
#include "sph_astro_scheme.h"
#include "sph_astro_state.h"
#include "update.h"
#include "utils.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

using namespace LAMMPS_NS;
using namespace FixConst;

FixSPHAstroH::FixSPHAstroH(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), drift_stats_(new SPHAstro::GradhStatistics()),
    state_(new SPHAstro::StateIndex())
{
  mode_ = Mode::ITERATE;
  hfact_ = 1.2;
  tolerance_ = 1e-4;
  max_iterations_ = 30;
  margin_ = SPHAstro::DEFAULT_MARGIN;
  h_max_ = INFINITY;
  user_cutghost_ = 0.0;
  pending_cutoff_ = 0.0;
  ghost_widenings_ = 0;
  for (double &c : carried_) c = 0.0;
  pair_ = nullptr;
  iterate_flag_ = 1;

  vector_flag = 1;
  size_vector = 9;
  restart_global = 1;
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
    if (key == "hmax") {
      h_max_ = utils::numeric(FLERR, val, false, lmp);
      if (!(h_max_ > 0.0)) error->all(FLERR, "fix sph/astro/h: hmax = {} must be > 0", val);
    } else if (key == "margin") {
      margin_ = utils::numeric(FLERR, val, false, lmp);
      if (!(margin_ >= 1.0)) error->all(FLERR, "fix sph/astro/h: margin = {} must be >= 1", val);
    } else if (key == "ghosts") {
      if (strcmp(val, "narrow") == 0)
        narrow_ghosts_ = true;
      else if (strcmp(val, "full") == 0)
        narrow_ghosts_ = false;
      else
        error->all(FLERR, "fix sph/astro/h: ghosts = {} is not one of: narrow, full", val);
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
      error->all(FLERR, "fix sph/astro/h {}: unknown keyword '{}'; allowed: {}{}", arg[3], key,
                 mode_ == Mode::ITERATE ? "hfact, tol, maxiter, margin, hmax, ghosts"
                                        : "margin, hmax, ghosts",
                 key == "rebuild" || key == "collections"
                     ? " (the package's neighbour search follows h within a run: no list "
                       "rebuild settings are needed)"
                     : "");
    iarg += 2;
  }
  // reneighbouring when h outgrows the lists or the ghost cutoff
  force_reneighbor = 1;
  next_reneighbor = -1;
  // LAMMPS' brick communication with a shell of its own width at each face (nullptr with
  // comm_style tiled: one cutoff)
  if (narrow_ghosts_) ghost_comm_ = CommSPHAstro::install(lmp);
}

FixSPHAstroH::~FixSPHAstroH()
{
  // LAMMPS' own brick communication again: CommSPHAstro's code leaves with the plugin, and
  // LAMMPS deletes its communication after its fixes
  if (auto *own = dynamic_cast<CommSPHAstro *>(comm)) {
    if (own->source() == this) own->set_source(nullptr);
    if (!own->source()) CommSPHAstro::uninstall(lmp);
  }
  delete state_;
  delete drift_stats_;
}

void *FixSPHAstroH::extract(const char *name, int &dim)
{
  dim = 1;
  if (strcmp(name, "hfact") == 0) return &hfact_;
  if (strcmp(name, "tolerance") == 0) return &tolerance_;
  if (strcmp(name, "margin") == 0) return &margin_;
  if (strcmp(name, "hmax") == 0) return &h_max_;
  if (strcmp(name, "carried_cap_start") == 0) return &carried_[0];
  if (strcmp(name, "carried_cap") == 0) return &carried_[1];
  dim = 0;
  iterate_flag_ = mode_ == Mode::ITERATE ? 1 : 0;
  if (strcmp(name, "iterate") == 0) return &iterate_flag_;
  if (strcmp(name, "maxiter") == 0) return &max_iterations_;
  return nullptr;
}

int FixSPHAstroH::setmask()
{
  // fix sph/astro calls advance_h() in its drift; end_of_step checks h against the lists'
  // limits and the ghost cutoff, which pre_exchange widens
  return END_OF_STEP | PRE_EXCHANGE | POST_RUN;
}

void FixSPHAstroH::init()
{
  pair_ = dynamic_cast<PairSPHAstro *>(force->pair_match("^sph/astro$", 0, 0));
  if (!pair_) error->all(FLERR, "fix sph/astro/h requires pair_style sph/astro");
  if (!SPHAstro::find_state(lmp, *state_) || modify->get_fix_by_style("^sph/astro$").empty())
    error->all(FLERR, "fix sph/astro/h requires fix sph/astro (integrator and per-particle state)");
  if (modify->get_fix_by_style("^sph/astro/h$").size() > 1)
    error->all(FLERR, "fix sph/astro/h: only one instance is allowed");
  // the SPH particles (the types of pair sph/astro's pair_coeff: sinks and stars are not) outside
  // the group
  bigint outside_local = 0, outside = 0;
  for (int i = 0; i < atom->nlocal; i++)
    if (pair_->setflag[atom->type[i]][atom->type[i]] && !(atom->mask[i] & groupbit))
      outside_local++;
  MPI_Allreduce(&outside_local, &outside, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  if (outside > 0) {
    if (mode_ == Mode::ITERATE)
      error->all(FLERR,
                 "fix sph/astro/h iterate: group {} must hold all SPH particles (the density "
                 "iteration sets h for every SPH particle)",
                 group->names[igroup]);
    else if (comm->me == 0)
      error->warning(FLERR, "fix sph/astro/h dhdt: particles outside group {} keep their h",
                     group->names[igroup]);
  }
  if (raised_) comm->cutghostuser = user_cutghost_;    // (an init without a run since)
  raised_ = false;
  user_cutghost_ = comm->cutghostuser;
  narrow_ready_ = false;
  ghost_comm_ = narrow_ghosts_ ? dynamic_cast<CommSPHAstro *>(comm) : nullptr;
  if (ghost_comm_) ghost_comm_->set_source(this);
  pending_cutoff_ = 0.0;
  // continuing a run (pair sph/astro took its h cap): its ghost cutoff and pending widening
  if (pair_->carried_cap_used()) {
    raised_ = carried_[2] > comm->cutghostuser;
    comm->cutghostuser = MAX(comm->cutghostuser, carried_[2]);
    pending_cutoff_ = carried_[3];
    if (pending_cutoff_ > 0.0) next_reneighbor = update->ntimestep + 1;
  }
}

// the setup's h iteration may take h near or past its lists' limit or the ghost cutoff
void FixSPHAstroH::setup(int /*vflag*/)
{
  in_run_ = true;
  check_limits();
  // the setup's h iteration ran with the whole shell; the next reneighbouring narrows it (runs
  // with pre no keep the shells of the run before, and narrow_ready_)
  narrow_ready_ = ghost_comm_ != nullptr;
  // particles held at the cap by the setup's iteration keep that h for one step
  int capped_local = pair_->h_statistics().capped, capped;
  MPI_Allreduce(&capped_local, &capped, 1, MPI_INT, MPI_SUM, world);
  int axis = -1;
  const double box_cap =
      SPHAstro::box_h_cap(lmp, pair_->kernel_radius(), neighbor->skin, axis) * (1.0 - 1e-12);
  if (capped > 0 && pair_->h_cap() < h_max_ && comm->me == 0) {
    if (pair_->h_cap() < box_cap)
      error->warning(FLERR,
                     "fix sph/astro/h: {} particles need h beyond the cap {:.6g} at the setup "
                     "of step {}; they keep the cap for one step, until the ghost cutoff is "
                     "widened (a larger margin, now {}, avoids this)",
                     capped, pair_->h_cap(), update->ntimestep, margin_);
    else
      error->warning(FLERR,
                     "fix sph/astro/h: {} particles need h beyond the cap {:.6g} at the setup "
                     "of step {}; they are held there: the cap is not widened past what {} "
                     "serves (h up to {:.6g})",
                     capped, pair_->h_cap(), update->ntimestep,
                     axis >= 0 ? "half the periodic box length" : "the box diagonal", box_cap);
  }
}

void FixSPHAstroH::end_of_step()
{
  check_limits();
}

// widen the ghost cutoff if the largest h came near h_cap, and with ghosts narrow make the
// shells anew if an h came near its face's shell (collective; an h that outgrows its lists
// inside a step has them extended there: sph_astro_neighbour_lists.h)
void FixSPHAstroH::check_limits()
{
  const double *h = atom->dvector[state_->h];
  const int *mask = atom->mask;
  const double grow = PairSPHAstro::LIST_REBUILD;
  const double cap = pair_->h_cap();
  double local[2] = {0.0, shells_overrun() ? 1.0 : 0.0}, all[2];
  for (int i = 0; i < atom->nlocal; i++)
    if (mask[i] & groupbit) local[0] = MAX(local[0], h[i]);
  MPI_Allreduce(local, all, 2, MPI_DOUBLE, MPI_MAX, world);
  const double hmax = all[0];
  if (all[1] > 0.0) {    // ghosts narrow: the shells made anew at the next step
    next_reneighbor = update->ntimestep + 1;
    ghost_remakes_++;
  }
  if (grow * hmax > cap && cap < h_max_) {
    // the new cap: room to grow, at most hmax and at most what half the shortest periodic box
    // side (a kernel wider than that sees a particle's own images) or the diagonal of a box
    // periodic in none serves (SPHAstro::box_h_cap)
    const double R = pair_->kernel_radius(), skin = neighbor->skin;
    int axis = -1;
    const double new_cap =
        MIN(MIN(MAX(margin_, WIDEN) * hmax, h_max_), SPHAstro::box_h_cap(lmp, R, skin, axis));
    if (new_cap > grow * cap) {
      pending_cutoff_ = R * new_cap + skin;
      next_reneighbor = update->ntimestep + 1;
    }
  }
}

// the faces of this rank's sub-domain, k = 2 d + side (side 0 lower, 1 upper): LAMMPS makes
// ghosts across all but a non-periodic box boundary
namespace {
struct SubdomainFaces {
  const double *sublo, *subhi;
  bool ghosts[6];
  int count;    // 2 x dimension
  explicit SubdomainFaces(LAMMPS *lmp) :
      sublo(lmp->domain->sublo), subhi(lmp->domain->subhi), count(2 * lmp->domain->dimension)
  {
    for (int d = 0; d < 3; d++) {
      const bool periodic = lmp->domain->periodicity[d] != 0;
      ghosts[2 * d] = periodic || lmp->comm->myloc[d] > 0;
      ghosts[2 * d + 1] = periodic || lmp->comm->myloc[d] < lmp->comm->procgrid[d] - 1;
    }
  }
  // the distance of x from face k (negative outside the sub-domain)
  double distance(const double *x, int k) const
  {
    const int d = k / 2;
    return k % 2 ? subhi[d] - x[d] : x[d] - sublo[d];
  }
};
}    // namespace

// the pair styles that compute forces: the sub-styles of a hybrid style (found by
// Force::pair_match over their keywords, with patterns that leave out the name hybrid...), else
// the style itself
static std::vector<Pair *> pair_styles(LAMMPS *lmp)
{
  std::vector<Pair *> pairs;
  Pair *pair = lmp->force->pair;
  if (!dynamic_cast<PairHybrid *>(pair)) {
    if (pair) pairs.push_back(pair);
    return pairs;
  }
  for (const char *pattern : {"^[^h]", "^h[^y]"})
    for (int nsub = 1;; nsub++) {
      Pair *sub = lmp->force->pair_match(pattern, 0, nsub);
      if (!sub || std::find(pairs.begin(), pairs.end(), sub) != pairs.end()) break;
      pairs.push_back(sub);
    }
  return pairs;
}

// ghosts narrow: the shell at a sub-domain face must hold, for every pair whose separation
// crosses it, the partner of each particle; a particle i within r_i of the face needs
// r_i = R h_i + skin (its support; atoms move up to skin/2 each between reneighbourings). The
// reach given for it is max(margin, WIDEN) R h_i + skin with the h of now (>= LIST_GROWTH: the
// reach of the lists, sph_astro_neighbour_lists.h), as the ghost cutoff serves margin x the
// largest h; floor: the cutoff of the other pair styles (+ skin) and comm_modify cutoff.
// Returns false where it cannot narrow: molecular systems (bonds cross faces), a pair style
// other than sph/astro and sph/astro/gravity, neighbour lists of fixes or computes (LAMMPS'
// one cutoff), and the setup of a run (its h iteration may take h far from the h of the start).
bool FixSPHAstroH::ghost_reaches(double *reach, double &floor)
{
  if (!narrow_ready_ || !pair_ || atom->molecular != Atom::ATOMIC) return false;
  const double skin = neighbor->skin;
  floor = user_cutghost_;
  const std::vector<Pair *> pairs = pair_styles(lmp);
  for (Pair *pair : pairs) {
    if (dynamic_cast<PairSPHAstro *>(pair)) continue;
    auto *gravity = dynamic_cast<PairSPHAstroGravity *>(pair);
    if (!gravity) return false;
    // (with MSM its cutoff is the one MSM chose)
    if (gravity->list_cutoff() > 0.0) floor = MAX(floor, gravity->list_cutoff() + skin);
  }
  for (int r = 0; r < neighbor->nrequest; r++) {
    const void *requestor = neighbor->requests[r]->get_requestor();
    if (std::find(pairs.begin(), pairs.end(), requestor) == pairs.end()) return false;
  }

  const double reach_per_h = pair_->kernel_radius() * MAX(margin_, WIDEN);
  const double *h = atom->dvector[state_->h];
  double **x = atom->x;
  const SubdomainFaces faces(lmp);
  for (int k = 0; k < 6; k++) reach[k] = 0.0;
  for (int i = 0; i < atom->nlocal; i++) {
    const double r = reach_per_h * h[i] + skin;
    for (int k = 0; k < faces.count; k++)
      if (faces.ghosts[k] && faces.distance(x[i], k) < r) reach[k] = MAX(reach[k], r);
  }
  return true;
}

// ghosts narrow, at the end of every step (check_limits): does a particle of this rank reach,
// LIST_REBUILD ahead of its h, across a face past that face's shell (then LAMMPS reneighbours
// at the next step, whose pre_exchange sets the shells anew)? One whose support R h + skin
// already crosses it may have missed partners in this step: stop
bool FixSPHAstroH::shells_overrun()
{
  if (!narrow_ready_ || ghost_comm_ != comm || !ghost_comm_->narrowed()) return false;
  const double R = pair_->kernel_radius(), skin = neighbor->skin;
  const double ahead_per_h = R * PairSPHAstro::LIST_GROWTH * PairSPHAstro::LIST_REBUILD;
  const double *h = atom->dvector[state_->h];
  double **x = atom->x;
  const SubdomainFaces faces(lmp);
  double width[6], narrowest = INFINITY;
  bool watched[6];
  for (int k = 0; k < 6; k++) {
    width[k] = ghost_comm_->width(k / 2, k % 2);
    watched[k] = faces.ghosts[k] && ghost_comm_->narrowed(k / 2, k % 2);
    if (watched[k]) narrowest = MIN(narrowest, width[k]);
  }
  bool overrun = false;
  for (int i = 0; i < atom->nlocal; i++) {
    const double ahead = ahead_per_h * h[i] + skin, support = R * h[i] + skin;
    if (ahead <= narrowest) continue;    // (most particles: within every shell)
    for (int k = 0; k < faces.count; k++) {
      if (!watched[k] || ahead <= width[k]) continue;
      const double distance = faces.distance(x[i], k);
      if (distance >= ahead) continue;
      overrun = true;
      if (support > width[k] && distance < support)
        error->one(FLERR,
                   "fix sph/astro/h: atom {} (h = {:.6g}) reaches {:.6g} across its {} "
                   "sub-domain face in dimension {}, past that face's ghost shell {:.6g} set at "
                   "the last reneighbouring; its h grew too fast for ghosts narrow (use a larger "
                   "margin, now {}, or ghosts full)",
                   atom->tag[i], h[i], support, k % 2 ? "upper" : "lower", k / 2 + 1, width[k],
                   margin_);
    }
  }
  return overrun;
}

// at a reneighbouring step, before LAMMPS exchanges atoms and makes the ghosts: the ghost
// cutoff widened if asked for, and with ghosts narrow the shell of each face set anew from
// the h of now (comm->setup(), as LAMMPS does itself when the box changes)
void FixSPHAstroH::pre_exchange()
{
  bool remake = narrow_ready_ && ghost_comm_ == comm;
  if (pending_cutoff_ > 0.0) {
    const double old_cutoff = MAX(comm->cutghostuser, neighbor->cutneighmax);
    if (pending_cutoff_ > old_cutoff) {
      comm->cutghostuser = pending_cutoff_;
      remake = true;
      ghost_widenings_++;
      if (comm->me == 0)
        utils::logmesg(lmp,
                       "fix sph/astro/h: ghost cutoff widened from {:.6g} to {:.6g} at step {} "
                       "(h cap {:.6g})\n",
                       old_cutoff, pending_cutoff_, update->ntimestep,
                       (pending_cutoff_ - neighbor->skin) / pair_->kernel_radius());
    }
    pending_cutoff_ = 0.0;
  }
  // (a changing box: LAMMPS sets the communication and bins up itself after this)
  if (!remake || domain->box_change) return;
  comm->setup();
  if (neighbor->style) neighbor->setup_bins();
}

// the next run sets its ghost cutoff from its h; the user's comm_modify cutoff comes back
void FixSPHAstroH::post_run()
{
  if (narrow_ready_ && ghost_comm_ == comm && comm->me == 0) {
    const char axes[] = "xyz";
    std::string shells;
    for (int d = 0; d < domain->dimension; d++) {
      const double lower = ghost_comm_->width(d, 0), upper = ghost_comm_->width(d, 1);
      shells += fmt::format("{}{} {:.6g} {:.6g}", d ? ", " : "", axes[d], lower, upper);
    }
    utils::logmesg(lmp,
                   "fix sph/astro/h ghosts narrow: shells at the lower and upper faces {} at the "
                   "end on rank 0 (ghost cutoff {:.6g}); {} reneighbourings asked for by the "
                   "shells since the fix was defined\n",
                   shells, MAX(comm->cutghostuser, neighbor->cutneighmax), ghost_remakes_);
  }
  carry();
  in_run_ = raised_ = false;
  comm->cutghostuser = user_cutghost_;
  pending_cutoff_ = 0.0;
}

void FixSPHAstroH::carry()
{
  if (!pair_) return;
  carried_[0] = pair_->h_cap_start();
  carried_[1] = pair_->h_cap();
  carried_[2] = comm->cutghostuser > user_cutghost_ ? comm->cutghostuser : 0.0;
  carried_[3] = pending_cutoff_;
}

// (between runs the values carried from the last run are written)
void FixSPHAstroH::write_restart(FILE *fp)
{
  if (in_run_) carry();
  if (comm->me != 0) return;
  int size = sizeof(carried_);
  fwrite(&size, sizeof(int), 1, fp);
  fwrite(carried_, sizeof(double), 4, fp);
}

void FixSPHAstroH::restart(char *buf)
{
  memcpy(carried_, buf, sizeof(carried_));
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
    h[i] = MIN(h[i], pair_->h_cap());
  }
  count_capped();
}

void FixSPHAstroH::count_capped()
{
  if (mode_ != Mode::DHDT) return;
  const double *h = atom->dvector[state_->h];
  const int *mask = atom->mask;
  const double cap = pair_->h_cap();
  *drift_stats_ = SPHAstro::GradhStatistics();
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    drift_stats_->particles++;
    if (h[i] < cap) continue;
    drift_stats_->capped++;
    if (!drift_stats_->first_capped || atom->tag[i] < drift_stats_->first_capped)
      drift_stats_->first_capped = atom->tag[i];
  }
}

const SPHAstro::GradhStatistics &FixSPHAstroH::h_statistics() const
{
  return mode_ == Mode::ITERATE ? pair_->h_statistics() : *drift_stats_;
}

double FixSPHAstroH::compute_vector(int n)
{
  const SPHAstro::GradhStatistics &stats = h_statistics();
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
  if (n == 4) return static_cast<double>(ghost_widenings_);
  if (n == 8) return static_cast<double>(ghost_remakes_);
  if (n == 5) {    // (the extensions are collective: the same count on every rank)
    return static_cast<double>(pair_->search_statistics().extensions);
  }
  if (n == 6 || n == 7) {
    const SPHAstro::SearchStatistics &search = pair_->search_statistics();
    bigint local = n == 6 ? search.step_builds : search.wide_rows, all = 0;
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
