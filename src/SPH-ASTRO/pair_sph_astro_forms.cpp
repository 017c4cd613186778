/* ----------------------------------------------------------------------
   SPH-ASTRO: the force passes of the pair forms of pair sph/astro's options
------------------------------------------------------------------------- */

// symmetrise kernel, pressure geometric and formulation pressure-energy (doc/pair_sph_astro.rst):
// their force passes,
// instantiated here in a translation unit of their own, so that they compile in parallel with
// pair_sph_astro.cpp (which declares them extern)

#include "pair_sph_astro_force.h"

using namespace LAMMPS_NS;

SPH_ASTRO_OPTION_FORMS()
