/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

#include "sph_astro_sync_energy.h"

#include "sph_astro_eos.h"
#include "sph_astro_state.h"

#include "atom.h"
#include "comm.h"
#include "compute.h"
#include "modify.h"
#include "update.h"
#include "utils.h"

#include <cmath>

using namespace LAMMPS_NS;

namespace SPHAstro {

namespace {
  // LAMMPS' potential energy compute, which the thermo output creates
  Compute *potential_energy(Modify *modify)
  {
    Compute *pe = modify->get_compute_by_id("thermo_pe");
    return (pe && pe->peflag) ? pe : nullptr;
  }
}    // namespace

void SyncEnergy::start_run()
{
  largest_ = NAN;
  points_ = readings_ = 0;
}

void SyncEnergy::request(bigint step)
{
  Compute *pe = potential_energy(modify);
  if (pe) pe->addstep(step);
}

double SyncEnergy::total(int groupbit, const EOS &eos, const StateIndex &state)
{
  Compute *pe = potential_energy(modify);
  if (!pe || update->eflag_global != update->ntimestep) return NAN;
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  double **v = atom->v;
  const double *rho = atom->dvector[state.rho];
  const double *u = atom->dvector[state.u];
  double local = 0.0;
  // the kinetic energy of every atom (those outside the group, point masses moved by other
  // fixes at every step, too: the potential energy holds their pairs), the thermal energy of
  // the group's gas
  for (int i = 0; i < nlocal; i++) {
    const double m = atom->rmass ? atom->rmass[i] : atom->mass[atom->type[i]];
    const double thermal = (mask[i] & groupbit) ? eos.energy_of(rho[i], u[i]) : 0.0;
    local += m * (0.5 * (v[i][0] * v[i][0] + v[i][1] * v[i][1] + v[i][2] * v[i][2]) + thermal);
  }
  double sum = 0.0;
  MPI_Allreduce(&local, &sum, 1, MPI_DOUBLE, MPI_SUM, world);
  return sum + pe->compute_scalar();
}

void SyncEnergy::measure(int groupbit, const EOS &eos, const StateIndex &state,
                         std::map<std::string, double> &references)
{
  const double energy = total(groupbit, eos, state);
  if (!std::isfinite(energy)) return;
  const auto [reference, set] = references.emplace("(synchronisation points)", energy);
  points_++;
  if (set) {    // this point sets E0: its error is 0 by definition, no reading
    reference_step_ = update->ntimestep;
    return;
  }
  const double e0 = reference->second;
  latest_ = e0 != 0.0 ? (energy - e0) / std::fabs(e0) : energy - e0;
  largest_ = std::isnan(largest_) ? std::fabs(latest_) : std::fmax(largest_, std::fabs(latest_));
  readings_++;
}

void SyncEnergy::log_summary(double dt_max, bigint steps) const
{
  if (comm->me != 0 || (readings_ == 0 && steps == 0)) return;
  if (readings_ > 0)
    utils::logmesg(lmp,
                   "fix sph/astro steps individual: relative energy error at the {} "
                   "synchronisation points of the run: largest |error| {:.6e}, at the last "
                   "{:.6e}\n",
                   points_, largest_, latest_);
  else
    utils::logmesg(lmp,
                   "fix sph/astro steps individual: no synchronisation point in this run after "
                   "the one that set the reference energy{}: the energy error there was not "
                   "measured (fix vector 9 and 10 are NaN; compute sph/astro/global's includes "
                   "the predictions of the particles inside their steps). Every particle ends "
                   "a step at each multiple of dt_max = {:.6g} of the time line; dtmax or tend "
                   "gives more such points\n",
                   reference_step_ >= 0 ? fmt::format(" (step {})", reference_step_) : "", dt_max);
}

}    // namespace SPHAstro
