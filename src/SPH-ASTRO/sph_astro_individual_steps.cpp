/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

#include "sph_astro_individual_steps.h"

#include "fix_sph_astro_owned.h"
#include "pair_sph_astro.h"
#include "sph_astro_options.h"
#include "sph_astro_sparse_message.h"
#include "sph_astro_time_bins.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "force.h"
#include "group.h"
#include "modify.h"
#include "neighbor.h"
#include "update.h"
#include "utils.h"

#include <algorithm>
#include <cmath>

using namespace LAMMPS_NS;

namespace SPHAstro {

IndividualSteps::IndividualSteps(LAMMPS *lmp, Fix *owner, int levels, bool pair_kicks) :
    Pointers(lmp), owner_(owner), levels_(levels), pair_kicks_(pair_kicks)
{
}

int IndividualSteps::owner_groupbit() const
{
  return owner_->groupbit;
}

double IndividualSteps::tick() const
{
  return dt_max_ / TimeBins::cycle();
}

void IndividualSteps::grow()
{
  const std::size_t n = atom->nmax;
  if (active_.size() < n) {
    active_.resize(n);
    bins_.resize(n);
    required_.resize(n);
    bins_sent_.resize(n);
    bins_changed_.resize(n);
  }
}

// keywords that would do nothing, and a limiter off, under which a blast runs into gas whose
// steps are long (Saitoh & Makino 2009, ApJ 697, L99): its energy goes wrong
void IndividualSteps::warn_keywords(LAMMPS *lmp, const std::map<std::string, std::string> &given,
                                    bool individual, bool long_range_sync, int levels)
{
  if (lmp->comm->me != 0) return;
  for (const char *key : {"limiter", "kicks"})
    if (!individual && given.count(key))
      lmp->error->warning(FLERR,
                          "fix sph/astro: {} {} is ignored with steps global (every particle "
                          "takes the global leapfrog's step; it applies to steps individual)",
                          key, given.at(key));
  if (given.count("longdisplacement") && !long_range_sync)
    lmp->error->warning(FLERR,
                        "fix sph/astro: longdisplacement {} is ignored without longrange sync (it "
                        "bounds the displacement between the long-range evaluations of sync)",
                        given.at("longdisplacement"));
  if (individual && levels == 0)
    lmp->error->warning(FLERR,
                        "fix sph/astro: limiter off with steps individual: a shock or blast that "
                        "reaches particles on long steps is not felt by them until their steps "
                        "end, and the energy is not conserved (a hot spot in cold gas lost 28 % "
                        "of its energy in 200 steps); use limiter 1 or 2 where gas is heated fast");
}

void IndividualSteps::check_options(const PairSPHAstro *pair, bool entropy, int igroup)
{
  const PairOptions &o = pair->options();
  const char *what = entropy ? "fix sph/astro thermal entropy"
      : o.density_continuity ? "pair_style sph/astro density continuity"
      : o.reconstruction()   ? "pair_style sph/astro reconstruct"
      : o.pressure_energy    ? "pair_style sph/astro formulation pressure-energy"
                             : nullptr;
  if (what)
    error->all(FLERR,
               "fix sph/astro steps individual: {} is not available with individual timesteps "
               "(use steps global)",
               what);
  // atoms of other types (point masses, moved by other fixes at every step) are always active
  // for the gravity styles (ActiveSet)
  if (pair->gas_outside(group->bitmask[igroup]) > 0)
    error->all(FLERR,
               "fix sph/astro steps individual: group {} must hold all SPH gas particles (the "
               "atom types of pair sph/astro's pair_coeff: each pair is evaluated when one of "
               "its particles is active)",
               group->names[igroup]);
  // (the tree's own part follows the active particles: only the PPPM part of its periodic
  // TreePM can wait for synchronisation points)
  const bool periodic = domain->xperiodic && domain->yperiodic && domain->zperiodic;
  if (long_range_ &&
      !(force->kspace &&
        (utils::strmatch(force->kspace_style, "^msm/sph/astro/gravity") ||
         utils::strmatch(force->kspace_style, "^pppm/sph/astro/gravity") ||
         (periodic && utils::strmatch(force->kspace_style, "^tree/sph/astro/gravity")))))
    error->all(FLERR,
               "fix sph/astro: longrange sync needs kspace_style msm/sph/astro/gravity, "
               "pppm/sph/astro/gravity or tree/sph/astro/gravity in a periodic box (kspace_style "
               "is {}{}); the tree in an open box computes the active particles only and needs "
               "no sync",
               force->kspace ? force->kspace_style : "none",
               force->kspace && !periodic ? ", open box" : "");
}

void IndividualSteps::init(const StateIndex &state, bool state_unchanged)
{
  state_ = state;
  if (!find_step_state(lmp, idx_))
    error->all(FLERR,
               "fix sph/astro steps individual: the per-particle step state fix {} is missing",
               STEPS_FIX_ID);
  // (its slots follow LAMMPS' exchanges, sorts and created atoms; a run begins with all)
  auto *owned = dynamic_cast<FixSPHAstroOwned *>(modify->get_fix_by_id(STEPS_FIX_ID));
  if (owned) owned->reserve(atom->nlocal);
  if (long_range_) {
    accel_long_ = find_long_range_state(lmp);
    if (accel_long_ < 0)
      error->all(FLERR,
                 "fix sph/astro longrange sync: the per-particle long-range state fix {} is "
                 "missing",
                 LONG_RANGE_FIX_ID);
    auto *kept = dynamic_cast<FixSPHAstroOwned *>(modify->get_fix_by_id(LONG_RANGE_FIX_ID));
    if (kept) kept->reserve(atom->nlocal);
    long_evaluations_ = 0.0;
  }
  continuing_ = started_ && state_unchanged && hierarchy_step_ == update->ntimestep;
  times_opened_ = times_closed_ = -1;    // the run's setup sends the ghosts anew
  bins_sent_step_ = -1;
  kicked_step_ = -1;    // (the setup may reorder the atoms)
}

void IndividualSteps::setup_pre_force(PairSPHAstro *pair)
{
  grow();
  const int nall = atom->nlocal + atom->nghost;
  const int *mask = atom->mask;
  // a continued hierarchy has every particle's values from its last evaluation: the setup
  // evaluates none; a new one evaluates all
  for (int i = 0; i < nall; i++) active_[i] = !continuing_ && (mask[i] & owner_->groupbit);
  long_due_ = long_range_ && !continuing_;
  times_opened_ = times_closed_ = bins_sent_step_ = -1;
  pair->set_active(active_.data(), records_pairs(), pair_kicks_);
}

void IndividualSteps::start(const std::vector<double> &wanted, double dtmax, double time_left,
                            PairSPHAstro *pair, bool open_pairs)
{
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  double **f = atom->f;
  double **accel = atom->darray[idx_.accel];
  const double *dudt = atom->dvector[state_.dudt];
  double *dudt_kept = atom->dvector[idx_.dudt];
  double top_local = -1.0, top;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & owner_->groupbit)) continue;
    const double m = mass(i);
    const double *along = long_range_acceleration(i);
    for (int d = 0; d < 3; d++) accel[i][d] = f[i][d] / m - along[d];
    dudt_kept[i] = dudt[i];
    if (std::isfinite(wanted[i])) top_local = std::max(top_local, wanted[i]);
  }
  MPI_Allreduce(&top_local, &top, 1, MPI_DOUBLE, MPI_MAX, world);
  if (dtmax > 0.0) top = top > 0.0 ? std::min(top, dtmax) : dtmax;
  if (time_left > 0.0) {    // tend on the grid: dt_max = (tend - now) / 2^k
    if (!(top > 0.0) || top >= time_left)
      top = time_left;
    else
      top = time_left / std::exp2(std::ceil(std::log2(time_left / top)));
  }
  if (!(top > 0.0) || !std::isfinite(top))
    error->all(FLERR,
               "fix sph/astro steps individual: no particle's timestep criteria limit its step "
               "and neither dtmax nor tend is set; set dtmax (the longest step)");
  dt_max_ = top;
  ti_now_ = 0.0;
  started_ = true;
  updates_ = steps_ = woken_ = 0.0;
  hierarchy_step_ = update->ntimestep;
  kicked_step_ = -1;
  assign_bins(wanted, true, pair);
  if (!open_pairs) {
    advance_to_next();
    return;
  }
  for (int i = 0; i < nlocal; i++) {    // a new hierarchy: no pair is pending
    std::fill_n(atom->darray[idx_.pending][i], PENDING_SLOTS * PENDING_VALUES, 0.0);
    std::fill_n(atom->darray[idx_.recent][i], RECENT_VALUES, 0.0);
    atom->dvector[idx_.pending_next][i] = 0.0;
  }
  pair_impulses(pair, false, true);
  keep_pending();
  double **accel_other = atom->darray[idx_.accel_other];
  double **kick = atom->darray[idx_.kick];
  double **lead = atom->darray[idx_.pair_lead];
  double *dudt_other = atom->dvector[idx_.dudt_other];
  double *kick_u = atom->dvector[idx_.kick_u];
  double *lead_u = atom->dvector[idx_.lead_u];
  const double *begin = atom->dvector[idx_.begin];
  const double *end = atom->dvector[idx_.end];
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & owner_->groupbit)) continue;
    const double m = mass(i);
    const double *sum = pair_sums(i);
    const double *rate = sum + SUM_KICKS;
    const double half = 0.5 * (end[i] - begin[i]) * tick();
    const double *along = long_range_acceleration(i);
    for (int d = 0; d < 3; d++) {
      accel_other[i][d] = (f[i][d] - rate[d]) / m - along[d];
      kick[i][d] = sum[d] / m;
      lead[i][d] = (half * rate[d] - sum[d]) / m;
    }
    dudt_other[i] = dudt_kept[i] - rate[3];
    kick_u[i] = sum[3];
    lead_u[i] = half * rate[3] - sum[3];
  }
  advance_to_next();
}

void IndividualSteps::kick_drift(double h_cap, bool evolve_u)
{
  const double t = tick();
  const double dt = next_dt();
  const double dt_over_d = dt / domain->dimension;
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  double **x = atom->x;
  double **v = atom->v;
  double **vest = atom->darray[state_.vest];
  double *u = atom->dvector[state_.u];
  double *uest = atom->dvector[state_.uest];
  double *rho = atom->dvector[state_.rho];
  double *h = atom->dvector[state_.h];
  const double *begin = atom->dvector[idx_.begin];
  const double *end = atom->dvector[idx_.end];
  double **accel = atom->darray[idx_.accel];
  double **accel_other = atom->darray[idx_.accel_other];
  double **kick = atom->darray[idx_.kick];
  const double *const *lead = atom->darray[idx_.pair_lead];
  const double *dudt = atom->dvector[idx_.dudt];
  const double *dudt_other = atom->dvector[idx_.dudt_other];
  double *kick_u = atom->dvector[idx_.kick_u];
  const double *lead_u = atom->dvector[idx_.lead_u];
  const double *divv = atom->dvector[idx_.divv];
  const double *const *recent = atom->darray[idx_.recent];
  const double t_end = ti_next_ * t;
  // the pair kicks that opened at the last evaluation: those of the atoms in its pairs, or
  // (the first step of a run, which may continue one with kicks pair, or of a hierarchy) all
  const bool listed = kicked_step_ >= 0 && kicked_step_ == update->ntimestep - 1;
  if (long_range_) long_range_interval();
  const double *const *along = long_range_ ? atom->darray[accel_long_] : nullptr;
  const double tau_long = (ti_next_ - long_middle_) * t;
  auto opening_kick = [&](int i) {
    for (int d = 0; d < 3; d++) {
      v[i][d] += kick[i][d];
      kick[i][d] = 0.0;
    }
    if (evolve_u) u[i] += kick_u[i];
    kick_u[i] = 0.0;
  };
  if (listed)
    for (int i : kicked_) opening_kick(i);
  if (nlocal == 0) return;
  // (the per-atom arrays are contiguous, LAMMPS' memory->create: one stream each, not a row
  // pointer per atom as well)
  double *xf = x[0], *vf = v[0], *vestf = vest[0];
  const double *accelf = accel[0];
  const double *leadf = pair_kicks_ ? lead[0] : nullptr;
  const double *recentf = pair_kicks_ ? recent[0] : nullptr;
  for (int i = 0; i < nlocal; i++) {
    double *xi = xf + 3 * i, *vi = vf + 3 * i, *vesti = vestf + 3 * i;
    const double *acceli = accelf + 3 * i;
    if (!(mask[i] & owner_->groupbit)) {
      for (int d = 0; d < 3; d++) vesti[d] = vi[d];
      uest[i] = u[i];
      continue;
    }
    if (!listed) opening_kick(i);
    if (begin[i] == ti_now_) {    // a step begins: first half kick (terms not of pairs)
      const double half = 0.5 * (end[i] - begin[i]) * t;
      for (int d = 0; d < 3; d++) vi[d] += half * accel_other[i][d];
      if (evolve_u) u[i] += half * dudt_other[i];
    }
    // the velocity predicted from the middle of the particle's step; with kicks pair, the
    // pairs on a shorter interval than that step have kicked it further (their lead is the
    // part of the prediction they have given). The drift takes it at the middle of this
    // LAMMPS step: x = x_b + v_b tau + a tau^2 / 2 inside the particle's step, which ends
    // where the drift with v_b + a dt_i / 2 does, and which a wake does not change
    const double mid = 0.5 * (begin[i] + end[i]);
    const double tau_drift = (0.5 * (ti_now_ + ti_next_) - mid) * t;
    const double tau = (ti_next_ - mid) * t;
    // with kicks pair, a sleeping particle's prediction takes the forces of its pairs evaluated
    // since its own evaluation, sum (F_ij,new - F_ij,old) (t - t_mid,ij) / m = s t - c (its
    // drift stays on its parabola)
    double lead_x[3] = {0.0, 0.0, 0.0}, lead_v[3] = {0.0, 0.0, 0.0};
    if (pair_kicks_) {
      const double *leadi = leadf + 3 * i, *recenti = recentf + RECENT_VALUES * i;
      for (int d = 0; d < 3; d++) {
        lead_x[d] = leadi[d];
        lead_v[d] = leadi[d] + recenti[d] * t_end - recenti[3 + d];
      }
    }
    for (int d = 0; d < 3; d++) {
      xi[d] += dt * (vi[d] + tau_drift * acceli[d] + lead_x[d]);
      vesti[d] = vi[d] + tau * acceli[d] + lead_v[d];
    }
    // (longrange sync: v is that of the interval's middle for the long range)
    if (along)
      for (int d = 0; d < 3; d++) vesti[d] += tau_long * along[i][d];
    uest[i] = evolve_u ? u[i] + tau * dudt[i] + lead_u[i] : u[i];
    // rho and h follow the last div v (active particles: the h iteration's first guess)
    if (divv[i] != 0.0) {
      if (h_cap > 0.0) h[i] = std::min(h[i] * std::exp(dt_over_d * divv[i]), h_cap);
      rho[i] *= std::exp(-dt * divv[i]);
    } else if (h_cap > 0.0) {
      h[i] = std::min(h[i], h_cap);
    }
  }
}

void IndividualSteps::pre_force(PairSPHAstro *pair)
{
  grow();
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  const double *end = atom->dvector[idx_.end];
  active_list_.clear();
  for (int i = 0; i < nlocal; i++) {
    active_[i] = (mask[i] & owner_->groupbit) && end[i] == ti_next_;
    if (active_[i]) active_list_.push_back(i);
  }
  double counts[2] = {static_cast<double>(active_list_.size()), 0.0}, totals[2];
  if (long_range_)
    for (int i = 0; i < nlocal; i++) counts[1] += (mask[i] & owner_->groupbit) ? 1.0 : 0.0;
  comm_ = Comm::ACTIVE;
  comm->forward_comm(owner_, 2);
  MPI_Allreduce(counts, totals, 2, MPI_DOUBLE, MPI_SUM, world);
  active_total_ = totals[0];
  // longrange sync: the kspace solver computes where every particle ends its step
  long_due_ = long_range_ && totals[0] == totals[1];
  updates_ += active_total_;
  steps_ += 1.0;
  pair->set_active(active_.data(), records_pairs(), pair_kicks_);
}

void IndividualSteps::final_kick(bool evolve_u, PairSPHAstro *pair)
{
  pair_impulses(pair, true, true);
  const double t = tick();
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  double **v = atom->v;
  double **f = atom->f;
  double *u = atom->dvector[state_.u];
  double *dudt = atom->dvector[state_.dudt];
  const double *begin = atom->dvector[idx_.begin];
  const double *end = atom->dvector[idx_.end];
  double **accel = atom->darray[idx_.accel];
  double **accel_other = atom->darray[idx_.accel_other];
  double **lead = atom->darray[idx_.pair_lead];
  double *dudt_kept = atom->dvector[idx_.dudt];
  double *dudt_other = atom->dvector[idx_.dudt_other];
  double *lead_u = atom->dvector[idx_.lead_u];
  double **pending = atom->darray[idx_.pending];
  double **recent = atom->darray[idx_.recent];
  double *pending_next = atom->dvector[idx_.pending_next];
  if (nlocal == 0) return;
  double *ff = f[0];    // (contiguous, as in kick_drift)
  const double *accelf = accel[0];
  // longrange sync, at a synchronisation point: the closing long-range half kick, over the
  // interval from the earliest begin of a step (that of the longest steps)
  double half_long = 0.0;
  if (long_due_) {
    double first, last;
    interval_ticks(first, last);
    if (std::isfinite(first)) half_long = 0.5 * (ti_next_ - first) * t;
  }
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & owner_->groupbit)) continue;
    const double m = mass(i);
    const bool closes = pair_kicks_ && pending_next[i] > 0.0 && pending_next[i] <= ti_next_;
    if (!active_[i] && !closes && !(pair_kicks_ && touched_mark_[i])) {
      // in no pair of this evaluation and no close of a pair: no kick, its leads stay
      dudt[i] = dudt_kept[i];
      for (int d = 0; d < 3; d++) ff[3 * i + d] = m * accelf[3 * i + d];
      continue;
    }
    // the pairs evaluated now close their interval on both atoms, active or not
    const double *sum = pair_sums(i);
    const double *rate = sum + SUM_KICKS;
    for (int d = 0; d < 3; d++) v[i][d] += sum[d] / m;
    if (evolve_u) u[i] += sum[3];
    const double half = 0.5 * (end[i] - begin[i]) * t;
    if (!active_[i]) {    // other forces of this step are not its: its last evaluation's
      for (int d = 0; d < 3; d++) lead[i][d] -= sum[d] / m;
      lead_u[i] -= sum[3];
      dudt[i] = dudt_kept[i];
      if (closes || (pair_kicks_ && extra_at_[i] >= 0)) {
        // the pairs that close now replace their opening's force in the prediction: the
        // pending slots of this close (and of earlier ones: pairs with a woken partner)
        double old_force[3] = {0.0, 0.0, 0.0}, old_middle[3] = {0.0, 0.0, 0.0};
        double *pend = pending[i];
        double next = 0.0;
        for (int slot = 0; closes && slot < PENDING_SLOTS; slot++, pend += PENDING_VALUES) {
          if (!(pend[0] > 0.0)) continue;
          if (pend[0] > ti_next_) {
            next = next > 0.0 ? std::min(next, pend[0]) : pend[0];
            continue;
          }
          for (int d = 0; d < 3; d++) {
            old_force[d] += pend[2 + d];
            old_middle[d] += pend[1] * t * pend[2 + d];
          }
          std::fill_n(pend, PENDING_VALUES, 0.0);
        }
        if (closes) pending_next[i] = next;
        const double *middle = extra_sums(i);
        for (int d = 0; d < 3; d++) {
          recent[i][d] += (rate[d] - old_force[d]) / m;
          recent[i][3 + d] += (middle[d] - old_middle[d]) / m;
        }
      }
      for (int d = 0; d < 3; d++) f[i][d] = m * accel[i][d];
    } else {
      if (pair_kicks_) {    // its own evaluation: nothing pending, no recent forces
        if (pending_next[i] > 0.0) std::fill_n(pending[i], PENDING_SLOTS * PENDING_VALUES, 0.0);
        pending_next[i] = 0.0;
        std::fill_n(recent[i], RECENT_VALUES, 0.0);
      }
      // (longrange sync: f holds a_long only at a synchronisation point, where all are active)
      if (long_due_) {
        const double *along = long_range_acceleration(i);
        for (int d = 0; d < 3; d++) {
          accel[i][d] = f[i][d] / m - along[d];
          accel_other[i][d] = (f[i][d] - rate[d]) / m - along[d];
          v[i][d] += half * accel_other[i][d] + half_long * along[d];
        }
      } else {
        for (int d = 0; d < 3; d++) {
          accel[i][d] = f[i][d] / m;
          accel_other[i][d] = (f[i][d] - rate[d]) / m;
          v[i][d] += half * accel_other[i][d];
        }
      }
      dudt_kept[i] = dudt[i];
      dudt_other[i] = dudt[i] - rate[3];
      if (evolve_u) u[i] += half * dudt_other[i];
    }
    if (evolve_u && (!(u[i] >= 0.0) || !std::isfinite(u[i])))
      error->one(FLERR,
                 "fix sph/astro: atom {} has specific internal energy u = {} (du/dt = {}) at "
                 "step {} (its own step {}); lower the timestep (courant, force, energy)",
                 atom->tag[i], u[i], dudt[i], update->ntimestep, 2.0 * half);
  }
}

void IndividualSteps::end_of_step(const std::vector<double> &wanted, PairSPHAstro *pair)
{
  ti_now_ = ti_next_;
  hierarchy_step_ = update->ntimestep;
  double first = 0.0, last_end = 0.0;
  if (long_range_ && !long_due_) interval_ticks(first, last_end);
  assign_bins(wanted, false, pair);
  if (long_range_ && !long_due_) long_range_woken(last_end);
  // the pairs evaluated now open their next interval (the impulses only: an active particle's
  // sum_j F_ij is m (accel - accel_other) since final_kick)
  pair_impulses(pair, false, false);
  keep_pending();
  const int *mask = atom->mask;
  double **kick = atom->darray[idx_.kick];
  double **lead = atom->darray[idx_.pair_lead];
  const double *const *accel = atom->darray[idx_.accel];
  const double *const *accel_other = atom->darray[idx_.accel_other];
  const double *begin = atom->dvector[idx_.begin];
  const double *end = atom->dvector[idx_.end];
  double *kick_u = atom->dvector[idx_.kick_u];
  double *lead_u = atom->dvector[idx_.lead_u];
  const double *dudt = atom->dvector[idx_.dudt];
  const double *dudt_other = atom->dvector[idx_.dudt_other];
  // the atoms in a pair of this evaluation, and the active ones (an inactive atom in no pair has
  // no opening kick, and its lead stays)
  auto open = [&](int i) {
    if (!(mask[i] & owner_->groupbit)) return;
    const double m = mass(i);
    const double *sum = pair_sums(i);
    for (int d = 0; d < 3; d++) kick[i][d] = sum[d] / m;
    kick_u[i] = sum[3];
    // lead: sum_j F_ij (t_mid,i - t_mid,ij) / m, all pairs of an active particle anew (its
    // step's middle is half a step ahead; a pair's is w_ij ahead); an inactive one's
    // pairs evaluated now have kicked it by sum_j F_ij w_ij further
    if (active_[i]) {
      const double half = 0.5 * (end[i] - begin[i]) * tick();
      for (int d = 0; d < 3; d++)
        lead[i][d] = half * (accel[i][d] - accel_other[i][d]) - sum[d] / m;
      lead_u[i] = half * (dudt[i] - dudt_other[i]) - sum[3];
    } else {
      for (int d = 0; d < 3; d++) lead[i][d] -= sum[d] / m;
      lead_u[i] -= sum[3];
    }
  };
  kicked_.clear();
  if (pair_kicks_) {
    for (int i : touched_owned_) open(i);
    for (int i : active_list_)
      if (!touched_mark_[i]) open(i);
    kicked_ = touched_owned_;
  }
  kicked_step_ = update->ntimestep;
  advance_to_next();
}

// the new bins of the active particles: their criteria, the grid, the limiter; their next step
void IndividualSteps::assign_bins(const std::vector<double> &wanted, bool fresh, PairSPHAstro *pair)
{
  grow();
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  double *bin = atom->dvector[idx_.bin];
  double *begin = atom->dvector[idx_.begin];
  double *end = atom->dvector[idx_.end];
  // longrange sync: at a synchronisation point no step longer than dt_long
  const double cap = long_due_ ? long_range_step() : INFINITY;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & owner_->groupbit)) {
      bins_[i] = 0.0;
      continue;
    }
    if (!active_[i]) {
      bins_[i] = bin[i];
      continue;
    }
    const int want = TimeBins::bin_for(dt_max_, std::min(wanted[i], cap));
    if (want > TimeBins::MAX_BIN)
      error->one(FLERR,
                 "fix sph/astro steps individual: atom {} needs a timestep {} shorter than the "
                 "shortest step dt_max / 2^{} = {} at step {}",
                 atom->tag[i], wanted[i], TimeBins::MAX_BIN, dt_max_ / TimeBins::cycle(),
                 update->ntimestep);
    bins_[i] = fresh ? want : TimeBins::next_bin(static_cast<int>(bin[i]), want, ti_now_);
  }
  if (levels_ > 0) limit(pair);
  double *woken = atom->dvector[idx_.woken];
  double *end_then = atom->dvector[idx_.end_then];
  for (int i = 0; i < nlocal; i++) {
    if (!active_[i]) continue;
    bin[i] = bins_[i];
    begin[i] = ti_now_;
    end[i] = end_then[i] = ti_now_ + TimeBins::ticks(static_cast<int>(bins_[i]));
    woken[i] = -1.0;
  }
}

// the owned atoms' bins to their ghosts: those that changed since the last send (the active and
// woken ones), or all where the ghosts' copies may not be those atoms' (a reneighbouring, a
// step without a send, a new run)
void IndividualSteps::send_bins()
{
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const bigint step = update->ntimestep;
  const bool changed_only = bins_sent_step_ == step - 1 && neighbor->ago != 0 && bins_nall_ == nall;
  for (int i = 0; i < nlocal; i++) {
    bins_changed_[i] = bins_[i] != bins_sent_[i];
    bins_sent_[i] = bins_[i];
  }
  comm_ = changed_only ? Comm::BINS_CHANGED : Comm::BINS;
  comm->forward_comm(owner_, 3);
  std::fill(bins_changed_.begin(), bins_changed_.begin() + nall, 0);
  bins_sent_step_ = step;
  bins_nall_ = nall;
}

// the timestep limiter over the pairs of this step's evaluation (each has an active particle)
void IndividualSteps::limit(PairSPHAstro *pair)
{
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  send_bins();
  std::fill(required_.begin(), required_.begin() + nall, -1.0);
  // neighbours: the pairs of the force evaluation (inside the kernel support(s); each has an
  // active particle)
  const double levels = levels_;
  pair->evaluated_pairs().for_each([&](int i, int j, bool, int) {
    required_[i] = std::max(required_[i], bins_[j] - levels);
    required_[j] = std::max(required_[j], bins_[i] - levels);
  });
  comm_ = Comm::REQUIRED;    // (the ghosts in a pair only)
  comm->reverse_comm(owner_, 3);

  const double t = tick();
  const int *mask = atom->mask;
  double **v = atom->v;
  double *u = atom->dvector[state_.u];
  double *bin = atom->dvector[idx_.bin];
  double *end = atom->dvector[idx_.end];
  double **accel_other = atom->darray[idx_.accel_other];
  const double *const *accel = atom->darray[idx_.accel];
  double **lead = atom->darray[idx_.pair_lead];
  const double *dudt = atom->dvector[idx_.dudt];
  const double *dudt_other = atom->dvector[idx_.dudt_other];
  double *lead_u = atom->dvector[idx_.lead_u];
  double *woken = atom->dvector[idx_.woken];
  double *end_then = atom->dvector[idx_.end_then];
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & owner_->groupbit) || !(required_[i] > bins_[i])) continue;
    if (active_[i]) {
      bins_[i] = required_[i];
      continue;
    }
    // wake a sleeping particle: its step ends at the next point of the allowed grid
    const double new_end = TimeBins::wake_end(ti_now_, static_cast<int>(required_[i]));
    if (!(new_end < end[i])) continue;
    // its first half kick (forces not of pairs) becomes that of the shortened step (its drift,
    // x_b + v_b tau + a tau^2 / 2, does not depend on the step's length); its pairs with
    // sleeping partners close with the rest of their shortened interval (pair_impulses; those
    // with the waking ones open theirs now)
    const double shift = 0.5 * (new_end - end[i]) * t;
    for (int d = 0; d < 3; d++) v[i][d] += shift * accel_other[i][d];
    // its step's middle moves by shift, its pairs' do not
    if (pair_kicks_) {
      for (int d = 0; d < 3; d++) lead[i][d] += shift * (accel[i][d] - accel_other[i][d]);
      lead_u[i] += shift * (dudt[i] - dudt_other[i]);
    }
    u[i] += shift * dudt_other[i];
    if (woken[i] < 0.0) {    // the end its pairs opened with until now (pair_impulses)
      woken[i] = ti_now_;
      end_then[i] = end[i];
    }
    end[i] = new_end;
    bin[i] = required_[i];
    woken_ += 1.0;
  }
}

// the next LAMMPS step ends where the first particle step ends; at the end of a cycle (all
// particles synchronised) the time line starts again at 0
void IndividualSteps::advance_to_next()
{
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  double *begin = atom->dvector[idx_.begin];
  double *end = atom->dvector[idx_.end];
  const double cycle = TimeBins::cycle();
  if (ti_now_ >= cycle) {
    times_opened_ = times_closed_ = -1;    // the ghosts' times are those of the last cycle
    double *woken = atom->dvector[idx_.woken];
    double *end_then = atom->dvector[idx_.end_then];
    for (int i = 0; i < nlocal; i++) {
      if (!(mask[i] & owner_->groupbit)) continue;
      begin[i] -= cycle;
      end[i] -= cycle;
      end_then[i] -= cycle;
      if (woken[i] >= 0.0) woken[i] -= cycle;
    }
    ti_now_ -= cycle;
    if (pair_kicks_) {
      double **pending = atom->darray[idx_.pending];
      double **recent = atom->darray[idx_.recent];
      const double shift = cycle * tick();
      double *pending_next = atom->dvector[idx_.pending_next];
      for (int i = 0; i < nlocal; i++) {
        double *pend = pending[i];
        for (int slot = 0; slot < PENDING_SLOTS; slot++, pend += PENDING_VALUES)
          if (pend[0] > 0.0) {
            pend[0] -= cycle;
            pend[1] -= cycle;
          }
        if (pending_next[i] > 0.0) pending_next[i] -= cycle;
        for (int d = 0; d < 3; d++) recent[i][3 + d] -= recent[i][d] * shift;
      }
    }
  }
  double ends_local[2] = {INFINITY, INFINITY}, ends[2];    // the first and (-) the last end
  for (int i = 0; i < nlocal; i++)
    if (mask[i] & owner_->groupbit) {
      ends_local[0] = std::min(ends_local[0], end[i]);
      ends_local[1] = std::min(ends_local[1], -end[i]);
    }
  MPI_Allreduce(ends_local, ends, 2, MPI_DOUBLE, MPI_MIN, world);
  ti_next_ = std::isfinite(ends[0]) ? ends[0] : cycle;    // no particles: one top step
  ti_last_ = std::isfinite(ends[1]) ? -ends[1] : cycle;
}

bool IndividualSteps::synchronised() const
{
  return ti_last_ == ti_next_;
}

int IndividualSteps::occupied_bins(std::vector<double> *histogram) const
{
  std::vector<double> local(TimeBins::MAX_BIN + 1, 0.0), all(TimeBins::MAX_BIN + 1);
  const double *bin = atom->dvector[idx_.bin];
  const int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++)
    if (mask[i] & owner_->groupbit) local[static_cast<int>(bin[i])] += 1.0;
  MPI_Allreduce(local.data(), all.data(), TimeBins::MAX_BIN + 1, MPI_DOUBLE, MPI_SUM, world);
  if (histogram) *histogram = all;
  int occupied = 0;
  for (double n : all) occupied += n > 0.0;
  return occupied;
}

double IndividualSteps::woken_total() const
{
  double all;
  MPI_Allreduce(&woken_, &all, 1, MPI_DOUBLE, MPI_SUM, world);
  return all;
}

void IndividualSteps::log_summary() const
{
  if (!started_) return;
  std::vector<double> histogram;
  const int occupied = occupied_bins(&histogram);
  const double woken = woken_total();
  if (comm->me != 0) return;
  const double n = static_cast<double>(atom->natoms);
  std::string bins;
  for (int b = 0; b <= TimeBins::MAX_BIN; b++)
    if (histogram[b] > 0.0) bins += fmt::format(" {}:{:.0f}", b, histogram[b]);
  const std::string limiter = levels_ > 0
      ? fmt::format("{} level{}, factor {}", levels_, levels_ > 1 ? "s" : "", 1 << levels_)
      : "off";
  utils::logmesg(lmp,
                 "fix sph/astro steps individual: {:.0f} particle-updates in {:.0f} steps ({:.1f} "
                 "per particle), {:.0f} woken by the limiter ({}); dt_max {:.6g}, {} occupied "
                 "bins (bin:particles, dt = dt_max/2^bin):{}{}\n",
                 updates_, steps_, n > 0 ? updates_ / n : 0.0, woken, limiter, dt_max_, occupied,
                 bins,
                 long_range_ ? fmt::format("; long range (longrange sync) computed {:.0f} times "
                                           "in this run, split scale {:.6g}",
                                           long_evaluations_, long_split_)
                             : "");
}

std::string IndividualSteps::shortest_step() const
{
  struct {
    double bin;
    int rank;
  } mine = {-1.0, comm->me}, all;
  tagint atom_id = 0;
  const double *bin = atom->dvector[idx_.bin];
  for (int i = 0; i < atom->nlocal; i++)
    if (bin[i] > mine.bin) {
      mine.bin = bin[i];
      atom_id = atom->tag[i];
    }
  MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE_INT, MPI_MAXLOC, world);
  MPI_Bcast(&atom_id, 1, MPI_LMP_TAGINT, all.rank, world);
  return fmt::format("atom {} steps dt_max / 2^{:.0f}", atom_id, all.bin);
}

std::uint64_t IndividualSteps::local_hash() const
{
  StateIndex state;
  if (!find_state(lmp, state)) return 0;
  const double *u = atom->dvector[state.u];
  std::uint64_t hash = 0;
  for (int i = 0; i < atom->nlocal; i++) hash ^= atom_state_hash(atom->tag[i], atom->v[i], u[i]);
  return hash;
}

void IndividualSteps::hand_over(std::uint64_t last_local_hash)
{
  StepIndex steps;
  StateIndex state;
  if (!started_ || !find_step_state(lmp, steps) || !find_state(lmp, state)) return;
  if (local_hash() != last_local_hash) return;
  started_ = false;
  const double *begin = atom->dvector[steps.begin];
  const int *mask = atom->mask;
  double **v = atom->v;
  double **vest = atom->darray[state.vest];
  double *u = atom->dvector[state.u];
  const double *uest = atom->dvector[state.uest];
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & owner_->groupbit) || begin[i] == ti_now_) continue;
    for (int d = 0; d < 3; d++) v[i][d] = vest[i][d];
    u[i] = uest[i];
  }
}

void IndividualSteps::write_restart(std::vector<double> &list) const
{
  list.insert(list.end(),
              {started_ ? 1.0 : 0.0, ti_now_, ti_next_, dt_max_,
               static_cast<double>(hierarchy_step_), updates_, steps_, woken_});
}

int IndividualSteps::read_restart(const double *list)
{
  started_ = list[0] != 0.0;
  ti_now_ = list[1];
  ti_next_ = list[2];
  ti_last_ = -1.0;    // (not kept: the energy is measured again at the next synchronisation)
  dt_max_ = list[3];
  hierarchy_step_ = static_cast<bigint>(list[4]);
  updates_ = list[5];
  steps_ = list[6];
  woken_ = list[7];
  // the particles' step state came back just before, when its fix was created
  Fix *state = modify->get_fix_by_id(STEPS_FIX_ID);
  if (started_ && !(state && state->restart_reset))
    error->all(FLERR,
               "fix sph/astro steps individual: the restart file holds the hierarchy of "
               "individual steps but not the particles' step state of fix {} (style {}); it was "
               "written by another version of SPH-ASTRO",
               STEPS_FIX_ID, state ? state->style : "none");
  return 8;
}

}    // namespace SPHAstro
