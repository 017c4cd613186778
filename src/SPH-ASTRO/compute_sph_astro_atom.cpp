/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: per-atom SPH quantities
------------------------------------------------------------------------- */

// compute ID group sph/astro/atom [rho] [h] [pressure] [cs] [u] [nneigh] [divv] [dudt]
// [omega] [alpha] [bin] [dt] (rho ... dudt, in this order, when none is named; bin: the time
// bin of fix sph/astro steps individual, the particle's step is dt_max / 2^bin; dt: the step
// of the particle's own timestep criteria of fix sph/astro). Pressure, sound speed, neighbour
// count and div v are those of the latest force evaluation of pair sph/astro.

#include "compute_sph_astro_atom.h"

#include "sph_astro_fields.h"
#include "sph_astro_state.h"

#include "atom.h"
#include "error.h"
#include "fix_sph_astro.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "pair_sph_astro.h"
#include "sph_astro_options.h"
#include "update.h"

#include <cstring>

using namespace LAMMPS_NS;

ComputeSPHAstroAtom::ComputeSPHAstroAtom(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg)
{
  state_ = new SPHAstro::StateIndex();
  nmax_ = 0;
  vector_ = nullptr;
  array_ = nullptr;
  pair_ = nullptr;
  fix_ = nullptr;

  static const char *names[] = {"rho",  "h",    "pressure", "cs",    "u",   "nneigh",
                                "divv", "dudt", "omega",    "alpha", "bin", "dt"};
  const int nnames = sizeof(names) / sizeof(names[0]);
  if (narg == 3)    // the state and hydro fields; omega and alpha when named
    for (int k = 0; k <= DUDT; k++) fields_.push_back(static_cast<Field>(k));
  for (int iarg = 3; iarg < narg; iarg++) {
    int k = 0;
    while (k < nnames && strcmp(arg[iarg], names[k]) != 0) k++;
    if (k == nnames)
      error->all(FLERR,
                 "compute sph/astro/atom: unknown field '{}'; allowed: rho, h, pressure, cs, u, "
                 "nneigh, divv, dudt, omega, alpha, bin, dt",
                 arg[iarg]);
    fields_.push_back(static_cast<Field>(k));
  }
  peratom_flag = 1;
  size_peratom_cols = fields_.size() == 1 ? 0 : static_cast<int>(fields_.size());
}

ComputeSPHAstroAtom::~ComputeSPHAstroAtom()
{
  delete state_;
  memory->destroy(vector_);
  memory->destroy(array_);
}

void ComputeSPHAstroAtom::init()
{
  pair_ = dynamic_cast<PairSPHAstro *>(force->pair_match("^sph/astro$", 0, 0));
  if (!pair_) error->all(FLERR, "compute sph/astro/atom requires pair_style sph/astro");
  if (!SPHAstro::find_state(lmp, *state_))
    error->all(FLERR, "compute sph/astro/atom requires fix sph/astro (the per-particle state)");
  steps_ = SPHAstro::StepIndex();
  SPHAstro::find_step_state(lmp, steps_);
  // (the step state stays after a run with individual steps when fix sph/astro is defined
  // again with global steps: its bins are then no particle's)
  const auto integrators = modify->get_fix_by_style("^sph/astro$");
  auto *integrator = integrators.empty() ? nullptr
                                         : dynamic_cast<FixSPHAstro *>(integrators.front());
  for (int field : fields_)
    if (field == BIN && (steps_.bin < 0 || !integrator || !integrator->individual_steps()))
      error->all(FLERR,
                 "compute sph/astro/atom bin: there are no time bins; they belong to fix "
                 "sph/astro steps individual");
  fix_ = nullptr;
  for (int field : fields_)
    if (field == DT) {
      const auto fixes = modify->get_fix_by_style("^sph/astro$");
      if (fixes.empty())
        error->all(FLERR,
                   "compute sph/astro/atom dt: the timestep criteria belong to fix sph/astro, "
                   "which is not defined");
      fix_ = dynamic_cast<FixSPHAstro *>(fixes.front());
    }
}

void ComputeSPHAstroAtom::compute_peratom()
{
  invoked_peratom = update->ntimestep;
  const int nlocal = atom->nlocal;
  if (atom->nmax > nmax_) {
    nmax_ = atom->nmax;
    if (size_peratom_cols == 0) {
      memory->destroy(vector_);
      memory->create(vector_, nmax_, "sph/astro/atom:vector");
      vector_atom = vector_;
    } else {
      memory->destroy(array_);
      memory->create(array_, nmax_, size_peratom_cols, "sph/astro/atom:array");
      array_atom = array_;
    }
  }
  if (!pair_)
    error->all(FLERR, "compute sph/astro/atom {} has not been initialised: run first (run 0)", id);
  if (pair_->computed_step() != update->ntimestep || pair_->computed_nlocal() != nlocal)
    error->all(FLERR,
               "compute sph/astro/atom: pair sph/astro last evaluated step {} with {} local "
               "atoms, not the current step {} with {}; use it during or right after a run",
               pair_->computed_step(), pair_->computed_nlocal(), update->ntimestep, nlocal);
  // omega: 1 unless variable h iterates; alpha: the switch's or the pair's constant
  const SPHAstro::Fields &pair_fields = pair_->fields();
  const double *omega = pair_->omega();
  const double *alpha = pair_->alpha_per_atom();
  // with pair sph/astro density continuity the counts take a neighbour pass: only if asked
  const int *mask = atom->mask;
  bool has_nneigh = false;
  for (int field : fields_) has_nneigh = has_nneigh || field == NNEIGH;
  if (fix_) {
    dt_.resize(nlocal);
    for (int i = 0; i < nlocal; i++) dt_[i] = (mask[i] & groupbit) ? fix_->own_timestep(i) : 0.0;
  }
  const double *columns[12] = {atom->dvector[state_->rho],
                               atom->dvector[state_->h],
                               pair_fields.pressure,
                               pair_fields.soundspeed,
                               atom->dvector[state_->u],
                               has_nneigh ? pair_->neighbour_counts() : nullptr,
                               pair_fields.divv,
                               atom->dvector[state_->dudt],
                               omega,
                               alpha,
                               steps_.bin >= 0 ? atom->dvector[steps_.bin] : nullptr,
                               fix_ ? dt_.data() : nullptr};
  const int nf = static_cast<int>(fields_.size());
  for (int k = 0; k < nf; k++) {
    const double *src = columns[fields_[k]];
    double fill = 0.0;    // value when there is no per-atom source
    if (fields_[k] == OMEGA) fill = 1.0;
    if (fields_[k] == ALPHA) fill = pair_->options().alpha;
    for (int i = 0; i < nlocal; i++) {
      const double value = !(mask[i] & groupbit) ? 0.0 : (src ? src[i] : fill);
      if (size_peratom_cols == 0)
        vector_[i] = value;
      else
        array_[i][k] = value;
    }
  }
}

double ComputeSPHAstroAtom::memory_usage()
{
  return static_cast<double>(nmax_) * fields_.size() * sizeof(double) +
      dt_.capacity() * sizeof(double);
}
