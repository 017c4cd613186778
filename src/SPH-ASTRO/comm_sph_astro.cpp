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
  for (int k = 0; k < 6; k++) {
    width_[k] = cutghost[k / 2];
    narrowed_[k] = 0;
  }
  if (!source_ || mode != Comm::SINGLE || triclinic) return;
  double reach[6], floor = 0.0;
  if (!source_->ghost_reaches(reach, floor)) return;

  // the two ranks of a face take the larger of their reaches: my lower face is my lower
  // neighbour's upper face (a rank alone in a periodic dimension is its own neighbour); the
  // largest over all ranks only where a cutoff spans more than one sub-domain (maxneed is the
  // same on every rank)
  double largest[6];
  if (std::max({maxneed[0], maxneed[1], maxneed[2]}) > 1)
    MPI_Allreduce(reach, largest, 6, MPI_DOUBLE, MPI_MAX, world);
  for (int d = 0; d < 3; d++) {
    double from_lower = 0.0, from_upper = 0.0;
    MPI_Sendrecv(&reach[2 * d + 1], 1, MPI_DOUBLE, procneigh[d][1], 0, &from_lower, 1, MPI_DOUBLE,
                 procneigh[d][0], 0, world, MPI_STATUS_IGNORE);
    MPI_Sendrecv(&reach[2 * d], 1, MPI_DOUBLE, procneigh[d][0], 1, &from_upper, 1, MPI_DOUBLE,
                 procneigh[d][1], 1, world, MPI_STATUS_IGNORE);
    double lo = std::max(reach[2 * d], from_lower), hi = std::max(reach[2 * d + 1], from_upper);
    // a cutoff past the neighbour's sub-domain: the later swaps pass ghosts on across faces
    // further away, whose reaches this rank does not see
    if (maxneed[d] > 1) lo = hi = std::max(largest[2 * d], largest[2 * d + 1]);
    width_[2 * d] = std::min(std::max(lo, floor), cutghost[d]);
    width_[2 * d + 1] = std::min(std::max(hi, floor), cutghost[d]);
  }

  // CommBrick's swaps: 2 maxneed[d] per dimension, sends to the lower neighbour (even ineed)
  // take the slab [.., sublo + cut], to the upper one [subhi - cut, ..]; the later swaps of a
  // dimension pass on the ghosts received, with the same bound
  const double *sublo = domain->sublo, *subhi = domain->subhi;
  int iswap = 0;
  for (int d = 0; d < 3; d++) {
    for (int ineed = 0; ineed < 2 * maxneed[d]; ineed++, iswap++) {
      if (ineed % 2 == 0)
        slabhi[iswap] = std::min(slabhi[iswap], sublo[d] + width_[2 * d]);
      else
        slablo[iswap] = std::max(slablo[iswap], subhi[d] - width_[2 * d + 1]);
    }
    for (int side = 0; side < 2; side++)
      narrowed_[2 * d + side] = width_[2 * d + side] < cutghost[d] ? 1 : 0;
    // (the ghosts' extent, for LAMMPS' bins)
    cutghost[d] = std::max(width_[2 * d], width_[2 * d + 1]);
  }
}

bool CommSPHAstro::narrowed() const
{
  for (int n : narrowed_)
    if (n) return true;
  return false;
}

void *CommSPHAstro::extract(const char *name, int &dim)
{
  dim = 1;
  if (strcmp(name, "sph/astro/widths") == 0) return width_;
  if (strcmp(name, "sph/astro/narrowed") == 0) return narrowed_;
  return CommBrick::extract(name, dim);
}
