/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The total energy E = K + U + W of a run with individual timesteps at its synchronisation
// points, the steps at which every particle ends its step (each point of the top bin's grid, and
// of any finer bin's grid where no particle is in a coarser bin).
// There v, u and x are each particle's integrated values; between them a particle inside its
// step enters compute sph/astro/global's sums with its predicted v and u, whose error (of order
// (da/dt) dt_i^2 for a particle's own step dt_i) is not the integrator's. W is LAMMPS'
// potential energy (compute thermo_pe: pair, kspace and fix terms), tallied at a
// synchronisation point because the step before asked for it.

#ifndef LMP_SPH_ASTRO_SYNC_ENERGY_H
#define LMP_SPH_ASTRO_SYNC_ENERGY_H

#include "pointers.h"

#include <cmath>
#include <map>
#include <string>

namespace SPHAstro {
struct EOS;
struct StateIndex;

class SyncEnergy : protected LAMMPS_NS::Pointers {
 public:
  explicit SyncEnergy(LAMMPS_NS::LAMMPS *lmp) : Pointers(lmp) {}

  // a run begins: no synchronisation point measured in it yet (latest() stays the last one's)
  void start_run();
  // have the potential energy tallied at step (the next synchronisation point)
  void request(LAMMPS_NS::bigint step);
  // at a synchronisation point: E and its relative error (E - E0) / |E0|, E0 the energy of the
  // first point, kept in references (the fix's reference energies by compute ID, saved in its
  // restart files) under a key that is no compute ID
  void measure(int groupbit, const EOS &eos, const StateIndex &state,
               std::map<std::string, double> &references);
  // the run's figures in the log (rank 0); dt_max: the top step, which every particle's step
  // divides; steps: LAMMPS steps the run took
  void log_summary(double dt_max, LAMMPS_NS::bigint steps) const;

  // NaN where no point after the one that set E0 was measured (none is a reading of 0)
  double latest() const { return latest_; }
  double largest() const { return largest_; }

 private:
  // E = sum_i m_i (v_i^2 / 2 + e(rho_i, u_i)) + W at this step, the thermal e over the group,
  // the kinetic over all atoms; NaN where the potential energy was not tallied at it
  // (collective)
  double total(int groupbit, const EOS &eos, const StateIndex &state);
  double latest_ = NAN;                      // error at the latest point after the one that set E0
  double largest_ = NAN;                     // largest |error| of this run's points
  LAMMPS_NS::bigint points_ = 0;             // points of this run measured, the one that set E0 too
  LAMMPS_NS::bigint readings_ = 0;           // ... after the one that set E0
  LAMMPS_NS::bigint reference_step_ = -1;    // the step that set E0 (-1: another instance's)
};

}    // namespace SPHAstro

#endif
