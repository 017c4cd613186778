/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Pair kicks of IndividualSteps (fix sph/astro kicks pair; sph_astro_individual_steps.h): the
// closing and opening impulses of the evaluated pairs, their sums per atom with the ghosts'
// parts, and the pair forces a sleeping particle's prediction waits for.

#include "sph_astro_individual_steps.h"

#include "pair_sph_astro.h"
#include "sph_astro_time_bins.h"

#include "atom.h"
#include "comm.h"
#include "neighbor.h"
#include "update.h"

#include <algorithm>

using namespace LAMMPS_NS;

namespace SPHAstro {

namespace {
  const double NO_PAIR_KICKS[IndividualSteps::EXTRA_STRIDE] = {0.0};    // kicks particle

  // the slot of a pending close time t: the close times a sleeping particle's pairs are
  // waiting for are each the next point after now of a bin's grid
  inline int pending_slot(double t)
  {
    return TimeBins::coarsest_bin(t) % PENDING_SLOTS;
  }
}    // namespace

// the pairs of the latest force evaluation kick both their atoms with the same impulse
// F_ij w_ij (Springel 2010, MNRAS 401, 791, sec. 7: a pair is integrated on the shorter step of
// its two atoms). The pair's interval runs from one time either atom is active to the next.
// Opening, after the new bins (at ti_now_): w_o = (min(end_i, end_j) - t_o) / 2, t_o = ti_now_.
// Closing, at the evaluation (ti_next_): w = (ti_next_ - t_o) - w_o, the rest of the interval,
// with t_o = max(begin_i, begin_j) and w_o from the ends the atoms had at t_o (an atom the
// limiter woke after t_o had d_step_end_then): w = w_o unless a wake shortened the interval.
// The pair's du/dt terms (EvaluatedPairs::heat) are integrated in the same way, each atom's
// its own. Per owned atom (with the ghosts' parts), n = SUM_STRIDE: sums_[n i..n i+2] =
// sum_j F_ij w_ij, [n i+3] = sum_j (du_i/dt)_ij w_ij, with_forces: [n i+4..n i+6] =
// sum_j F_ij, [n i+7] = sum_j (du_i/dt)_ij (nsum_ of them sent: 8 with the forces, else 4).
// An atom that sleeps through the close of a pair's interval also gets (extra_, extra_width_
// values sent): a closing's sum_j F_ij t_mid,ij of the intervals that close, an opening's
// sum_j F_ij per pending slot with the close (its prediction's terms, final_kick, keep_pending).
// The times the opening sent to the ghosts serve the next closing unless atoms moved between
// ranks or were reordered (a reneighbouring) or the time line started a new cycle.
void IndividualSteps::pair_impulses(PairSPHAstro *pair, bool closing, bool with_forces)
{
  if (!pair_kicks_) return;
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  // the ghosts' copies of the times: a closing keeps those of the last opening (no atom's
  // times change in between) unless a reneighbouring, a new cycle or a new run came between;
  // an opening sends the atoms whose times changed since this step's closing
  const bigint step = update->ntimestep;
  if (times_.size() < NTIMES * static_cast<std::size_t>(nall)) times_.resize(NTIMES * nall);
  if (closing) {
    if (times_opened_ != step - 1 || neighbor->ago == 0 || times_nall_ != nall) send_times(false);
    times_closed_ = step;
  } else {
    send_times(times_closed_ == step && times_nall_ == nall);
    times_opened_ = step;
  }
  times_nall_ = nall;
  opening_ = !closing;
  nsum_ = with_forces ? SUM_STRIDE : SUM_KICKS;
  extra_width_ = closing ? 3 : EXTRA_STRIDE;
  // the ghosts' entries are zero between calls; the owned ones of the last call are cleared
  if (sums_.size() < SUM_STRIDE * static_cast<std::size_t>(nall)) {
    sums_.resize(SUM_STRIDE * static_cast<std::size_t>(nall), 0.0);
  }
  if (touched_mark_.size() < static_cast<std::size_t>(nall)) {
    touched_mark_.resize(nall, 0);
    extra_at_.resize(nall, -1);
  }
  for (int i : touched_owned_) {    // (slots: atoms may have moved since)
    std::fill_n(&sums_[SUM_STRIDE * static_cast<std::size_t>(i)], SUM_STRIDE, 0.0);
    touched_mark_[i] = 0;
    extra_at_[i] = -1;
  }
  extra_.clear();
  touched_owned_.clear();
  const double half_tick = 0.5 * tick();
  const EvaluatedPairs &pairs = pair->evaluated_pairs();
  // (those of the force evaluation: no drift since; from the first row, as in pair_loop)
  const double *x = pairs.rows.empty() ? nullptr : atom->x[0];
  const double *heat = pairs.heats ? pairs.heat.data() : nullptr;
  int k = 0;
  for (const EvaluatedPairs::Row &row : pairs.rows) {
    const int i = row.i;
    const double *ti = &times_[NTIMES * i];
    const bool i_sleeps = !active_[i];
    const double xi = x[3 * i], yi = x[3 * i + 1], zi = x[3 * i + 2];
    // impulse and force, then the u kick and du/dt; closing: sum_j F_ij t_mid,ij
    double impulse[SUM_KICKS] = {0.0, 0.0, 0.0, 0.0}, force[SUM_KICKS] = {0.0, 0.0, 0.0, 0.0};
    double middle[3] = {0.0, 0.0, 0.0};
    for (; k < row.end; k++) {
      const int jp = pairs.partner[k], j = jp >= 0 ? jp : ~jp;
      const double fpair = pairs.fpair[k];
      const double f[3] = {(xi - x[3 * j]) * fpair, (yi - x[3 * j + 1]) * fpair,
                           (zi - x[3 * j + 2]) * fpair};
      const double *tj = &times_[NTIMES * j];
      double w, mid = 0.0;
      if (closing) {
        const double opened = std::max(ti[0], tj[0]);
        const double end_i = ti[2] > opened ? ti[3] : ti[1];
        const double end_j = tj[2] > opened ? tj[3] : tj[1];
        const double close = std::min(end_i, end_j);
        w = half_tick * (2.0 * ti_next_ - opened - close);
        mid = half_tick * (opened + close);
        if (i_sleeps)
          for (int d = 0; d < 3; d++) middle[d] += mid * f[d];
      } else {
        // a particle that sleeps through the interval's close keeps the pair's force in the
        // slot of that close (the prediction's term of its next closing)
        const double close = std::min(ti[1], tj[1]);
        w = half_tick * (close - ti_now_);
        if (ti[1] > close) {
          double *slot = extra_of(i) + 4 * pending_slot(close);
          for (int d = 0; d < 3; d++) slot[d] += f[d];
          slot[3] = close;
        }
        if (jp >= 0 && tj[1] > close) {
          double *slot = extra_of(j) + 4 * pending_slot(close);
          for (int d = 0; d < 3; d++) slot[d] -= f[d];
          slot[3] = close;
        }
      }
      for (int d = 0; d < 3; d++) {
        impulse[d] += w * f[d];
        force[d] += f[d];
      }
      // (u: a closing weight below 0, of an interval a wake shortened below what its opening
      // kick assumed, would take back heat at the new rate, which a shock may have raised
      // far above the old one: u takes nothing back)
      const double w_u = std::max(w, 0.0);
      if (heat) {
        impulse[3] += w_u * heat[2 * k];
        force[3] += heat[2 * k];
      }
      if (jp < 0) continue;
      double *sj = &sums_[SUM_STRIDE * j];
      for (int d = 0; d < 3; d++) sj[d] -= w * f[d];
      if (heat) sj[3] += w_u * heat[2 * k + 1];
      if (with_forces) {
        for (int d = 0; d < 3; d++) sj[SUM_KICKS + d] -= f[d];
        if (heat) sj[SUM_KICKS + 3] += heat[2 * k + 1];
      }
      if (closing && !active_[j]) {
        double *ej = extra_of(j);
        for (int d = 0; d < 3; d++) ej[d] -= mid * f[d];
      }
      touch(j, nlocal);
    }
    double *si = &sums_[SUM_STRIDE * i];
    for (int d = 0; d < SUM_KICKS; d++) si[d] += impulse[d];
    if (with_forces)
      for (int d = 0; d < SUM_KICKS; d++) si[SUM_KICKS + d] += force[d];
    if (closing && i_sleeps) {
      double *ei = extra_of(i);
      for (int d = 0; d < 3; d++) ei[d] += middle[d];
    }
    touch(i, nlocal);
  }
  comm_ = Comm::SUMS;
  comm->reverse_comm(owner_, SUM_STRIDE + EXTRA_STRIDE + 3);
  for (int g : touched_) {
    std::fill_n(&sums_[SUM_STRIDE * static_cast<std::size_t>(g)], nsum_, 0.0);
    touched_mark_[g] = 0;
    extra_at_[g] = -1;
  }
  touched_.clear();
}

// after an opening: each owned atom keeps the forces of the pairs whose close it sleeps through,
// by the time of that close (a slot already holding another close, which does not happen
// while the pairs of an atom span at most PENDING_SLOTS bins, adds to it)
void IndividualSteps::keep_pending()
{
  if (!pair_kicks_) return;
  double **pending = atom->darray[idx_.pending];
  double *pending_next = atom->dvector[idx_.pending_next];
  for (int i : touched_owned_) {
    if (extra_at_[i] < 0) continue;
    const double *sum = extra_sums(i);
    double *pend = pending[i];
    for (int slot = 0; slot < PENDING_SLOTS; slot++, sum += 4, pend += PENDING_VALUES) {
      if (!(sum[3] > 0.0)) continue;
      if (!(pend[0] > 0.0)) {
        pend[0] = sum[3];
        pend[1] = 0.5 * (ti_now_ + sum[3]);
      }
      for (int d = 0; d < 3; d++) pend[2 + d] += sum[d];
      if (!(pending_next[i] > 0.0) || pend[0] < pending_next[i]) pending_next[i] = pend[0];
    }
  }
}

double *IndividualSteps::extra_of(int i)
{
  if (extra_at_[i] < 0) {
    extra_at_[i] = static_cast<int>(extra_.size() / EXTRA_STRIDE);
    extra_.resize(extra_.size() + EXTRA_STRIDE, 0.0);
  }
  return &extra_[EXTRA_STRIDE * static_cast<std::size_t>(extra_at_[i])];
}

const double *IndividualSteps::extra_sums(int i) const
{
  return (pair_kicks_ && extra_at_[i] >= 0)
      ? &extra_[EXTRA_STRIDE * static_cast<std::size_t>(extra_at_[i])]
      : NO_PAIR_KICKS;
}

const double *IndividualSteps::pair_sums(int i) const
{
  return (pair_kicks_ && touched_mark_[i]) ? &sums_[SUM_STRIDE * static_cast<std::size_t>(i)]
                                           : NO_PAIR_KICKS;
}

// the owned atoms' times to their ghosts: all, or (changed_only) those that differ from what
// was sent last (times_ holds it for owned atoms)
void IndividualSteps::send_times(bool changed_only)
{
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  if (times_changed_.size() < static_cast<std::size_t>(nall)) times_changed_.resize(nall, 0);
  const double *begin = atom->dvector[idx_.begin];
  const double *end = atom->dvector[idx_.end];
  const double *woken = atom->dvector[idx_.woken];
  const double *end_then = atom->dvector[idx_.end_then];
  for (int i = 0; i < nlocal; i++) {
    double *ti = &times_[NTIMES * i];
    if (changed_only && ti[0] == begin[i] && ti[1] == end[i] && ti[2] == woken[i] &&
        ti[3] == end_then[i])
      continue;
    ti[0] = begin[i];
    ti[1] = end[i];
    ti[2] = woken[i];
    ti[3] = end_then[i];
    if (changed_only) times_changed_[i] = 1;
  }
  comm_ = changed_only ? Comm::TIMES_CHANGED : Comm::TIMES;
  comm->forward_comm(owner_, NTIMES + 2);
  if (changed_only) std::fill(times_changed_.begin(), times_changed_.begin() + nall, 0);
}

}    // namespace SPHAstro
