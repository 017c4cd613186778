/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

#include "sph_astro_sentinel.h"

#include "fix_sph_astro_h.h"
#include "pair_sph_astro.h"
#include "sph_astro_options.h"
#include "sph_astro_passes.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
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
  dt_reported_ = h_reported_ = isolated_reported_ = fixed_reported_ = images_reported_ = false;
  dt_run_start_ = 0.0;
}

void StabilitySentinel::check_velocities(int groupbit, const char *when)
{
  if (atom->nlocal == 0) return;
  double **v = atom->v;
  const double *vf = v[0];    // (contiguous: one stream, no row pointer per atom)
  const int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++)
    if ((mask[i] & groupbit) &&
        !std::isfinite(vf[3 * i] * vf[3 * i] + vf[3 * i + 1] * vf[3 * i + 1] +
                       vf[3 * i + 2] * vf[3 * i + 2]))
      error->one(FLERR,
                 "fix sph/astro: atom {} has velocity ({}, {}, {}) {} (step {}); velocities must "
                 "be finite, with a finite square (|v| < 1e154)",
                 atom->tag[i], v[i][0], v[i][1], v[i][2], when, update->ntimestep);
}

void StabilitySentinel::check_plane(const char *when)
{
  if (domain->dimension != 2) return;
  double **x = atom->x, **v = atom->v;
  for (int i = 0; i < atom->nlocal; i++)
    if (x[i][2] != 0.0 || v[i][2] != 0.0)
      error->one(FLERR,
                 "fix sph/astro: dimension 2, but atom {} has z = {} (v_z = {}) {} (step {}); "
                 "2d SPH takes the 2d kernel of distances that include z, so every atom must "
                 "lie at z = 0 and move in that plane (set group all z 0.0; no force or "
                 "velocity in z)",
                 atom->tag[i], x[i][2], v[i][2], when, update->ntimestep);
}

void StabilitySentinel::check_speed_outlier(PairSPHAstro *pair, int igroup)
{
  const int groupbit = group->bitmask[igroup];
  if (action_ == Action::OFF || !(collapse_ > 0.0)) return;
  double **v = atom->v;
  const int *mask = atom->mask;
  const double *cs = pair->fields().soundspeed;
  // sum of log(|v| + c_s) over the particles that move or have a sound speed, their count,
  // and the largest |v| (a hot spot's sound speed, as in a blast, is not reported)
  double sums[2] = {0.0, 0.0}, sums_all[2], fastest = 0.0, fastest_all;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double speed = sqrt(v[i][0] * v[i][0] + v[i][1] * v[i][1] + v[i][2] * v[i][2]);
    fastest = MAX(fastest, speed);
    if (!(speed + cs[i] > 0.0)) continue;
    sums[0] += log(speed + cs[i]);
    sums[1] += 1.0;
  }
  MPI_Allreduce(sums, sums_all, 2, MPI_DOUBLE, MPI_SUM, world);
  MPI_Allreduce(&fastest, &fastest_all, 1, MPI_DOUBLE, MPI_MAX, world);
  if (sums_all[1] < 2.0) return;
  const double typical = exp(sums_all[0] / sums_all[1]);
  if (!(fastest_all * collapse_ > typical)) return;
  tagint id = MAXTAGINT, id_all;
  double speed[2] = {0.0, 0.0}, speed_all[2];
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double vi = sqrt(v[i][0] * v[i][0] + v[i][1] * v[i][1] + v[i][2] * v[i][2]);
    if (vi == fastest_all && atom->tag[i] < id) {
      id = atom->tag[i];
      speed[0] = vi;
      speed[1] = cs[i];
    }
  }
  MPI_Allreduce(&id, &id_all, 1, MPI_LMP_TAGINT, MPI_MIN, world);
  if (id != id_all) speed[0] = speed[1] = 0.0;
  MPI_Allreduce(speed, speed_all, 2, MPI_DOUBLE, MPI_SUM, world);
  report(fmt::format("fix sph/astro: atom {} moves at |v| = {:.6g} (sound speed {:.6g}), {:.3g} "
                     "times the typical signal speed |v| + c_s of group {} ({:.6g}, geometric "
                     "mean): it alone shortens the timestep by about that factor; check the "
                     "velocities given by velocity, set or read_data; keyword collapse sets the "
                     "factor (1/collapse)",
                     id_all, speed_all[0], speed_all[1], fastest_all / typical,
                     group->names[igroup], typical));
}

void StabilitySentinel::check_support(PairSPHAstro *pair, int groupbit)
{
  if (images_reported_) return;
  int flag, cols;
  const int index = atom->find_custom("h", flag, cols);
  if (index < 0) return;
  const double *h = atom->dvector[index];
  const int *mask = atom->mask;
  double hmax = 0.0, hmax_all;
  for (int i = 0; i < atom->nlocal; i++)
    if ((mask[i] & groupbit) && h[i] > hmax) hmax = h[i];
  MPI_Allreduce(&hmax, &hmax_all, 1, MPI_DOUBLE, MPI_MAX, world);
  const double support = pair->kernel_radius() * hmax_all;
  const double lengths[3] = {domain->xprd, domain->yprd, domain->zprd};
  int shortest = -1;
  for (int d = 0; d < domain->dimension; d++)
    if (domain->periodicity[d] && support > lengths[d] &&
        (shortest < 0 || lengths[d] < lengths[shortest]))
      shortest = d;
  if (shortest < 0) return;
  images_reported_ = true;
  tagint id = MAXTAGINT, id_all;
  for (int i = 0; i < atom->nlocal; i++)
    if ((mask[i] & groupbit) && h[i] == hmax_all) id = MIN(id, atom->tag[i]);
  MPI_Allreduce(&id, &id_all, 1, MPI_LMP_TAGINT, MPI_MIN, world);
  report(fmt::format("fix sph/astro: at step {} atom {} has h = {:.6g}: its kernel support {:.6g} "
                     "is {:.3g} times the periodic box length {:.6g} in {}, so it meets its own "
                     "periodic images and each neighbour several times; the neighbour search and "
                     "the force cost grow as that ratio to the power {}: lower h (set d_h, or "
                     "hmax of fix sph/astro/h) or enlarge the box",
                     update->ntimestep, id_all, hmax_all, support, support / lengths[shortest],
                     lengths[shortest], "xyz"[shortest], domain -> dimension));
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
  utils::flush_buffers(lmp);    // (on the screen at the step it concerns, not at a later flush)
}

void StabilitySentinel::check_first_step(PairSPHAstro *pair, int groupbit,
                                         const std::function<std::string()> &cause)
{
  if (!(collapse_ > 0.0)) return;
  int flag, cols;
  const int index = atom->find_custom("h", flag, cols);
  if (index < 0) return;
  const double *h = atom->dvector[index];
  const double *cs = pair->fields().soundspeed;
  double **v = atom->v, **f = atom->f;
  const double *rmass = atom->rmass, *mass = atom->mass;
  const int *mask = atom->mask, *type = atom->type;
  // each particle's own time scale: h crossed at its signal speed |v| + c_s, or from rest
  // under its acceleration, sqrt(h / |a|); the shortest over the group (none for a cold gas at
  // rest without forces)
  double shortest = INFINITY;
  tagint id = MAXTAGINT;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit) || !(h[i] > 0.0)) continue;
    const double speed = sqrt(v[i][0] * v[i][0] + v[i][1] * v[i][1] + v[i][2] * v[i][2]);
    const double m = rmass ? rmass[i] : mass[type[i]];
    const double accel = sqrt(f[i][0] * f[i][0] + f[i][1] * f[i][1] + f[i][2] * f[i][2]) / m;
    double own = INFINITY;
    if (speed + cs[i] > 0.0) own = h[i] / (speed + cs[i]);
    if (accel > 0.0) own = MIN(own, sqrt(h[i] / accel));
    if (own < shortest || (own == shortest && atom->tag[i] < id)) {
      shortest = own;
      id = atom->tag[i];
    }
  }
  struct {
    double value;
    int rank;
  } mine = {shortest, comm->me}, least;
  MPI_Allreduce(&mine, &least, 1, MPI_DOUBLE_INT, MPI_MINLOC, world);
  if (!std::isfinite(least.value) || !(update->dt < collapse_ * least.value)) return;
  tagint id_all = id;
  MPI_Bcast(&id_all, 1, MPI_LMP_TAGINT, least.rank, world);
  dt_reported_ = true;
  report(fmt::format(
      "fix sph/astro: the run's first timestep {:.6g} at step {} is {:.3g} times the shortest "
      "time in which a particle crosses its h at its signal speed |v| + c_s or under its "
      "acceleration ({:.6g}, atom {}): the timestep criteria ({}) are driven by a setting, such "
      "as viscosity alpha and beta or conductivity far beyond their usual range (0.1-2), or "
      "an extreme initial state; keyword collapse sets the share",
      update->dt, update->ntimestep, update->dt / least.value, least.value, id_all, cause()));
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

void StabilitySentinel::check(PairSPHAstro *pair, FixSPHAstroH *hfix, int groupbit, bool adaptive,
                              const std::function<std::string()> &cause)
{
  if (action_ == Action::OFF) return;
  // (the run's first timestep: that of its first step, all setup forces in)
  const bool first_step = dt_run_start_ == 0.0;
  if (first_step) {
    dt_run_start_ = update->dt;
    if (adaptive) check_first_step(pair, groupbit, cause);
  }
  if (!dt_reported_ && adaptive && collapse_ > 0.0 && update->dt < collapse_ * dt_run_start_) {
    dt_reported_ = true;
    const std::string why = cause();
    report(fmt::format(
        "fix sph/astro: the timestep {:.6g} at step {} fell below {:g} x the run's first "
        "timestep {:.6g} ({}); a collapse, a blow-up, or a setting (alpha, hfact, initial "
        "state) that drives the criteria down; keyword collapse sets the share",
        update->dt, update->ntimestep, collapse_, dt_run_start_, why));
  }
  if (first_step || hfix) check_support(pair, groupbit);    // (fixed h: h does not change)
  check_particles(pair, hfix, groupbit);
}

void StabilitySentinel::check_particles(PairSPHAstro *pair, FixSPHAstroH *hfix, int groupbit)
{
  if (action_ == Action::OFF) return;
  const bool check_h = !h_reported_ && hfix;
  // particles alone in their kernel support feel no pressure (the counts of the latest
  // density pass; density continuity has none without a pass of its own)
  const bool check_isolated = !isolated_reported_ && !pair->options().density_continuity;
  if (!check_h && !check_isolated) return;
  const GradhStatistics &st = hfix ? hfix->h_statistics() : pair->h_statistics();
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
    if (hfix->mode() == FixSPHAstroH::Mode::ITERATE)
      report(fmt::format(
          "fix sph/astro: at step {} the h iteration of {:.0f} of {:.0f} particles did not "
          "converge (first: {}) and {:.0f} were held at the h cap (first: {}); their h does not "
          "follow rho, so their forces are not the grad-h forces: raise fix sph/astro/h "
          "maxiter, margin or hmax, start from a better h, or separate particles that lie "
          "(nearly) on one point; keyword hshare sets the share",
          update->ntimestep, all[0], all[2], name(first_all[0]), all[1], name(first_all[1])));
    else
      report(fmt::format(
          "fix sph/astro: at step {} {:.0f} of {:.0f} particles were held at the h cap of fix "
          "sph/astro/h dhdt (first: {}); their h stops following dh/dt = (h/d) div v: raise "
          "fix sph/astro/h margin or hmax; keyword hshare sets the share",
          update->ntimestep, all[1], all[2], name(first_all[1])));
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
