/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Morris & Monaghan and Cullen & Dehnen viscosity switches

// fix ID group sph/astro/switch morris-monaghan ALPHA_MIN ALPHA_MAX L
// fix ID group sph/astro/switch cullen-dehnen ALPHA_MIN ALPHA_MAX L
//
// Particles start at alpha_max unless d_alpha was set (set group all d_alpha 0.1). After each
// force evaluation alpha_i is advanced over dt with the exact solution of its ODE at
// frozen coefficients (switch_morris_monaghan(), switch_cullen_dehnen() in
// sph_astro_pair_terms.h), which stays between alpha_min and alpha_max for any dt.
// The pair style reads d_alpha_force, the alpha of the last force evaluation, copied from
// d_alpha before each step's force evaluation: the setup force evaluation of a continued run
// (run N + run N, read_restart) then repeats the last step's forces exactly.
// Cullen-Dehnen: d(div v_i)/dt = (div v_i - div v_i of the previous force evaluation) / dt;
// the previous value is stored at setup and after every step, so it migrates with the atom
// and comes back from a restart file.
// Global vector: 1 mean alpha, 2 largest alpha (group).

#include "fix_sph_astro_switch.h"

#include "fix_sph_astro.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "modify.h"
#include "pair_sph_astro.h"
#include "sph_astro_fields.h"
#include "sph_astro_pair_terms.h"
#include "sph_astro_state.h"
#include "update.h"
#include "utils.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

static constexpr const char *ALPHA_FIX_ID = "SPH_ASTRO_ALPHA";
static constexpr const char *DIVV_PREV_FIX_ID = "SPH_ASTRO_DIVV_PREV";
static constexpr const char *ALPHA_FORCE_FIX_ID = "SPH_ASTRO_ALPHA_FORCE";

FixSPHAstroSwitch::FixSPHAstroSwitch(LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg)
{
  form_ = Form::MORRIS_MONAGHAN;
  alpha_min_ = 0.1;
  alpha_max_ = 1.0;
  ell_ = 0.1;
  alpha_index_ = -1;
  needs_curl_ = 0;
  h_index_ = -1;
  pair_ = nullptr;
  integrator_ = nullptr;
  alpha_force_valid_ = false;
  create_attribute = 1;    // set_arrays(): created particles start at alpha_max

  vector_flag = 1;
  size_vector = 2;
  global_freq = 1;
  extvector = 0;

  if (narg < 4) utils::missing_cmd_args(FLERR, "fix sph/astro/switch", error);
  if (strcmp(arg[3], "morris-monaghan") == 0)
    form_ = Form::MORRIS_MONAGHAN;
  else if (strcmp(arg[3], "cullen-dehnen") == 0)
    form_ = Form::CULLEN_DEHNEN;
  else
    error->all(FLERR,
               "fix sph/astro/switch: switch '{}' is not one of: morris-monaghan, cullen-dehnen",
               arg[3]);
  if (narg != 7)
    error->all(FLERR, "fix sph/astro/switch {} takes ALPHA_MIN ALPHA_MAX L (got {} values)", arg[3],
               narg - 4);
  alpha_min_ = utils::numeric(FLERR, arg[4], false, lmp);
  alpha_max_ = utils::numeric(FLERR, arg[5], false, lmp);
  ell_ = utils::numeric(FLERR, arg[6], false, lmp);
  if (alpha_min_ < 0.0 || !(alpha_max_ > alpha_min_))
    error->all(FLERR,
               "fix sph/astro/switch: need 0 <= alpha_min < alpha_max (got alpha_min = {}, "
               "alpha_max = {})",
               arg[4], arg[5]);
  if (!(ell_ > 0.0))
    error->all(FLERR, "fix sph/astro/switch: decay constant L = {} must be > 0", arg[6]);
}

void *FixSPHAstroSwitch::extract(const char *name, int &dim)
{
  dim = 0;
  needs_curl_ = form_ == Form::CULLEN_DEHNEN ? 1 : 0;
  if (strcmp(name, "needs_curl") == 0) return &needs_curl_;
  return nullptr;
}

int FixSPHAstroSwitch::setmask()
{
  return PRE_FORCE | FINAL_INTEGRATE;
}

double *FixSPHAstroSwitch::divv_prev()
{
  int flag, cols;
  const int index = atom->find_custom("divv_prev", flag, cols);
  return index >= 0 ? atom->dvector[index] : nullptr;
}

void FixSPHAstroSwitch::post_constructor()
{
  int flag, cols;
  alpha_index_ = atom->find_custom("alpha", flag, cols);
  if (alpha_index_ < 0) {
    Fix *store =
        modify->add_fix(std::string(ALPHA_FIX_ID) + " all property/atom d_alpha ghost yes");
    alpha_index_ = atom->find_custom("alpha", flag, cols);
    // a new switch starts at alpha_max; after read_restart the stored alpha comes back
    if (!store->restart_reset) {
      double *a = atom->dvector[alpha_index_];
      for (int i = 0; i < atom->nlocal; i++) a[i] = alpha_max_;
    }
  } else if (flag != 1 || cols != 0)
    error->all(FLERR, "fix sph/astro/switch: custom property alpha exists but is not d_alpha");

  if (atom->find_custom("alpha_force", flag, cols) < 0) {
    Fix *store = modify->add_fix(std::string(ALPHA_FORCE_FIX_ID) +
                                 " all property/atom d_alpha_force ghost yes");
    // a restart file brings back the alpha of the last force evaluation; a data file starts a
    // new run (fix_sph_astro_switch.rst), which copies d_alpha at its setup
    alpha_force_valid_ = store->restart_reset != 0;
    store->wd_section = 0;
  } else if (flag != 1 || cols != 0)
    error->all(FLERR,
               "fix sph/astro/switch: custom property alpha_force exists but is not d_alpha_force");

  if (form_ == Form::CULLEN_DEHNEN) {
    if (atom->find_custom("divv_prev", flag, cols) < 0)
      modify->add_fix(std::string(DIVV_PREV_FIX_ID) + " all property/atom d_divv_prev");
    else if (flag != 1 || cols != 0)
      error->all(FLERR,
                 "fix sph/astro/switch: custom property divv_prev exists but is not d_divv_prev");
  }
}

double *FixSPHAstroSwitch::alpha()
{
  int flag, cols;
  alpha_index_ = atom->find_custom("alpha", flag, cols);
  return alpha_index_ >= 0 ? atom->dvector[alpha_index_] : nullptr;
}

double *FixSPHAstroSwitch::alpha_force()
{
  int flag, cols;
  const int index = atom->find_custom("alpha_force", flag, cols);
  return index >= 0 ? atom->dvector[index] : nullptr;
}

// created particles (create_atoms, fix deposit, ...) start at alpha_max
void FixSPHAstroSwitch::set_arrays(int i)
{
  double *a = alpha(), *af = alpha_force();
  if (a) a[i] = alpha_max_;
  if (af) af[i] = alpha_max_;
}

void FixSPHAstroSwitch::init()
{
  pair_ = dynamic_cast<PairSPHAstro *>(force->pair_match("^sph/astro$", 0, 0));
  if (!pair_) error->all(FLERR, "fix sph/astro/switch requires pair_style sph/astro");
  auto integrators = modify->get_fix_by_style("^sph/astro$");
  integrator_ = integrators.empty() ? nullptr : dynamic_cast<FixSPHAstro *>(integrators.front());
  if (!integrator_)
    error->all(FLERR, "fix sph/astro/switch requires fix sph/astro (alpha follows its steps)");
  SPHAstro::StateIndex state;
  if (!SPHAstro::find_state(lmp, state) || modify->get_fix_by_style("^sph/astro$").empty())
    error->all(FLERR, "fix sph/astro/switch requires fix sph/astro");
  h_index_ = state.h;
  if (modify->get_fix_by_style("^sph/astro/switch$").size() > 1)
    error->all(FLERR, "fix sph/astro/switch: only one instance is allowed");

  // values outside [alpha_min, alpha_max] (set by hand, or left in the storage of atoms
  // created later: set their d_alpha) start at alpha_max, before the setup forces use them
  double *a = alpha();
  for (int i = 0; i < atom->nlocal; i++)
    if (!(a[i] >= alpha_min_ && a[i] <= alpha_max_)) a[i] = alpha_max_;
}

// a first run evaluates its setup forces with d_alpha; a continued one with the alpha of the
// last force evaluation, as the step it continues
void FixSPHAstroSwitch::setup_pre_force(int /*vflag*/)
{
  if (alpha_force_valid_) return;
  pre_force(0);
  alpha_force_valid_ = true;
}

void FixSPHAstroSwitch::pre_force(int /*vflag*/)
{
  const double *a = alpha();
  double *af = alpha_force();
  for (int i = 0; i < atom->nlocal; i++) af[i] = a[i];
}

// the div v of the setup force evaluation is the reference for the first step's d(div v)/dt;
// after a restart it equals the stored one (the setup forces repeat the last step's)
void FixSPHAstroSwitch::setup(int /*vflag*/)
{
  if (form_ != Form::CULLEN_DEHNEN) return;
  const double *divv = pair_->fields().divv;
  double *prev = divv_prev();
  for (int i = 0; i < atom->nlocal; i++) prev[i] = divv[i];
}

// alpha over each particle's own step: every particle with global steps, the particles
// evaluated at this step with individual ones (fix sph/astro own_step())
void FixSPHAstroSwitch::final_integrate()
{
  const double *divv = pair_->fields().divv;
  const double *cs = pair_->fields().soundspeed;
  const double *h = atom->dvector[h_index_];
  double *a = alpha();
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  double dt;
  if (form_ == Form::MORRIS_MONAGHAN) {
    for (int i = 0; i < nlocal; i++)
      if ((mask[i] & groupbit) && integrator_->own_step(i, dt))
        a[i] = SPHAstro::switch_morris_monaghan(a[i], divv[i], cs[i], h[i], dt, alpha_min_,
                                                alpha_max_, ell_);
    return;
  }
  const double *curlv = pair_->fields().curlv;
  double *prev = divv_prev();
  if (!curlv || !prev)
    error->all(FLERR, "fix sph/astro/switch cullen-dehnen: curl v or d_divv_prev is missing");
  for (int i = 0; i < nlocal; i++) {
    if (!integrator_->own_step(i, dt)) continue;
    if (mask[i] & groupbit) {
      const double ddivvdt = (divv[i] - prev[i]) / dt;
      a[i] = SPHAstro::switch_cullen_dehnen(a[i], divv[i], ddivvdt, curlv[i], cs[i], h[i], dt,
                                            alpha_min_, alpha_max_, ell_);
    }
    prev[i] = divv[i];
  }
}

double FixSPHAstroSwitch::compute_vector(int n)
{
  const double *a = alpha();
  const int *mask = atom->mask;
  double local[2] = {0.0, 0.0}, count = 0.0, all[2];
  for (int i = 0; i < atom->nlocal; i++)
    if (mask[i] & groupbit) {
      local[0] += a[i];
      local[1] = MAX(local[1], a[i]);
      count += 1.0;
    }
  if (n == 0) {
    double sums[2] = {local[0], count};
    MPI_Allreduce(sums, all, 2, MPI_DOUBLE, MPI_SUM, world);
    return all[1] > 0.0 ? all[0] / all[1] : 0.0;
  }
  MPI_Allreduce(&local[1], &all[0], 1, MPI_DOUBLE, MPI_MAX, world);
  return all[0];
}
