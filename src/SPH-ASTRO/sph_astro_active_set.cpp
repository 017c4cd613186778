/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The force styles that follow the integrator (sph_astro_active_set.h), found by type among
// the pair style, its hybrid sub-styles and the kspace style.

#include "sph_astro_active_set.h"

#include "force.h"
#include "kspace.h"
#include "lammps.h"
#include "pair.h"
#include "utils.h"

#include <algorithm>

using namespace LAMMPS_NS;

namespace SPHAstro {

namespace {
  template <class Client> std::vector<Client *> clients(LAMMPS *lmp)
  {
    std::vector<Client *> out;
    Force *force = lmp->force;
    std::vector<Pair *> pairs;
    if (force->pair && utils::strmatch(force->pair_style, "^hybrid")) {
      // the n-th sub-style (pair_match returns the only one again for any n when there is one)
      for (int n = 1;; n++) {
        Pair *sub = force->pair_match(".", 0, n);
        if (!sub || std::find(pairs.begin(), pairs.end(), sub) != pairs.end()) break;
        pairs.push_back(sub);
      }
    } else if (force->pair)
      pairs.push_back(force->pair);
    for (Pair *pair : pairs)
      if (auto *c = dynamic_cast<Client *>(pair)) out.push_back(c);
    if (auto *c = dynamic_cast<Client *>(force->kspace)) out.push_back(c);
    return out;
  }
}    // namespace

std::vector<ActiveSetClient *> active_set_clients(LAMMPS *lmp)
{
  return clients<ActiveSetClient>(lmp);
}

std::vector<LongRangeClient *> long_range_clients(LAMMPS *lmp)
{
  return clients<LongRangeClient>(lmp);
}

}    // namespace SPHAstro
