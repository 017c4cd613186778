/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   The check a plugin entry point makes before registering styles: the integer sizes it was
   compiled with (LAMMPS_SMALLBIG, _BIGBIG or _SMALLSMALL, from the LAMMPS it was configured
   against) must be those of the LAMMPS that loads it, as tagint, imageint and bigint are in
   every per-atom array and in the layout of classes. Uses only what keeps its binary
   interface across the sizes: lammps_extract_setting() and Error's formatting call.
------------------------------------------------------------------------- */

#ifndef LMP_SPH_ASTRO_PLUGIN_SIZES_H
#define LMP_SPH_ASTRO_PLUGIN_SIZES_H

#include "error.h"
#include "lammps.h"
#include "library.h"

namespace LAMMPS_NS {

inline void sph_astro_check_integer_sizes(void *lmp)
{
  const int host_tagint = lammps_extract_setting(lmp, "tagint");
  const int host_imageint = lammps_extract_setting(lmp, "imageint");
  const int host_bigint = lammps_extract_setting(lmp, "bigint");
  if ((host_tagint == (int) sizeof(tagint)) && (host_imageint == (int) sizeof(imageint)) &&
      (host_bigint == (int) sizeof(bigint)))
    return;
  ((LAMMPS *) lmp)
      ->error->all(FLERR,
                   "SPH-ASTRO plugin: integer sizes (bytes) tagint {} imageint {} bigint {} "
                   "differ from this LAMMPS' tagint {} imageint {} bigint {}: the plugin was "
                   "built against another LAMMPS (LAMMPS_SIZES); rebuild it against this one",
                   sizeof(tagint), sizeof(imageint), sizeof(bigint), host_tagint, host_imageint,
                   host_bigint);
}

}    // namespace LAMMPS_NS

#endif
