/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Fix sph/astro: the timestep, global (the smallest of every particle's criteria, after
// Monaghan 1992, ARA&A 30, 543, sec. 10.3; sph_astro_timestep.h) or individual (the hierarchy
// of sph_astro_individual_steps.h), bounded by dtmin, dtmax, tend and the bounds of other
// fixes (TimestepLimiter). The integration: fix_sph_astro.cpp.

#include "fix_sph_astro.h"

#include "pair_sph_astro.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "modify.h"
#include "output.h"
#include "sph_astro_active_set.h"
#include "sph_astro_conduction.h"
#include "sph_astro_individual_steps.h"
#include "sph_astro_options.h"
#include "sph_astro_passes.h"
#include "sph_astro_sentinel.h"
#include "sph_astro_state.h"
#include "sph_astro_timestep.h"
#include "update.h"
#include "utils.h"

#include <cmath>

using namespace LAMMPS_NS;
using namespace SPHAstro;

std::string FixSPHAstro::limits() const
{
  return fmt::format("limited by atom {}: Courant dt {:.6g}, force dt {:.6g}, energy dt {:.6g}, "
                     "conduction dt {:.6g}{}",
                     last_limiting_atom_, last_dt_cv_, last_dt_force_, last_dt_energy_,
                     last_dt_cond_,
                     std::isfinite(last_dt_limiter_)
                         ? fmt::format(", other fixes (sinks) dt {:.6g}", last_dt_limiter_)
                         : std::string());
}

// the timestep criteria of atom i (sph_astro_timestep.h): Courant, force, energy, conduction
// (physical and artificial)
void FixSPHAstro::criteria(int i, double dts[4]) const
{
  const double h = atom->dvector[state_->h][i];
  double **f = atom->f;
  const double m = atom->rmass ? atom->rmass[i] : atom->mass[atom->type[i]];
  double fi[3] = {f[i][0], f[i][1], f[i][2]};
  // longrange sync: between synchronisation points f lacks the long range (its last value)
  if (steps_ && steps_->long_range_split() && !steps_->long_range_due()) {
    const double *along = steps_->long_range_acceleration(i);
    for (int d = 0; d < 3; d++) fi[d] += m * along[d];
  }
  const double a = std::sqrt(fi[0] * fi[0] + fi[1] * fi[1] + fi[2] * fi[2]) / m;
  dts[0] = dt_courant(courant_, h, pair_->courant_signal_speed(i));
  dts[1] = dt_force(force_factor_, h, a);
  dts[2] = evolve_u_ && energy_factor_ > 0.0
      ? dt_energy(energy_factor_, atom->dvector[state_->u][i], atom->dvector[state_->dudt][i])
      : INFINITY;
  dts[3] = INFINITY;
  const double kappa = pair_->options().conduction;    // physical heat conduction, 0: off
  if (kappa > 0.0)
    dts[3] = conduction_timestep(cond_factor_, atom->dvector[state_->rho][i], h, kappa);
  if (pair_->options().artificial_conductivity())
    dts[3] = MIN(dts[3], dt_conductivity(condu_factor_, pair_->conductivity_rate(i)));
}

void FixSPHAstro::next_timestep(bool from_end_of_step)
{
  double dt = update->dt;
  // dt fixed: the criteria only for the sentinel's check that dt is stable
  if (adaptive_ || sentinel_->watches_fixed_step()) {
    const int *mask = atom->mask;
    const int nlocal = atom->nlocal;

    // minimum over particles of each criterion, with the rank of the limiting atom
    struct {
      double value;
      int rank;
    } mine[4] = {{INFINITY, comm->me},
                 {INFINITY, comm->me},
                 {INFINITY, comm->me},
                 {INFINITY, comm->me}},
      all[4];
    tagint limiting[4] = {0, 0, 0, 0};
    for (int i = 0; i < nlocal; i++) {
      if (!(mask[i] & groupbit)) continue;
      double dts[4];
      criteria(i, dts);
      for (int k = 0; k < 4; k++)
        if (dts[k] < mine[k].value) {
          mine[k].value = dts[k];
          limiting[k] = atom->tag[i];
        }
    }
    MPI_Allreduce(mine, all, 4, MPI_DOUBLE_INT, MPI_MINLOC, world);
    last_dt_cv_ = all[0].value;
    last_dt_force_ = all[1].value;
    last_dt_energy_ = all[2].value;
    last_dt_cond_ = all[3].value;
    int which = 0;
    for (int k = 1; k < 4; k++)
      if (all[k].value < all[which].value) which = k;
    const double dtnew = all[which].value;
    last_limiting_atom_ = limiting[which];
    MPI_Bcast(&last_limiting_atom_, 1, MPI_LMP_TAGINT, all[which].rank, world);
    if (!adaptive_)
      sentinel_->check_fixed_step(dt, dtnew, [this]() {
        return limits();
      });
    // with no finite constraint (isolated cold particles) the step stays as it is
    else if (std::isfinite(dtnew))
      dt = dtnew;
    // the bounds of other fixes (fix sph/astro/sink: the sinks' orbits and approach)
    if (adaptive_) {
      last_dt_limiter_ = INFINITY;
      for (TimestepLimiter *limiter : limiters_)
        last_dt_limiter_ = MIN(last_dt_limiter_, limiter->timestep_limit());
      if (last_dt_limiter_ < dt) dt = last_dt_limiter_;
    }
    if (adaptive_ && dtmax_ > 0.0) dt = MIN(dt, dtmax_);
    if (adaptive_ && dtmin_ > 0.0 && dt < dtmin_)
      error->all(FLERR, "fix sph/astro: timestep {} fell below dtmin = {} at step {} ({})", dt,
                 dtmin_, update->ntimestep, limits());
  }
  if (tend_ > 0.0) {
    const double remaining = tend_ - current_time();
    if (remaining > 0.0 && dt >= remaining * (1.0 - 1e-12)) {
      dt = remaining;
      // from end_of_step the new dt is that of the next step, which then reaches tend
      if (from_end_of_step) schedule_output(update->ntimestep + 1);
    }
  }
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    if (adaptive_)
      error->all(FLERR,
                 "fix sph/astro: timestep {} at step {} is not positive and finite ({}); check "
                 "that atom's velocity, force and state",
                 dt, update->ntimestep, limits());
    error->all(FLERR, "fix sph/astro: timestep {} at step {} is not positive and finite", dt,
               update->ntimestep);
  }
  check_time_after(dt);
  set_timestep(dt);
}

void FixSPHAstro::check_time_after(double dt) const
{
  const double now = current_time();
  if (std::isfinite(now + dt)) return;
  error->all(FLERR,
             "fix sph/astro: the simulation time {} plus the next timestep {} is not finite at "
             "step {} (no particle's criteria limit the step; {}): set a smaller dtmax",
             now, dt, update->ntimestep,
             dtmax_ > 0.0 ? fmt::format("dtmax = {}", dtmax_) : std::string("no dtmax is set"));
}

void FixSPHAstro::set_timestep(double dt)
{
  if (dt == update->dt) return;
  // same sequence as fix dt/reset and Input::timestep()
  update->update_time();
  update->dt = dt;
  update->dt_default = 0;
  if (force->pair) force->pair->reset_dt();
  for (auto &ifix : modify->get_fix_list()) ifix->reset_dt();
  output->reset_dt();
}

/* ----------------------------------------------------------------------
   individual timesteps (steps individual): sph_astro_individual_steps.h
------------------------------------------------------------------------- */

// each active particle's step (all: every particle's) from its criteria, at most dtmax
void FixSPHAstro::wanted_steps(bool all)
{
  const int nlocal = atom->nlocal;
  wanted_.assign(nlocal, INFINITY);
  const int *mask = atom->mask;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit) || !(all || steps_->active(i))) continue;
    wanted_[i] = own_timestep(i);
  }
}

double FixSPHAstro::own_timestep(int i) const
{
  double dts[4];
  criteria(i, dts);
  double dt = MIN(MIN(dts[0], dts[1]), MIN(dts[2], dts[3]));
  if (dtmax_ > 0.0) dt = MIN(dt, dtmax_);
  return dt;
}

bool FixSPHAstro::own_step(int i, double &dt) const
{
  if (!steps_) {
    dt = update->dt;
    return true;
  }
  return steps_->own_step(i, dt);
}

bool FixSPHAstro::mid_step(int i) const
{
  return steps_ && steps_->mid_step(i);
}

// LAMMPS' next step: to the next end of a particle step
void FixSPHAstro::next_individual_timestep()
{
  const double dt = steps_->next_dt();
  if (dtmin_ > 0.0 && dt < dtmin_)
    error->all(FLERR,
               "fix sph/astro: timestep {} fell below dtmin = {} at step {} (individual steps: "
               "the shortest particle step)",
               dt, dtmin_, update->ntimestep);
  if (!(dt > 0.0) || !std::isfinite(dt))
    error->all(FLERR, "fix sph/astro: timestep {} at step {} is not positive and finite", dt,
               update->ntimestep);
  check_time_after(dt);
  // thermo at the step that reaches tend (on the time line's grid)
  if (tend_ > 0.0 && current_time() + dt >= tend_ * (1.0 - 1e-12))
    schedule_output(update->ntimestep + 1);
  set_timestep(dt);
}
