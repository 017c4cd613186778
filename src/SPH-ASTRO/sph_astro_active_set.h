/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// What the integrator (fix sph/astro) and the force styles below it tell each other, without
// knowing each other's classes: the particles active in a force evaluation (individual
// timesteps), for a grid long-range solver with `longrange sync` when to compute, and the
// solver's choices that a restart file carries. The gravity styles implement the client
// interfaces; fix sph/astro finds them at init (pair style, its hybrid sub-styles, kspace
// style) and calls them.

#ifndef LMP_SPH_ASTRO_ACTIVE_SET_H
#define LMP_SPH_ASTRO_ACTIVE_SET_H

#include <string>
#include <vector>

namespace LAMMPS_NS {
class LAMMPS;
}

namespace SPHAstro {

// The particles whose step ends with the coming force evaluation: one flag per owned and ghost
// atom (null: all, global steps). Atoms outside the integrator's group (groupbit) are moved by
// other fixes at every step, so they are always active.
struct ActiveSet {
  const char *flags = nullptr;
  int groupbit = 0;

  bool all() const { return flags == nullptr; }
  bool active(int i, const int *mask) const { return !flags || flags[i] || !(mask[i] & groupbit); }
};

// A force style that evaluates the active particles only. Its init() forgets the set (all
// active); fix sph/astro sets it before every force evaluation of a run with individual steps
// (valid until the end of that step).
class ActiveSetClient {
 public:
  virtual void set_active_set(const ActiveSet &set) = 0;
  // one line for the log at the end of a run (empty: none)
  virtual std::string run_summary() { return {}; }

 protected:
  ~ActiveSetClient() = default;
};

// fix sph/astro longrange sync (individual steps): the long-range force of a grid solver
// only where every particle ends its step, integrated on the intervals between
// (sph_astro_individual_steps.h)
class LongRangeSchedule {
 public:
  // does the solver compute its forces in this evaluation
  virtual bool long_range_due() const = 0;
  // around the solver's evaluation: the forces before it, then a_long = (f - those) / m with
  // split scale r_s; or the forces before it back (an evaluation for the energy alone)
  virtual void long_range_before() = 0;
  virtual void long_range_after(double split_scale) = 0;
  virtual void long_range_discard() = 0;

 protected:
  ~LongRangeSchedule() = default;
};

// a grid long-range solver that follows a LongRangeSchedule (null: compute at every step)
class LongRangeClient {
 public:
  virtual void set_long_range_schedule(LongRangeSchedule *schedule) = 0;

 protected:
  ~LongRangeClient() = default;
};

// A solver whose choices at a run's start (MSM: split radius and grid) a run continued from a
// restart file must keep: fix sph/astro writes them into its restart record ...
class ContinuationClient {
 public:
  virtual std::vector<double> continuation_state() const = 0;

 protected:
  ~ContinuationClient() = default;
};

// ... and gives back those of the restart file read (null: none)
class ContinuationStore {
 public:
  virtual const std::vector<double> *restart_continuation() const = 0;

 protected:
  ~ContinuationStore() = default;
};

// a fix that bounds fix sph/astro's global timestep by criteria of its own (fix
// sph/astro/sink: the sinks' orbits and approach); asked at every choice of the step
class TimestepLimiter {
 public:
  // the longest step allowed now (collective: called on all ranks together; +inf: none)
  virtual double timestep_limit() = 0;

 protected:
  ~TimestepLimiter() = default;
};

// the clients among the pair style, its hybrid sub-styles and the kspace style
std::vector<ActiveSetClient *> active_set_clients(LAMMPS_NS::LAMMPS *lmp);
std::vector<LongRangeClient *> long_range_clients(LAMMPS_NS::LAMMPS *lmp);

}    // namespace SPHAstro

#endif
