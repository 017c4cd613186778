/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

#include "sph_astro_fields.h"

#include "memory.h"
#include "sph_astro_reconstruction.h"

namespace SPHAstro {

void Fields::grow(LAMMPS_NS::Memory *memory, int n, const Needs &needs)
{
  if (n <= nmax && (!needs.curl || curlv) && (!needs.signal || vsigmax) &&
      (!needs.pressure_factor || pressure_factor) && (!needs.energy_sum || energy_sum) &&
      (!needs.reconstruction || vgrad) && (!needs.conductivity || condrate) &&
      (!needs.pressure_energy || pe_gradh) && (!needs.conduction || conduct) &&
      (!needs.balsara || balsara) && (!needs.dphidh_sum || dphidh_sum))
    return;
  if (n > nmax) nmax = n;
  auto make = [&](double *&a, bool wanted, const char *name) {
    memory->destroy(a);
    if (wanted) memory->create(a, nmax, name);
  };
  auto make2 = [&](double **&a, bool wanted, int ncol, const char *name) {
    memory->destroy(a);
    if (wanted) memory->create(a, nmax, ncol, name);
  };
  make(pressure, true, "pair:sph/astro:pressure");
  make(soundspeed, true, "pair:sph/astro:soundspeed");
  make(vdotgradw, true, "pair:sph/astro:vdotgradw");
  make(divv, true, "pair:sph/astro:divv");
  make(nneigh, true, "pair:sph/astro:nneigh");
  make(omega, true, "pair:sph/astro:omega");
  make(prho, true, "pair:sph/astro:prho");
  make2(dcurl, needs.curl, 4, "pair:sph/astro:dcurl");
  make(curlv, needs.curl, "pair:sph/astro:curlv");
  make(balsara, needs.balsara, "pair:sph/astro:balsara");
  make(vsigmax, needs.signal, "pair:sph/astro:vsigmax");
  make2(vgsum, needs.reconstruction, VGRAD_SUMS, "pair:sph/astro:vgsum");
  make2(vgrad, needs.reconstruction, VGRAD_DATA, "pair:sph/astro:vgrad");
  make(condrate, needs.conductivity, "pair:sph/astro:condrate");
  make(pe_gradh, needs.pressure_energy, "pair:sph/astro:pe_gradh");
  make(pressure_factor, needs.pressure_factor, "pair:sph/astro:pressure_factor");
  make(energy_sum, needs.energy_sum, "pair:sph/astro:energy_sum");
  make(conduct, needs.conduction, "pair:sph/astro:conduct");
  make(dphidh_sum, needs.dphidh_sum, "pair:sph/astro:dphidh_sum");
}

void Fields::destroy(LAMMPS_NS::Memory *memory)
{
  for (double **a :
       {&pressure, &soundspeed, &vdotgradw, &divv, &nneigh, &omega, &prho, &curlv, &balsara,
        &vsigmax, &condrate, &pe_gradh, &pressure_factor, &energy_sum, &conduct, &dphidh_sum})
    memory->destroy(*a);
  memory->destroy(dcurl);
  memory->destroy(vgsum);
  memory->destroy(vgrad);
  nmax = 0;
}

double Fields::memory_usage() const
{
  int arrays = 7;
  for (const double *a : {curlv, balsara, vsigmax, condrate, pe_gradh, pressure_factor, energy_sum,
                          conduct, dphidh_sum})
    if (a) arrays++;
  if (dcurl) arrays += 4;
  if (vgsum) arrays += VGRAD_SUMS + VGRAD_DATA;
  return static_cast<double>(arrays) * nmax * sizeof(double);
}

}    // namespace SPHAstro
