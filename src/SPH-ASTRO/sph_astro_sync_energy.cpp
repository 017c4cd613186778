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
  largest_ = 0.0;
  points_ = 0;
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
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double m = atom->rmass ? atom->rmass[i] : atom->mass[atom->type[i]];
    local += m *
        (0.5 * (v[i][0] * v[i][0] + v[i][1] * v[i][1] + v[i][2] * v[i][2]) +
         eos.energy_of(rho[i], u[i]));
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
  const double e0 = references.emplace("(synchronisation points)", energy).first->second;
  latest_ = e0 != 0.0 ? (energy - e0) / std::fabs(e0) : energy - e0;
  largest_ = std::fmax(largest_, std::fabs(latest_));
  points_++;
}

void SyncEnergy::log_summary() const
{
  if (comm->me != 0 || points_ == 0) return;
  utils::logmesg(lmp,
                 "fix sph/astro steps individual: relative energy error at the {} "
                 "synchronisation points of the run: largest |error| {:.6e}, at the last {:.6e}\n",
                 points_, largest_, latest_);
}

}    // namespace SPHAstro
