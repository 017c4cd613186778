/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Fix sph/astro: kick-drift-kick leapfrog of x, v and u (Springel 2005, MNRAS 364, 1105) with the predicted v and u the pair style uses for the viscosity and
// the equation of state at the end of the step:
//   v^{n+1/2} = v^n + dt/2 a^n,  x^{n+1} = x^n + dt v^{n+1/2},  v_est = v^{n+1/2} + dt/2 a^n
//   u^{n+1/2} = u^n + dt/2 du^n, u_est = u^{n+1/2} + dt/2 du^n
//   (forces at n+1 from x^{n+1}, v_est, u_est)
//   v^{n+1} = v^{n+1/2} + dt/2 a^{n+1},  u^{n+1} = u^{n+1/2} + dt/2 du^{n+1}
// Adaptive global timestep (after Monaghan 1992, ARA&A 30, 543, sec. 10.3; sph_astro_timestep.h):
//   dt_cv = C h / (c + h|div v| + 1.2 (alpha c + beta h |div v|)),  dt_f = C_f sqrt(h / |a|)
// and, for the ideal gas, dt_u = C_u u / |du/dt| where du/dt < 0 (keeps u positive); with
// physical heat conduction dt_k = C_k rho h^2 / kappa (sph_astro_conduction.h), and with
// artificial conductivity dt_a = C_a / sum_j k_ij, k_ij = m_j alpha_u v_sig |dW/dr|_ij / rho_ij
// (its explicit diffusion rate; sph_astro_pair_terms.h: stable for C_a <= 1).
// The conduction entry of the output vector is the smaller of dt_k and dt_a.
// With pair sph/astro density continuity rho is integrated in the same way as u:
//   rho^{n+1/2} = rho^n + dt/2 drho^n,  rho_est = rho^{n+1/2} + dt/2 drho^n  (forces at n+1)
//   rho^{n+1} = rho^{n+1/2} + dt/2 drho^{n+1},  drho_i/dt = sum_j m_j v_ij . grad_i W_ij
// (Monaghan 1992, eq. 2.12), starting from one density summation at the first force evaluation.
// The timestep selection is in fix_sph_astro_timestep.cpp.

#include "fix_sph_astro.h"

#include "fix_sph_astro_h.h"
#include "pair_sph_astro.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "kspace.h"
#include "memory.h"
#include "modify.h"
#include "neighbor.h"
#include "output.h"
#include "sph_astro_active_set.h"
#include "sph_astro_individual_steps.h"
#include "sph_astro_options.h"
#include "sph_astro_passes.h"
#include "sph_astro_sentinel.h"
#include "sph_astro_shrink_wrap.h"
#include "sph_astro_state.h"
#include "sph_astro_sync_energy.h"
#include "sph_astro_timestep.h"
#include "timer.h"
#include "update.h"
#include "utils.h"

#include <cmath>
#include <cstring>
#include <vector>

using namespace LAMMPS_NS;
using namespace FixConst;
using namespace SPHAstro;

// the reference-energy count of a restart record is raised by these when the shrink-wrap
// padding (3 values), the time (RestartTime), the state of msm/sph/astro/gravity and an
// individual-step block follow
static constexpr int STEP_BLOCK = 1 << 20, PADDING_BLOCK = 1 << 21, TIME_BLOCK = 1 << 22,
                     KSPACE_BLOCK = 1 << 23;

FixSPHAstro::FixSPHAstro(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), state_(new StateIndex()), entropy_index_(new EntropyIndex()),
    continuity_index_(new ContinuityIndex()), sentinel_(new StabilitySentinel(lmp))
{
  bool individual = false;
  std::map<std::string, std::string> given;    // the keywords given, with their last value

  time_integrate = 1;
  restart_global = 1;
  force_reneighbor = 1;    // an atom that left a shrink-wrapped box (post_integrate)
  next_reneighbor = -1;
  create_attribute = 1;    // set_arrays() for created particles
  scalar_flag = 1;         // current dt
  vector_flag = 1;         // [dt_courant, dt_force, dt_energy, dt_conduction]
  size_vector = 4;
  global_freq = 1;
  extscalar = 0;
  extvector = 0;

  int iarg = 3;
  while (iarg < narg) {
    const std::string key = arg[iarg];
    if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix sph/astro " + key, error);
    const char *val = arg[iarg + 1];
    if (key == "courant") {
      courant_ = utils::numeric(FLERR, val, false, lmp);
      if (!(courant_ > 0.0) || courant_ > 1.0)
        error->all(FLERR, "fix sph/astro: courant = {} must be in (0, 1]", val);
    } else if (key == "vsig") {
      if (strcmp(val, "viscosity") != 0 && strcmp(val, "pairs") != 0)
        error->all(FLERR, "fix sph/astro: vsig '{}' is not one of: viscosity, pairs", val);
      courant_pairs_ = strcmp(val, "pairs") == 0;
    } else if (key == "force") {
      force_factor_ = utils::numeric(FLERR, val, false, lmp);
      if (!(force_factor_ > 0.0) || force_factor_ > 1.0)
        error->all(FLERR, "fix sph/astro: force = {} must be in (0, 1]", val);
    } else if (key == "thermal") {
      if (strcmp(val, "energy") == 0)
        entropy_ = false;
      else if (strcmp(val, "entropy") == 0)
        entropy_ = true;
      else
        error->all(FLERR, "fix sph/astro: thermal '{}' is not one of: energy, entropy", val);
    } else if (key == "energy") {
      energy_factor_ = utils::numeric(FLERR, val, false, lmp);
      if (energy_factor_ < 0.0 || energy_factor_ > 1.0)
        error->all(FLERR, "fix sph/astro: energy = {} must be in [0, 1] (0: no u criterion)", val);
    } else if (key == "conduction") {
      cond_factor_ = utils::numeric(FLERR, val, false, lmp);
      if (!(cond_factor_ > 0.0) || cond_factor_ > 1.0)
        error->all(FLERR, "fix sph/astro: conduction = {} must be in (0, 1]", val);
    } else if (key == "conductivity") {
      condu_factor_ = utils::numeric(FLERR, val, false, lmp);
      if (!(condu_factor_ > 0.0) || condu_factor_ > 1.0)
        error->all(FLERR,
                   "fix sph/astro: conductivity = {} must be in (0, 1] (C in dt = C / the "
                   "artificial conductivity's diffusion rate; 1 is the stability limit)",
                   val);
    } else if (key == "xsph") {
      xsph_eps_ = utils::numeric(FLERR, val, false, lmp);
      if (!(xsph_eps_ >= 0.0) || xsph_eps_ > 1.0)
        error->all(FLERR, "fix sph/astro: xsph = {} must be in [0, 1] (0: off; 0.5 is usual)", val);
    } else if (key == "dtmax") {
      dtmax_ = utils::numeric(FLERR, val, false, lmp);
      if (!(dtmax_ > 0.0)) error->all(FLERR, "fix sph/astro: dtmax = {} must be > 0", val);
    } else if (key == "dtmin") {
      dtmin_ = utils::numeric(FLERR, val, false, lmp);
      if (!(dtmin_ > 0.0)) error->all(FLERR, "fix sph/astro: dtmin = {} must be > 0", val);
    } else if (key == "tend") {
      tend_ = utils::numeric(FLERR, val, false, lmp);
      if (!(tend_ > 0.0)) error->all(FLERR, "fix sph/astro: tend = {} must be > 0", val);
    } else if (key == "steps") {
      if (strcmp(val, "global") == 0)
        individual = false;
      else if (strcmp(val, "individual") == 0)
        individual = true;
      else
        error->all(FLERR, "fix sph/astro: steps '{}' is not one of: global, individual", val);
    } else if (key == "limiter") {
      if (strcmp(val, "off") == 0)
        limiter_levels_ = 0;
      else {
        limiter_levels_ = utils::inumeric(FLERR, val, false, lmp);
        if (limiter_levels_ < 1 || limiter_levels_ > 10)
          error->all(FLERR,
                     "fix sph/astro: limiter {} must be off or a number of bins from 1 to 10 (a "
                     "particle's step at most 2^N times its neighbours'; by default 2 with kicks "
                     "pair, 1 with kicks particle)",
                     val);
      }
    } else if (key == "longrange") {
      if (strcmp(val, "every") != 0 && strcmp(val, "sync") != 0)
        error->all(FLERR, "fix sph/astro: longrange '{}' is not one of: every, sync", val);
      long_range_sync_ = strcmp(val, "sync") == 0;
    } else if (key == "longdisplacement") {
      long_displacement_ = utils::numeric(FLERR, val, false, lmp);
      if (!(long_displacement_ > 0.0) || long_displacement_ > 1.0)
        error->all(FLERR,
                   "fix sph/astro: longdisplacement = {} must be in (0, 1] (the largest "
                   "displacement between long-range evaluations, over the solver's split scale)",
                   val);
    } else if (key == "kicks") {
      if (strcmp(val, "particle") != 0 && strcmp(val, "pair") != 0)
        error->all(FLERR, "fix sph/astro: kicks '{}' is not one of: particle, pair", val);
      pair_kicks_ = strcmp(val, "pair") == 0;
    } else if (sentinel_->parse(key, val)) {
      // sentinel, collapse, hshare (sph_astro_sentinel.h)
    } else if (key == "dt") {
      if (strcmp(val, "adaptive") == 0)
        adaptive_ = true;
      else if (strcmp(val, "fixed") == 0)
        adaptive_ = false;
      else
        error->all(FLERR, "fix sph/astro: dt '{}' is not one of: adaptive, fixed", val);
    } else
      error->all(
          FLERR,
          "fix sph/astro: unknown keyword '{}'; allowed: thermal, courant, vsig, force, energy, "
          "conduction, conductivity, xsph, dtmax, dtmin, tend, dt, steps, limiter, "
          "kicks, longrange, longdisplacement, sentinel, collapse, hshare",
          key);
    given[key] = val;
    iarg += 2;
  }
  if (atom->rho_flag || atom->esph_flag)
    error->all(FLERR,
               "fix sph/astro: atom_style sph (LAMMPS' SPH package) has its own density and "
               "energy that SPH-ASTRO would not use; use atom_style atomic (the SPH-ASTRO state "
               "is d_rho, d_h, d_u, ...)");
  if (!atom->tag_enable)
    error->all(FLERR, "fix sph/astro needs atom IDs (atom_modify id yes) to report atoms");
  if (dtmin_ > 0.0 && dtmax_ > 0.0 && dtmin_ > dtmax_)
    error->all(FLERR, "fix sph/astro: dtmin {} is larger than dtmax {}", dtmin_, dtmax_);
  if (long_range_sync_ && !individual)
    error->all(FLERR,
               "fix sph/astro: longrange sync needs steps individual (with global steps every "
               "step is a synchronisation point)");
  IndividualSteps::warn_keywords(lmp, given, individual, long_range_sync_, limiter_levels_);
  if (individual) {
    if (!adaptive_)
      error->all(FLERR,
                 "fix sph/astro: steps individual needs dt adaptive (each particle's step comes "
                 "from its own criteria)");
    if (xsph_eps_ > 0.0)
      error->all(FLERR, "fix sph/astro: xsph is not available with steps individual");
    // a factor 4 by default (Schaller et al. 2024, as SWIFT); particle kicks take 2: a sleeping
    // particle kicked by its own evaluation's force over a step 4x its neighbours' gives Sedov's
    // L1(rho) 5-16 % above the global-step run's (doc/validation.md)
    if (limiter_levels_ < 0) limiter_levels_ = pair_kicks_ ? 2 : 1;
    steps_ = new IndividualSteps(lmp, this, limiter_levels_, pair_kicks_);
    if (long_range_sync_) steps_->split_long_range(long_displacement_, force_factor_);
    comm_forward = 6;     // step begin, end, woken, end_then of changed atoms, and their index
    comm_reverse = 10;    // pair impulses and forces (and u) of the ghosts with pairs, and index
    // [5] active particles this step, [6] occupied bins, [7] particle-updates, [8] woken,
    // [9] relative energy error at the latest synchronisation point, [10] largest of the run
    size_vector = 10;
    sync_energy_ = new SyncEnergy(lmp);
  }
  if (xsph_eps_ > 0.0) {    // per-atom output: the XSPH velocity correction
    peratom_flag = 1;
    size_peratom_cols = 3;
    peratom_freq = 1;
  }
}

FixSPHAstro::~FixSPHAstro()
{
  memory->destroy(xsph_);
  // (the particles inside their steps: to the current time, if unchanged since the last run)
  if (steps_ && steps_local_hash_taken_) steps_->hand_over(steps_local_hash_);
  delete steps_;
  delete sync_energy_;
  delete sentinel_;
  delete state_;
  delete entropy_index_;
  delete continuity_index_;
}

void *FixSPHAstro::extract(const char *name, int &dim)
{
  dim = 0;
  entropy_flag_ = entropy_ ? 1 : 0;
  if (strcmp(name, "entropy") == 0) return &entropy_flag_;
  return nullptr;
}

int FixSPHAstro::setmask()
{
  int mask = INITIAL_INTEGRATE | POST_INTEGRATE | FINAL_INTEGRATE | END_OF_STEP;
  if (xsph_eps_ > 0.0) mask |= POST_FORCE;    // XSPH correction after the forces
  if (steps_) mask |= PRE_FORCE;              // the active particles of a step
  return mask;
}

void FixSPHAstro::post_constructor()
{
  ensure_state(lmp, "fix sph/astro");
  if (entropy_) ensure_entropy_state(lmp, "fix sph/astro thermal entropy");
  // a pair style read from a restart file did not create its state: LAMMPS restores the
  // per-atom values of d_rhoest d_drhodt once the fix exists again
  if (pair_has_continuity()) ensure_continuity_state(lmp, "fix sph/astro");
  if (steps_) ensure_step_state(lmp, "fix sph/astro steps individual");
  if (long_range_sync_) ensure_long_range_state(lmp, "fix sph/astro longrange sync");
}

bool FixSPHAstro::pair_has_continuity() const
{
  auto *pair = dynamic_cast<PairSPHAstro *>(force->pair_match("^sph/astro$", 0, 0));
  return pair && pair->options().density_continuity;
}

void FixSPHAstro::init()
{
  // a grid long-range solver (msm/sph/astro/gravity) in a shrink-wrapped box maps atoms only
  // inside the box, which LAMMPS sets at each reneighbouring
  box_check_ = domain->nonperiodic == 2 && force->kspace != nullptr;
  pair_ = dynamic_cast<PairSPHAstro *>(force->pair_match("^sph/astro$", 0, 0));
  if (!pair_) error->all(FLERR, "fix sph/astro requires pair_style sph/astro");
  // point masses (atoms of types that are not gas of pair sph/astro) have no h or sound speed
  // for the timestep criteria: other fixes move them
  const bigint point_masses = pair_->point_masses_in(groupbit);
  if (point_masses > 0)
    error->all(FLERR,
               "fix sph/astro: group {} holds {} atoms of types that are not SPH gas (not in a "
               "pair_coeff I I of pair_style sph/astro); give fix sph/astro the group of the gas "
               "and move point masses with fix nve",
               group->names[igroup], point_masses);
  if (force->ftm2v != 1.0 || force->mvv2e != 1.0)
    error->all(FLERR,
               "fix sph/astro: units {} mix energy and force units (ftm2v = {}); use units lj, "
               "si, cgs, micro or nano",
               update->unit_style, force->ftm2v);
  if (!find_state(lmp, *state_))
    error->all(FLERR, "fix sph/astro: the per-particle state fix {} is missing", STATE_FIX_ID);
  // the kick-drift-kick steps of this fix are written for run_style verlet (respa would call
  // none of them on the outer levels: nothing would move)
  if (!utils::strmatch(update->integrate_style, "^verlet"))
    error->all(FLERR, "fix sph/astro: run_style {} is not supported; use run_style verlet",
               update->integrate_style);
  pair_->set_courant_pairs(courant_pairs_);
  evolve_u_ = pair_->options().eos.uses_energy();
  if (entropy_) {
    if (pair_->options().eos.type != EOSType::IDEAL)
      error->all(FLERR,
                 "fix sph/astro thermal entropy needs pair_style sph/astro eos ideal (P = A "
                 "rho^gamma)");
    if (!find_entropy_state(lmp, *entropy_index_))
      error->all(FLERR, "fix sph/astro: the entropy state fix {} is missing", ENTROPY_FIX_ID);
  }
  auto hfixes = modify->get_fix_by_style("^sph/astro/h$");
  hfix_ = hfixes.empty() ? nullptr : dynamic_cast<FixSPHAstroH *>(hfixes.front());
  continuity_ = pair_->options().density_continuity;
  if (continuity_ && !find_continuity_state(lmp, *continuity_index_))
    error->all(FLERR,
               "fix sph/astro: pair_style sph/astro density continuity needs the per-atom state "
               "fix {}; it is missing (define pair_style and fix sph/astro again)",
               CONTINUITY_FIX_ID);
  if (modify->get_fix_by_style("^sph/astro$").size() > 1)
    error->all(FLERR,
               "fix sph/astro: only one instance is allowed (it sets the global timestep); use "
               "one fix for all SPH particles");
  sentinel_->check_setting(this, adaptive_);
  restart_time_.restore(update);    // (as Integrate::init() left it: sph_astro_restart_time.h)

  // predictions are kept only when they belong to this step and v and u (and rho) are as the
  // last run left them (a continued or restarted run); after `velocity` or `set` they start
  // anew
  const bool unchanged = state_hash(lmp, *state_, pair_has_continuity()) == state_hash_;
  if (!unchanged) entropy_needs_init_ = true;    // A follows from the new u at the next density
  // the reference energies refer to the state the last run (or the restart file) left: after a
  // change of v or u (velocity, set) they are set anew
  state_changed_ = hash_taken_ ? (unchanged ? 0 : 1) : -1;
  if (state_changed_ == 1 && !reference_energy_.empty()) {
    reference_energy_.clear();
    if (comm->me == 0)
      utils::logmesg(lmp,
                     "fix sph/astro: v or u changed since the last run or restart file (velocity, "
                     "set, ...): the reference energies E0 of compute sph/astro/global and of the "
                     "synchronisation points are set anew\n");
  }
  pair_->schedule_initialisation(entropy_ && entropy_needs_init_,
                                 continuity_ && density_needs_init_);
  if (steps_) {
    steps_->check_options(pair_, entropy_, igroup);
    steps_->init(*state_, unchanged);
  }
  // the force styles below the integrator: which particles are active, when a grid solver
  // computes (their init has reset both)
  active_clients_ = steps_ ? active_set_clients(lmp) : std::vector<ActiveSetClient *>();
  limiters_.clear();
  for (Fix *fix : modify->get_fix_list())
    if (auto *limiter = dynamic_cast<TimestepLimiter *>(fix)) limiters_.push_back(limiter);
  if (long_range_sync_)
    for (LongRangeClient *client : long_range_clients(lmp)) client->set_long_range_schedule(steps_);
  if (predicted_step_ != update->ntimestep || !unchanged) {
    const int nlocal = atom->nlocal;
    double **v = atom->v;
    double **vest = atom->darray[state_->vest];
    const double *u = atom->dvector[state_->u];
    double *uest = atom->dvector[state_->uest];
    for (int i = 0; i < nlocal; i++) {
      vest[i][0] = v[i][0];
      vest[i][1] = v[i][1];
      vest[i][2] = v[i][2];
      uest[i] = u[i];
    }
    if (continuity_) {
      const double *rho = atom->dvector[state_->rho];
      double *rhoest = atom->dvector[continuity_index_->rhoest];
      for (int i = 0; i < nlocal; i++) rhoest[i] = rho[i];
    }
  }
}

void FixSPHAstro::setup(int /*vflag*/)
{
  // the setup's force evaluation has initialised A and rho (pair sph/astro was told at init)
  entropy_needs_init_ = density_needs_init_ = false;
  stopped_at_tend_ = false;
  user_dt_ = update->dt;
  sentinel_->start_run();
  sentinel_->check_velocities(groupbit, "at the start of the run");
  sentinel_->check_plane("at the start of the run");
  sentinel_->check_speed_outlier(pair_, igroup);
  sentinel_->check_particles(pair_, hfix_, groupbit);    // (the setup's density pass)
  if (tend_ > 0.0 && current_time() >= tend_ * (1.0 - 1e-12)) {
    if (comm->me == 0)
      error->warning(FLERR, "fix sph/astro: time {} already at tend {}: the run stops at once",
                     current_time(), tend_);
    stopped_at_tend_ = true;
    timer->force_timeout();
    return;
  }
  if (steps_) {
    // a continued hierarchy goes on with its next step; a new one starts here, and again at
    // step 1, when the setup forces of all fixes are in
    sync_energy_->start_run();
    if (!steps_->continuing()) {
      // a new hierarchy: every particle begins its step here
      sync_energy_->measure(groupbit, pair_->options().eos, *state_, reference_energy_);
      wanted_steps(true);
      steps_->start(wanted_, dtmax_, tend_ > 0.0 ? tend_ - current_time() : 0.0, pair_, false);
      dt_pending_ = true;
    }
    next_individual_timestep();
    return;
  }
  if (xsph_eps_ > 0.0) xsph_correction();    // for the first drift
  // fixes defined after this one add their setup forces later: the first step's dt is taken
  // again at the start of step 1, when all forces are in
  next_timestep();
  dt_pending_ = true;
}

double FixSPHAstro::current_time() const
{
  return update->atime + (update->ntimestep - update->atimestep) * update->dt;
}

void FixSPHAstro::setup_pre_force(int /*vflag*/)
{
  if (!steps_) return;
  steps_->setup_pre_force(pair_);
  tell_active_set();
}

void FixSPHAstro::pre_force(int /*vflag*/)
{
  if (!steps_) return;
  steps_->pre_force(pair_);
  tell_active_set();
}

void FixSPHAstro::tell_active_set()
{
  ActiveSet set;
  set.flags = steps_->active_flags();
  set.groupbit = groupbit;
  for (ActiveSetClient *client : active_clients_) client->set_active_set(set);
}

// an atom outside a shrink-wrapped box with a grid solver (sph_astro_shrink_wrap.h)
void FixSPHAstro::post_integrate()
{
  if (box_check_ && atom_left_shrink_wrapped_box(lmp)) next_reneighbor = update->ntimestep;
}

void FixSPHAstro::initial_integrate(int /*vflag*/)
{
  if (steps_) {
    if (dt_pending_) {    // a new hierarchy: every particle's bin from the setup forces
      dt_pending_ = false;
      // (the time at the start of this step: current_time() is that at its end)
      const double now = current_time() - update->dt;
      wanted_steps(true);
      steps_->start(wanted_, dtmax_, tend_ > 0.0 ? tend_ - now : 0.0, pair_, true);
      next_individual_timestep();
    }
    steps_->kick_drift(hfix_ ? pair_->h_cap() : 0.0, evolve_u_);
    if (hfix_) hfix_->count_capped();
    predicted_step_ = update->ntimestep;
    return;
  }
  if (dt_pending_) {
    dt_pending_ = false;
    next_timestep();
  }
  if (hfix_) hfix_->advance_h(update->dt);
  const double dt = update->dt;
  const double dtf = 0.5 * dt;
  double **x = atom->x;
  double **v = atom->v;
  double **f = atom->f;
  const int *mask = atom->mask;
  const int *type = atom->type;
  const double *rmass = atom->rmass;
  const double *mass = atom->mass;
  double **vest = atom->darray[state_->vest];
  double *u = atom->dvector[state_->u];
  double *uest = atom->dvector[state_->uest];
  const double *dudt = atom->dvector[state_->dudt];
  double *A = entropy_ ? atom->dvector[entropy_index_->A] : nullptr;
  double *Aest = entropy_ ? atom->dvector[entropy_index_->Aest] : nullptr;
  const double *dAdt = entropy_ ? atom->dvector[entropy_index_->dAdt] : nullptr;
  const int nlocal = atom->nlocal;
  double **dv_xsph = xsph_eps_ > 0.0 ? xsph_ : nullptr;    // drift velocity correction
  double *rho = continuity_ ? atom->dvector[state_->rho] : nullptr;
  double *rhoest = continuity_ ? atom->dvector[continuity_index_->rhoest] : nullptr;
  const double *drhodt = continuity_ ? atom->dvector[continuity_index_->drhodt] : nullptr;

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) {
      vest[i][0] = v[i][0];
      vest[i][1] = v[i][1];
      vest[i][2] = v[i][2];
      uest[i] = u[i];
      if (rho) rhoest[i] = rho[i];
      continue;
    }
    const double dtfm = dtf / (rmass ? rmass[i] : mass[type[i]]);
    for (int d = 0; d < 3; d++) {
      v[i][d] += dtfm * f[i][d];
      vest[i][d] = v[i][d] + dtfm * f[i][d];
      x[i][d] += dt * v[i][d];
    }
    if (dv_xsph)    // XSPH: dx/dt = v + eps sum_j m_j / rho_ij (v_j - v_i) W_ij
      for (int d = 0; d < 3; d++) x[i][d] += dt * dv_xsph[i][d];
    if (entropy_) {
      A[i] += dtf * dAdt[i];
      Aest[i] = A[i] + dtf * dAdt[i];
    } else if (evolve_u_) {
      u[i] += dtf * dudt[i];
      uest[i] = u[i] + dtf * dudt[i];
    } else
      uest[i] = u[i];
    if (rho) {    // density continuity: rho like u (Monaghan 1992, eq. 2.12)
      rho[i] += dtf * drhodt[i];
      rhoest[i] = rho[i] + dtf * drhodt[i];
    }
  }
  predicted_step_ = update->ntimestep;
}

void FixSPHAstro::final_integrate()
{
  if (steps_) {
    steps_->final_kick(evolve_u_, pair_);
    return;
  }
  const double dtf = 0.5 * update->dt;
  double **v = atom->v;
  double **f = atom->f;
  const int *mask = atom->mask;
  const int *type = atom->type;
  const double *rmass = atom->rmass;
  const double *mass = atom->mass;
  double *u = atom->dvector[state_->u];
  const double *dudt = atom->dvector[state_->dudt];
  const int nlocal = atom->nlocal;
  double *A = entropy_ ? atom->dvector[entropy_index_->A] : nullptr;
  const double *dAdt = entropy_ ? atom->dvector[entropy_index_->dAdt] : nullptr;
  double *rho = atom->dvector[state_->rho];
  const double *drhodt = continuity_ ? atom->dvector[continuity_index_->drhodt] : nullptr;
  const double gamma = pair_->options().eos.gamma;

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double dtfm = dtf / (rmass ? rmass[i] : mass[type[i]]);
    v[i][0] += dtfm * f[i][0];
    v[i][1] += dtfm * f[i][1];
    v[i][2] += dtfm * f[i][2];
    if (drhodt) {    // density continuity: rho at the end of the step (before u of entropy)
      rho[i] += dtf * drhodt[i];
      if (!(rho[i] > 0.0) || !std::isfinite(rho[i]))
        error->one(FLERR,
                   "fix sph/astro: atom {} has density rho = {} (drho/dt = {}) at step {} with "
                   "pair_style sph/astro density continuity; lower the timestep (courant, force)",
                   atom->tag[i], rho[i], drhodt[i], update->ntimestep);
    }
    if (entropy_) {
      // A and, from it, u = A rho^(gamma-1) / (gamma-1) at the end of the step (Springel & Hernquist 2002)
      A[i] += dtf * dAdt[i];
      if (!(A[i] >= 0.0) || !std::isfinite(A[i]))
        error->one(FLERR,
                   "fix sph/astro: atom {} has entropic function A = {} (dA/dt = {}) at step {}",
                   atom->tag[i], A[i], dAdt[i], update->ntimestep);
      u[i] = A[i] * std::pow(rho[i], gamma - 1.0) / (gamma - 1.0);
    } else if (evolve_u_) {
      u[i] += dtf * dudt[i];
      if (!(u[i] >= 0.0) || !std::isfinite(u[i]))
        error->one(FLERR,
                   "fix sph/astro: atom {} has specific internal energy u = {} (du/dt = {}) at "
                   "step {}; lower the timestep (courant, force) or check the initial state",
                   atom->tag[i], u[i], dudt[i], update->ntimestep);
    }
  }
}

void FixSPHAstro::end_of_step()
{
  sentinel_->check_velocities(groupbit, "after the step");
  sentinel_->check_plane("after the step");
  // (individual steps: the particles that ended their step begin the next one, also at tend,
  // so that the state after the run is that of the time line's current point)
  if (steps_) {
    if (steps_->synchronised())
      sync_energy_->measure(groupbit, pair_->options().eos, *state_, reference_energy_);
    wanted_steps(false);
    steps_->end_of_step(wanted_, pair_);
    if (steps_->synchronised()) sync_energy_->request(update->ntimestep + 1);
  }
  if (tend_ > 0.0 && current_time() >= tend_ * (1.0 - 1e-12)) {
    stopped_at_tend_ = true;
    timer->force_timeout();
    if (comm->me == 0)
      utils::logmesg(lmp, "fix sph/astro: reached tend = {} at step {}\n", tend_,
                     update->ntimestep);
    return;
  }
  if (steps_)
    next_individual_timestep();
  else
    next_timestep(true);
  sentinel_->check(pair_, hfix_, groupbit, adaptive_, [this]() {
    return steps_ ? steps_->shortest_step() : limits();
  });
}

void FixSPHAstro::post_run()
{
  if (steps_) steps_->log_summary();        // the hierarchy's figures and its bins
  if (sync_energy_ && steps_->started())    // its energy at synchronisation points
    sync_energy_->log_summary(steps_->dt_max(), update->nsteps);
  for (ActiveSetClient *client : active_set_clients(lmp)) {
    const std::string line = client->run_summary();    // (collective)
    if (!line.empty() && comm->me == 0) utils::logmesg(lmp, line + "\n");
  }
  // a stop at tend ends this run only; later runs get the user's timeout back
  if (stopped_at_tend_) timer->reset_timeout();
  // a fixed step shortened to land on tend is the user's step again
  if (!adaptive_ && update->dt != user_dt_) set_timestep(user_dt_);
  state_hash_ = state_hash(lmp, *state_, pair_has_continuity());
  hash_taken_ = true;
  if (steps_) {
    steps_local_hash_ = steps_->local_hash();
    steps_local_hash_taken_ = true;
  }
  restart_time_.take(update);    // (a next run continues this time: sph_astro_restart_time.h)
}

// make thermo (and the computes it needs) report the step that reaches tend. All computes
// with timeflag: addstep_compute() would skip those not invoked since the last
// clearstep_compute(), which any fix evaluated every step (fix vector, fix ave/time) calls
void FixSPHAstro::schedule_output(bigint step)
{
  // Output::write() of the current step (after end_of_step) re-schedules thermo at
  // MIN(step + thermo every, laststep): the run's last step is now this one
  if (update->laststep > step) update->laststep = step;
  if (output->next_thermo > step) {
    output->next_thermo = step;
    output->next = MIN(output->next, step);
    // every time-dependent compute, also those not invoked since the last output (e.g. when a
    // dump every step reset their invoked flags): thermo at that step needs the energy tallied
    modify->addstep_compute_all(step);
  }
}

void FixSPHAstro::set_arrays(int i)
{
  clear_state(lmp, i);
}

int FixSPHAstro::pack_forward_comm(int n, int *list, double *buf, int /*pbc_flag*/, int * /*pbc*/)
{
  return steps_ ? steps_->pack_forward_comm(n, list, buf) : 0;
}

void FixSPHAstro::unpack_forward_comm(int n, int first, double *buf)
{
  if (steps_) steps_->unpack_forward_comm(n, first, buf);
}

int FixSPHAstro::pack_reverse_comm(int n, int first, double *buf)
{
  return steps_ ? steps_->pack_reverse_comm(n, first, buf) : 0;
}

void FixSPHAstro::unpack_reverse_comm(int n, int *list, double *buf)
{
  if (steps_) steps_->unpack_reverse_comm(n, list, buf);
}

double FixSPHAstro::compute_scalar()
{
  return update->dt;
}

double FixSPHAstro::compute_vector(int n)
{
  if (n >= 4 && steps_) {
    if (n == 4) return steps_->active_count();
    if (n == 5) return steps_->occupied_bins();
    if (n == 6) return steps_->updates();
    if (n == 7) return steps_->woken_total();
    return n == 8 ? sync_energy_->latest() : sync_energy_->largest();
  }
  const double values[4] = {last_dt_cv_, last_dt_force_, last_dt_energy_, last_dt_cond_};
  return values[n];
}

double FixSPHAstro::reference_energy(const std::string &compute_id, double current)
{
  auto found = reference_energy_.find(compute_id);
  if (found != reference_energy_.end()) return found->second;
  reference_energy_[compute_id] = current;
  return current;
}

// global restart data: predicted step, hash of v and u, and the reference energies as
// (length of ID, ID characters, energy) records, all stored as doubles
void FixSPHAstro::write_restart(FILE *fp)
{
  // a restart file written during a run (restart command) holds the hash of this step; one
  // written between runs that of the last run's end, so that v or u changed since count as
  // changed in the run continued from it too
  const uint64_t hash = (update->whichflag == 0 && hash_taken_)
      ? state_hash_
      : state_hash(lmp, *state_, pair_has_continuity());
  if (comm->me != 0) return;
  auto *solver = dynamic_cast<ContinuationClient *>(force->kspace);
  std::vector<double> list = {static_cast<double>(predicted_step_), static_cast<double>(hash >> 32),
                              static_cast<double>(hash & 0xffffffffULL),
                              static_cast<double>(reference_energy_.size() +
                                                  (steps_ ? STEP_BLOCK : 0) + PADDING_BLOCK +
                                                  TIME_BLOCK + (solver ? KSPACE_BLOCK : 0))};
  for (const auto &[id, energy] : reference_energy_) {
    list.push_back(static_cast<double>(id.size()));
    for (char c : id) list.push_back(static_cast<double>(c));
    list.push_back(energy);
  }
  for (int d = 0; d < 3; d++) list.push_back(DomainPadding::of(domain)[d]);
  RestartTime::write(update, list);
  if (solver) {    // (its length, then its values)
    const std::vector<double> state = solver->continuation_state();
    list.push_back(static_cast<double>(state.size()));
    list.insert(list.end(), state.begin(), state.end());
  }
  if (steps_) steps_->write_restart(list);
  int size = static_cast<int>(list.size() * sizeof(double));
  fwrite(&size, sizeof(int), 1, fp);
  fwrite(list.data(), sizeof(double), list.size(), fp);
}

void FixSPHAstro::restart(char *buf)
{
  entropy_needs_init_ = false;    // A comes back with the restart file
  density_needs_init_ = false;    // so does the integrated rho (density continuity)
  auto *list = reinterpret_cast<double *>(buf);
  int n = 0;
  predicted_step_ = static_cast<bigint>(list[n++]);
  state_hash_ = static_cast<uint64_t>(list[n++]) << 32;
  state_hash_ |= static_cast<uint64_t>(list[n++]);
  hash_taken_ = true;
  const int count = static_cast<int>(list[n++]);
  const int nref = count & (STEP_BLOCK - 1);
  reference_energy_.clear();
  for (int k = 0; k < nref; k++) {
    const int len = static_cast<int>(list[n++]);
    std::string id;
    for (int c = 0; c < len; c++) id += static_cast<char>(list[n++]);
    reference_energy_[id] = list[n++];
  }
  if (count & PADDING_BLOCK) n += restore_shrink_wrap_padding(domain, list + n);
  if (count & TIME_BLOCK) n += restart_time_.read(list + n);
  kspace_state_.clear();
  if (count & KSPACE_BLOCK) {
    const int len = static_cast<int>(list[n++]);
    kspace_state_.assign(list + n, list + n + len);
    n += len;
  }
  // a hierarchy of individual steps continues where it was (if this fix steps individually)
  if ((count & STEP_BLOCK) && steps_) steps_->read_restart(list + n);
}

/* ----------------------------------------------------------------------
   XSPH (keyword xsph EPS; Monaghan 1989, J. Comput. Phys. 82, 1; Monaghan 1992, eq. 4.1):
   particles drift with the smoothed velocity
     dx_i/dt = v_i + dv_i,  dv_i = eps sum_j m_j / rho_ij (v_j - v_i) W(r_ij, h_ij)
   rho_ij = (rho_i + rho_j)/2, h_ij = (h_i + h_j)/2. W_ij is symmetric and v_j - v_i
   antisymmetric, so sum_i m_i dv_i = 0 pair by pair. The velocities are the predicted ones of
   the last force evaluation (ghosts have them from pair sph/astro's communication). v itself
   is unchanged; since x no longer moves with v, the total energy is conserved only
   approximately (doc/fix_sph_astro.rst). Computed after every force evaluation (post_force,
   and setup for the first drift) over the neighbour lists of pair sph/astro.
------------------------------------------------------------------------- */

void FixSPHAstro::post_force(int /*vflag*/)
{
  xsph_correction();
}

void FixSPHAstro::xsph_correction()
{
  if (atom->nmax > xsph_nmax_) {
    xsph_nmax_ = atom->nmax;
    memory->destroy(xsph_);
    memory->create(xsph_, xsph_nmax_, 3, "fix_sph_astro:xsph");
    array_atom = xsph_;
  }
  pair_->xsph_correction(xsph_eps_, xsph_);
}
