/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   A plugin that only makes the SPH-ASTRO plugin's integer-size check
   (plugin/sph_astro_plugin_sizes.h) and registers nothing: built with other
   LAMMPS_SIZES than the loading LAMMPS by unittest/plugin_lammps_sizes.sh,
   where the full plugin is refused by the dynamic linker before its check runs
------------------------------------------------------------------------- */

#include "sph_astro_plugin_sizes.h"

extern "C" void lammpsplugin_init(void *lmp, void *, void *)
{
  LAMMPS_NS::sph_astro_check_integer_sizes(lmp);
}
