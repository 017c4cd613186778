/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// LAMMPS shrink-wraps the box (boundary s, m) only at a reneighbouring; an atom that drifts out
// of it before the next one (an expanding gas moves up to half the skin) lies beyond the grid of
// MSM, which stops with "Out of range atoms". fix sph/astro makes such a step a reneighbouring
// one, where LAMMPS wraps the box around the atoms again.
//
// LAMMPS pads a shrink-wrapped side by 1e-4 of the box length the box had when it was set
// (Domain::small, from Domain::set_initial_box); read_restart sets that padding anew from the
// restart file's box. A continued run would wrap a narrower box than the uninterrupted one,
// and MSM, whose grid spacing is the box length over its grid points, would give other forces
// (8e-8 apart on a collapsing ball of the tests). fix sph/astro keeps the padding in its restart record.

#ifndef LMP_SPH_ASTRO_SHRINK_WRAP_H
#define LMP_SPH_ASTRO_SHRINK_WRAP_H

#include "atom.h"
#include "domain.h"
#include "lammps.h"

#include <mpi.h>

namespace SPHAstro {

// has any owned atom left a shrink-wrapped side of the box (collective)
inline bool atom_left_shrink_wrapped_box(LAMMPS_NS::LAMMPS *lmp)
{
  const LAMMPS_NS::Domain *domain = lmp->domain;
  double **x = lmp->atom->x;
  const int nlocal = lmp->atom->nlocal;
  int outside = 0;
  for (int d = 0; d < 3 && !outside; d++) {
    const bool wrap_lo = domain->boundary[d][0] >= 2, wrap_hi = domain->boundary[d][1] >= 2;
    if (!wrap_lo && !wrap_hi) continue;
    const double lo = domain->boxlo[d], hi = domain->boxhi[d];
    for (int i = 0; i < nlocal && !outside; i++)
      outside = (wrap_lo && x[i][d] < lo) || (wrap_hi && x[i][d] >= hi);
  }
  int any = 0;
  MPI_Allreduce(&outside, &any, 1, MPI_INT, MPI_MAX, lmp->world);
  return any != 0;
}

// Domain::small is protected: a pointer to it, named through a derived class (never made)
class DomainPadding : public LAMMPS_NS::Domain {
 public:
  static double *of(LAMMPS_NS::Domain *domain) { return domain->*(&DomainPadding::small); }
};

// the padding of a restart record back into the domain (shrink-wrapped sides only use it);
// returns the number of values read
inline int restore_shrink_wrap_padding(LAMMPS_NS::Domain *domain, const double *list)
{
  double *small = DomainPadding::of(domain);
  for (int d = 0; d < 3; d++) small[d] = list[d];
  return 3;
}

}    // namespace SPHAstro

#endif
