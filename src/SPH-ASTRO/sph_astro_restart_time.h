/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The simulation time a run continues. LAMMPS keeps the time as update->atime at step
// update->atimestep, the last step at which the timestep changed (t = atime + (step -
// atimestep) dt), and writes both to restart files. At the start of every run Integrate::init()
// sets atimestep to the current step without advancing atime (integrate.cpp), which is right
// after a run (Verlet::cleanup() advanced it) but not for a file written during a run by the
// restart command while the timestep had stayed the same for some steps (individual steps, a
// step held at dtmax): the continued run would be (step - atimestep) dt behind. And the time
// that Verlet::cleanup() advanced, atime + (step - atimestep) dt, adds up to other bits than
// the pair it came from. Fix sph/astro takes the pair at the end of a run (before cleanup) and
// from the restart file read (its restart record) and puts it back at its init(), which follows
// Integrate::init(), as long as the run starts at that step with that timestep and the time is
// that pair's (as read, or advanced by LAMMPS at that step).

#ifndef LMP_SPH_ASTRO_RESTART_TIME_H
#define LMP_SPH_ASTRO_RESTART_TIME_H

#include "lmptype.h"
#include "update.h"

#include <vector>

namespace SPHAstro {

struct RestartTime {
  static constexpr int VALUES = 4;
  double atime = 0.0, dt = 0.0;
  LAMMPS_NS::bigint atimestep = -1, step = -1;    // step: when the pair was taken (-1: never)

  // the pair now (the end of a run: before Verlet::cleanup() advances it)
  void take(const LAMMPS_NS::Update *update)
  {
    atime = update->atime;
    atimestep = update->atimestep;
    step = update->ntimestep;
    dt = update->dt;
  }
  static void write(const LAMMPS_NS::Update *update, std::vector<double> &list)
  {
    list.insert(list.end(),
                {update->atime, static_cast<double>(update->atimestep),
                 static_cast<double>(update->ntimestep), update->dt});
  }
  int read(const double *list)
  {
    atime = list[0];
    atimestep = static_cast<LAMMPS_NS::bigint>(list[1]);
    step = static_cast<LAMMPS_NS::bigint>(list[2]);
    dt = list[3];
    return VALUES;
  }
  // after Integrate::init(): the pair back where LAMMPS lost or advanced it (the time, the same
  // value, then adds up as in the run continued)
  void restore(LAMMPS_NS::Update *update) const
  {
    if (step < 0 || atimestep == step || update->ntimestep != step || update->dt != dt ||
        update->atimestep != step)
      return;
    const double advanced = atime + (step - atimestep) * dt;    // (Update::update_time())
    if (update->atime != atime && update->atime != advanced) return;
    update->atime = atime;
    update->atimestep = atimestep;
  }
};

}    // namespace SPHAstro

#endif
