/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

#include "sph_astro_sentinel.h"

#include "pair_sph_astro.h"
#include "sph_astro_options.h"
#include "sph_astro_passes.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "fix.h"
#include "group.h"
#include "modify.h"
#include "update.h"
#include "utils.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

namespace SPHAstro {

bool StabilitySentinel::parse(const std::string &key, const char *val)
{
  if (key == "sentinel") {
    if (strcmp(val, "warn") == 0)
      action_ = Action::WARN;
    else if (strcmp(val, "stop") == 0)
      action_ = Action::STOP;
    else if (strcmp(val, "off") == 0)
      action_ = Action::OFF;
    else
      error->all(FLERR, "fix sph/astro: sentinel '{}' is not one of: warn, stop, off", val);
  } else if (key == "collapse") {
    collapse_ = utils::numeric(FLERR, val, false, lmp);
    if (!(collapse_ >= 0.0) || collapse_ >= 1.0)
      error->all(FLERR,
                 "fix sph/astro: collapse = {} must be in [0, 1) (the share of the run's first "
                 "timestep below which the sentinel reports; 0: never)",
                 val);
  } else if (key == "hshare") {
    hshare_ = utils::numeric(FLERR, val, false, lmp);
    if (!(hshare_ >= 0.0) || hshare_ > 1.0)
      error->all(FLERR,
                 "fix sph/astro: hshare = {} must be in [0, 1] (the share of particles failing "
                 "the h iteration, held at the h cap or without neighbours above which the "
                 "sentinel reports)",
                 val);
  } else
    return false;
  return true;
}

void StabilitySentinel::start_run()
{
  dt_reported_ = h_reported_ = isolated_reported_ = fixed_reported_ = false;
  dt_run_start_ = 0.0;
}

void StabilitySentinel::check_velocities(int groupbit, const char *when)
{
  double **v = atom->v;
  const int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++)
    if ((mask[i] & groupbit) &&
        !(std::isfinite(v[i][0]) && std::isfinite(v[i][1]) && std::isfinite(v[i][2])))
      error->one(FLERR,
                 "fix sph/astro: atom {} has velocity ({}, {}, {}) {} (step {}); velocities must "
                 "be finite",
                 atom->tag[i], v[i][0], v[i][1], v[i][2], when, update->ntimestep);
}

// other integrators or timestep setters on the same particles, fix deform with the adaptive
// timestep, an empty group, minimize
void StabilitySentinel::check_setting(Fix *self, bool adaptive)
{
  if (update->whichflag == 2)
    error->all(FLERR,
               "fix sph/astro: minimize is not supported: SPH forces are not the gradient of a "
               "potential energy; relax a state with run and fix viscous, or damp it with a "
               "large artificial viscosity");
  const int groupbit = self->groupbit, igroup = self->igroup;
  for (auto &other : modify->get_fix_list()) {
    if (other == self) continue;
    if (adaptive && utils::strmatch(other->style, "^dt/reset"))
      error->all(FLERR,
                 "fix sph/astro: fix {} ({}) also sets the timestep; fix sph/astro sets it from "
                 "the SPH criteria (use its keywords dtmax, dtmin, or dt fixed)",
                 other->id, other->style);
    if (adaptive && utils::strmatch(other->style, "^deform") && comm->me == 0)
      error->warning(FLERR,
                     "fix sph/astro: fix {} (deform) strains the box by the same amount every "
                     "step, set from the timestep at the run's start, while fix sph/astro "
                     "changes the timestep: the box and the particles' flow disagree; use dt "
                     "fixed",
                     other->id);
    if (other->time_integrate && (group->bitmask[other->igroup] & groupbit) &&
        group->count(igroup) > 0 && comm->me == 0)
      error->warning(FLERR,
                     "fix sph/astro: fix {} ({}) also integrates particles of group {}: they "
                     "are moved twice per step",
                     other->id, other->style, group->names[igroup]);
  }
  if (group->count(igroup) == 0 && comm->me == 0)
    error->warning(FLERR, "fix sph/astro: group {} holds no particles: nothing is integrated",
                   group->names[igroup]);
}

void StabilitySentinel::report(const std::string &message)
{
  if (action_ == Action::STOP) error->all(FLERR, message + " (sentinel stop)");
  if (comm->me == 0) error->warning(FLERR, message);
}

void StabilitySentinel::check_fixed_step(double dt, double stable,
                                         const std::function<std::string()> &cause)
{
  if (!watches_fixed_step() || !(dt > stable)) return;
  fixed_reported_ = true;
  report(fmt::format("fix sph/astro dt fixed: the timestep {:.6g} at step {} is {:.3g} times "
                     "the longest stable step {:.6g} ({}); the run may blow up (negative u, "
                     "density or h): lower the timestep or use dt adaptive",
                     dt, update->ntimestep, dt / stable, stable, cause()));
}

void StabilitySentinel::check(PairSPHAstro *pair, int groupbit, bool adaptive, bool iterate,
                              const std::function<std::string()> &cause)
{
  if (action_ == Action::OFF) return;
  // (the run's first timestep: that of its first step, all setup forces in)
  if (dt_run_start_ == 0.0) dt_run_start_ = update->dt;
  if (!dt_reported_ && adaptive && collapse_ > 0.0 && update->dt < collapse_ * dt_run_start_) {
    dt_reported_ = true;
    const std::string why = cause();
    report(fmt::format(
        "fix sph/astro: the timestep {:.6g} at step {} fell below {:g} x the run's first "
        "timestep {:.6g} ({}); a collapse, a blow-up, or a setting (alpha, hfact, initial "
        "state) that drives the criteria down; keyword collapse sets the share",
        update->dt, update->ntimestep, collapse_, dt_run_start_, why));
  }
  const bool check_h = !h_reported_ && iterate;
  // particles alone in their kernel support feel no pressure (the counts of the latest
  // density pass; density continuity has none without a pass of its own)
  const bool check_isolated = !isolated_reported_ && !pair->options().density_continuity;
  if (!check_h && !check_isolated) return;
  const GradhStatistics &st = pair->h_statistics();
  const tagint none = MAXTAGINT;
  tagint first[3] = {st.first_failure ? st.first_failure : none,
                     st.first_capped ? st.first_capped : none, none},
         first_all[3];
  double counts[5] = {static_cast<double>(st.failures), static_cast<double>(st.capped),
                      static_cast<double>(st.particles), 0.0, 0.0},
         all[5];
  if (check_isolated) {
    const double *nneigh = pair->neighbour_counts();
    const int *mask = atom->mask;
    for (int i = 0; i < atom->nlocal; i++) {
      if (!(mask[i] & groupbit)) continue;
      counts[4] += 1.0;
      if (nneigh[i] > 0.0) continue;
      counts[3] += 1.0;
      first[2] = MIN(first[2], atom->tag[i]);
    }
  }
  MPI_Allreduce(counts, all, 5, MPI_DOUBLE, MPI_SUM, world);
  const bool h_bad = check_h && all[2] > 0.0 && all[0] + all[1] > hshare_ * all[2];
  const bool isolated = check_isolated && all[4] > 0.0 && all[3] > hshare_ * all[4];
  if (!h_bad && !isolated) return;
  MPI_Allreduce(first, first_all, 3, MPI_LMP_TAGINT, MPI_MIN, world);
  auto name = [none](tagint id) {
    return id == none ? std::string("none") : fmt::format("atom {}", id);
  };
  if (h_bad) {
    h_reported_ = true;
    report(fmt::format(
        "fix sph/astro: at step {} the h iteration of {:.0f} of {:.0f} particles did not "
        "converge (first: {}) and {:.0f} were held at the h cap (first: {}); their h does not "
        "follow rho, so their forces are not the grad-h forces: raise fix sph/astro/h maxiter, "
        "margin or hmax, or start from a better h; keyword hshare sets the share",
        update->ntimestep, all[0], all[2], name(first_all[0]), all[1], name(first_all[1])));
  }
  if (isolated) {
    isolated_reported_ = true;
    report(fmt::format(
        "fix sph/astro: at step {} {:.0f} of {:.0f} particles (first: {}) have no neighbour "
        "inside their kernel support: they feel no pressure and do not move with the gas; h is "
        "too small for the particle spacing (raise d_h or use fix sph/astro/h); keyword hshare "
        "sets the share",
        update->ntimestep, all[3], all[4], name(first_all[2])));
  }
}

}    // namespace SPHAstro
