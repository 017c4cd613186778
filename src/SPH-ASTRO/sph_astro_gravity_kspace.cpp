/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: what the gravity kspace styles share
------------------------------------------------------------------------- */

#include "sph_astro_gravity_kspace.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "lammps.h"
#include "modify.h"
#include "pair.h"
#include "utils.h"

#include <cmath>
#include <cstring>
#include <mpi.h>
#include <string>

using namespace LAMMPS_NS;

namespace SPHAstro {

void ensure_mass_charge(LAMMPS *lmp, const char *caller)
{
  if (lmp->atom->q_flag) {
    if (!lmp->modify->get_fix_by_id(GRAVITY_Q_FIX_ID) && lmp->comm->me == 0)
      lmp->error->warning(FLERR,
                          "{}: the atom style's charges q will be overwritten by the masses "
                          "(the gravity solvers use q to hold them)",
                          caller);
    return;
  }
  lmp->modify->add_fix(std::string(GRAVITY_Q_FIX_ID) + " all property/atom q ghost yes");
}

void masses_to_charges(LAMMPS *lmp)
{
  Atom *atom = lmp->atom;
  double *q = atom->q;
  const double *rmass = atom->rmass;
  const double *mass = atom->mass;
  const int *type = atom->type;
  const int nlocal = atom->nlocal;
  if (rmass)
    for (int i = 0; i < nlocal; i++) q[i] = rmass[i];
  else
    for (int i = 0; i < nlocal; i++) q[i] = mass[type[i]];
}

double gravity_constant(LAMMPS *lmp, const char *caller)
{
  Pair *pair = lmp->force->pair;
  int dim = -1;
  auto G = pair ? static_cast<double *>(pair->extract("gravity_G", dim)) : nullptr;
  if (!G)
    lmp->error->all(FLERR,
                    "{} needs pair_style sph/astro/gravity (alone or as a hybrid/overlay "
                    "sub-style) for the short-range part and G",
                    caller);
  return *G;
}

double gravity_reference_force(LAMMPS *lmp, double G)
{
  Atom *atom = lmp->atom;
  double mlocal = 0.0, mtotal = 0.0;
  for (int i = 0; i < atom->nlocal; i++)
    mlocal += atom->rmass ? atom->rmass[i] : atom->mass[atom->type[i]];
  MPI_Allreduce(&mlocal, &mtotal, 1, MPI_DOUBLE, MPI_SUM, lmp->world);
  const double volume = lmp->domain->xprd * lmp->domain->yprd * lmp->domain->zprd;
  if (atom->natoms == 0 || mtotal <= 0.0 || volume <= 0.0) return G;
  return G * mtotal * (mtotal / atom->natoms) / std::pow(volume, 2.0 / 3.0);
}

std::string boundary_string(LAMMPS *lmp)
{
  const char letter[4] = {'p', 'f', 's', 'm'};
  std::string out;
  for (int d = 0; d < 3; d++) {
    if (d) out += ' ';
    const int lo = lmp->domain->boundary[d][0], hi = lmp->domain->boundary[d][1];
    out += letter[lo];
    if (hi != lo) out += letter[hi];
  }
  return out;
}

ScopedGravityConstants::ScopedGravityConstants(Force *force, double G, double fref) :
    force_(force), qqr2e_(force->qqr2e), qqrd2e_(force->qqrd2e), qelectron_(force->qelectron),
    angstrom_(force->angstrom)
{
  force->qqrd2e = G;
  force->qqr2e = fref;    // two_charge_force = qqr2e qelectron^2 / angstrom^2 = F_ref
  force->qelectron = 1.0;
  force->angstrom = 1.0;
}

ScopedGravityConstants::~ScopedGravityConstants()
{
  force_->qqr2e = qqr2e_;
  force_->qqrd2e = qqrd2e_;
  force_->qelectron = qelectron_;
  force_->angstrom = angstrom_;
}

void check_accuracy(LAMMPS *lmp, const char *caller, int narg, char **arg)
{
  if (narg < 1) utils::missing_cmd_args(FLERR, caller, lmp->error);
  const double accuracy = utils::numeric(FLERR, arg[0], false, lmp);
  if (!(accuracy > 0.0))
    lmp->error->all(FLERR,
                    "{}: accuracy {} must be > 0 (the relative error of the gravitational "
                    "forces, e.g. 1e-4)",
                    caller, arg[0]);
}

}    // namespace SPHAstro
