/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

#include "comm_sph_astro.h"

#include "domain.h"

#include <algorithm>
#include <cstring>
#include <new>

using namespace LAMMPS_NS;

// CommBrick's constructor from another Comm (the one comm_style uses) leaves its pointer
// localsendlist unset, and its destructor frees that pointer when it is not null: the object
// is made in zeroed memory (LAMMPS deletes it with delete, which takes memory from new)
template <class BRICK> static BRICK *brick_from(LAMMPS *lmp, Comm *oldcomm)
{
  void *memory = ::operator new(sizeof(BRICK));
  std::memset(memory, 0, sizeof(BRICK));
  return new (memory) BRICK(lmp, oldcomm);
}

CommSPHAstro::CommSPHAstro(LAMMPS *lmp, Comm *oldcomm) : CommBrick(lmp, oldcomm)
{
  localsendlist = nullptr;
}

CommSPHAstro *CommSPHAstro::install(LAMMPS *lmp)
{
  if (auto *own = dynamic_cast<CommSPHAstro *>(lmp->comm)) return own;
  if (lmp->comm->style != Comm::BRICK || !dynamic_cast<CommBrick *>(lmp->comm)) return nullptr;
  Comm *oldcomm = lmp->comm;
  auto *own = brick_from<CommSPHAstro>(lmp, oldcomm);
  lmp->comm = own;
  delete oldcomm;
  return own;
}

void CommSPHAstro::uninstall(LAMMPS *lmp)
{
  if (!dynamic_cast<CommSPHAstro *>(lmp->comm)) return;
  Comm *oldcomm = lmp->comm;
  lmp->comm = brick_from<CommBrick>(lmp, oldcomm);
  delete oldcomm;
}

void CommSPHAstro::setup()
{
  CommBrick::setup();
  for (int &n : narrowed_dim_) n = 0;
  if (!source_ || mode != Comm::SINGLE || triclinic) return;
  double width[3];
  if (!source_->ghost_widths(width)) return;

  // CommBrick's swaps: 2 maxneed[d] per dimension, sends to the lower neighbour (even ineed)
  // take the slab [.., sublo + cut], to the upper one [subhi - cut, ..]; the later swaps of a
  // dimension pass on the ghosts received, with the same bound
  const double *sublo = domain->sublo, *subhi = domain->subhi;
  int iswap = 0;
  for (int dim = 0; dim < 3; dim++) {
    const double w = std::min(width[dim], cutghost[dim]);
    narrowed_dim_[dim] = w < cutghost[dim] ? 1 : 0;
    for (int ineed = 0; ineed < 2 * maxneed[dim]; ineed++, iswap++) {
      if (ineed % 2 == 0)
        slabhi[iswap] = std::min(slabhi[iswap], sublo[dim] + w);
      else
        slablo[iswap] = std::max(slablo[iswap], subhi[dim] - w);
    }
    cutghost[dim] = w;
  }
}

void *CommSPHAstro::extract(const char *name, int &dim)
{
  dim = 1;
  if (strcmp(name, "sph/astro/widths") == 0) return cutghost;
  if (strcmp(name, "sph/astro/narrowed") == 0) return narrowed_dim_;
  return CommBrick::extract(name, dim);
}
