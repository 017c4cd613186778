/* ----------------------------------------------------------------------
   SPH-ASTRO: long-range self-gravity from LAMMPS' MSM (open boundaries)
------------------------------------------------------------------------- */

// kspace_style msm/sph/astro/gravity ACCURACY: LAMMPS' multilevel summation (Hardy 2006; Hardy
// et al. 2009, Parallel Computing 35, 164) with the masses as charges and -G in place of the
// Coulomb prefactor (sph_astro_gravity_kspace.h): it supplies -G sum m_i m_j gamma(r_ij/a)/a
// over all pairs (a = the pair cutoff), the pair style sph/astro/gravity the softened rest.
// LAMMPS' MSM refuses systems whose charges do not sum to zero; for open boundaries the
// multilevel sum is exact for any total mass (the top grid level is summed directly), so the
// gravity variant allows it. Periodic boxes are refused: a periodic self-gravitating system
// needs the neutralising background that only the Ewald/PPPM variant supplies.

#include "msm_sph_astro_gravity.h"

#include "sph_astro_gravity_kspace.h"

#include "domain.h"
#include "error.h"
#include "comm.h"
#include "force.h"

using namespace LAMMPS_NS;
using namespace SPHAstro;

static constexpr const char *STYLE = "kspace_style msm/sph/astro/gravity";

MSMSPHAstroGravity::MSMSPHAstroGravity(LAMMPS *lmp) : MSM(lmp)
{
  warn_nonneutral = 2;    // allow (and do not warn about) a non-zero total mass
  ensure_mass_charge(lmp, STYLE);
}

void MSMSPHAstroGravity::init()
{
  if (domain->xperiodic || domain->yperiodic || domain->zperiodic)
    error->all(FLERR,
               "{}: boundary {} is periodic; MSM gravity needs non-periodic boundaries (f, s "
               "or m) in x, y and z (for periodic boxes use kspace_style pppm/sph/astro/gravity)",
               STYLE, boundary_string(lmp));
  // LAMMPS' MSM (4 Feb 2025, also the stock msm with charges) is wrong with open boundaries
  // when more than 2 MPI ranks lie along one axis of the processor grid: forces against the
  // O(N^2) reference, uniform sphere n 8: RMS error 1.4e-5 on 1, 2 and 4 (1x2x2) ranks,
  // 2.3e-3 on 3 (any of 3x1x1, 1x3x1, 1x1x3) and on 4 as 4x1x1 (doc/kspace_sph_astro_gravity.rst)
  if (comm->procgrid[0] > 2 || comm->procgrid[1] > 2 || comm->procgrid[2] > 2)
    error->all(FLERR,
               "{}: processor grid {}x{}x{} has more than 2 MPI ranks along an axis, where "
               "LAMMPS' MSM with open boundaries gives wrong long-range forces (RMS error "
               "~2e-3 instead of the requested accuracy); use at most 2 ranks per axis "
               "(1, 2, 4 or 8 ranks, e.g. processors 2 2 2) or direct summation",
               STYLE, comm->procgrid[0], comm->procgrid[1], comm->procgrid[2]);
  G_ = gravity_constant(lmp, STYLE);
  masses_to_charges(lmp);
  {
    // accuracy estimates with a positive prefactor G and the reference force
    ScopedGravityConstants constants(force, G_, gravity_reference_force(lmp, G_));
    MSM::init();
  }
  qqrd2e = -G_;    // attraction
}

void MSMSPHAstroGravity::compute(int eflag, int vflag)
{
  masses_to_charges(lmp);
  qsum_qsq(0);
  q2 = qsqsum * G_;
  MSM::compute(eflag, vflag);
}
