/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: long-range self-gravity from LAMMPS' PPPM (periodic boxes)
------------------------------------------------------------------------- */

// kspace_style pppm/sph/astro/gravity ACCURACY: LAMMPS' PPPM (Hockney & Eastwood 1988) with the
// masses as charges and -G in place of the Coulomb prefactor (sph_astro_gravity_kspace.h):
// it supplies -G sum m_i m_j erf(g r_ij)/r_ij over all pairs and periodic images, the
// pair style sph/astro/gravity the softened short-range rest. The k = 0 mode is dropped as in
// every Ewald method, i.e. the mean density is neutralised by a uniform background (the "Jeans
// swindle"); PPPM's energy includes the matching background term -pi (sum m)^2 / (2 g^2 V).

#include "pppm_sph_astro_gravity.h"

#include "sph_astro_gravity_kspace.h"
#include "sph_astro_pair_coeff.h"

#include "domain.h"
#include "error.h"
#include "force.h"

using namespace LAMMPS_NS;
using namespace SPHAstro;

static constexpr const char *STYLE = "kspace_style pppm/sph/astro/gravity";

PPPMSPHAstroGravity::PPPMSPHAstroGravity(LAMMPS *lmp) : PPPM(lmp)
{
  G_ = 0.0;
  warn_nonneutral = 2;    // masses never sum to zero: no warning
  ensure_mass_charge(lmp, STYLE);
}

void PPPMSPHAstroGravity::settings(int narg, char **arg)
{
  check_accuracy(lmp, STYLE, narg, arg);
  PPPM::settings(narg, arg);
}

void PPPMSPHAstroGravity::init()
{
  schedule_ = nullptr;    // fix sph/astro longrange sync sets it at its init, after this
  if (domain->nonperiodic)
    error->all(FLERR,
               "{}: boundary {} is not periodic in x, y and z; PPPM needs boundary p p p (for "
               "open boundaries use kspace_style msm/sph/astro/gravity)",
               STYLE, boundary_string(lmp));
  if (slabflag) error->all(FLERR, "{}: kspace_modify slab is not supported for gravity", STYLE);
  check_hybrid_coeffs(lmp, STYLE);
  G_ = gravity_constant(lmp, STYLE);
  masses_to_charges(lmp);
  {
    // accuracy estimates and g_ewald with a positive prefactor G and the reference force
    ScopedGravityConstants constants(force, G_, gravity_reference_force(lmp, G_));
    PPPM::init();
  }
  qqrd2e = -G_;    // attraction
}

void PPPMSPHAstroGravity::compute(int eflag, int vflag)
{
  // fix sph/astro longrange sync: the forces only where every particle ends its step, kept
  // apart; in between only the energy and virial when asked for (its forces are taken back)
  LongRangeSchedule *split = schedule_;
  const bool energy_only = split && !split->long_range_due();
  if (energy_only && !eflag && !vflag) return;
  // masses may change (per-atom masses, atoms added or lost): refresh q, sum m and sum m^2
  masses_to_charges(lmp);
  qsum_qsq(0);
  q2 = qsqsum * G_;
  if (split) split->long_range_before();
  PPPM::compute(eflag, vflag);
  if (energy_only)
    split->long_range_discard();
  else if (split)
    split->long_range_after(cutoff);
}
