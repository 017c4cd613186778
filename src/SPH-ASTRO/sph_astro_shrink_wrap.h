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

#include <algorithm>
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

// The box Domain::reset_box wraps around the atoms at a run's setup: on the shrink-wrapped sides
// of an orthogonal box the atoms' extent plus the padding, boundary m at least its minimum; the
// other sides as they are (collective). False if no side is shrink-wrapped or there are no atoms.
inline bool shrink_wrapped_box(LAMMPS_NS::LAMMPS *lmp, double lo[3], double hi[3])
{
  LAMMPS_NS::Domain *domain = lmp->domain;
  for (int d = 0; d < 3; d++) {
    lo[d] = domain->boxlo[d];
    hi[d] = domain->boxhi[d];
  }
  if (domain->nonperiodic != 2 || domain->triclinic || lmp->atom->natoms == 0) return false;
  double extent[6], all[6];    // -min x, y, z and max x, y, z (one MPI_MAX)
  for (double &e : extent) e = -1.0e300;
  double **x = lmp->atom->x;
  for (int i = 0; i < lmp->atom->nlocal; i++)
    for (int d = 0; d < 3; d++) {
      extent[d] = std::max(extent[d], -x[i][d]);
      extent[3 + d] = std::max(extent[3 + d], x[i][d]);
    }
  MPI_Allreduce(extent, all, 6, MPI_DOUBLE, MPI_MAX, lmp->world);
  const double *small = DomainPadding::of(domain);
  const double minlo[3] = {domain->minxlo, domain->minylo, domain->minzlo};
  const double minhi[3] = {domain->minxhi, domain->minyhi, domain->minzhi};
  for (int d = 0; d < 3; d++) {
    if (domain->periodicity[d]) continue;
    const int *side = domain->boundary[d];
    if (side[0] == 2) lo[d] = -all[d] - small[d];
    if (side[0] == 3) lo[d] = std::min(-all[d] - small[d], minlo[d]);
    if (side[1] == 2) hi[d] = all[3 + d] + small[d];
    if (side[1] == 3) hi[d] = std::max(all[3 + d] + small[d], minhi[d]);
  }
  return true;
}

// the box set to [lo, hi] while this lives (if active), the box before restored after
class BoxScope {
 public:
  BoxScope(LAMMPS_NS::Domain *domain, const double lo[3], const double hi[3], bool active) :
      domain_(domain), active_(active)
  {
    if (!active_) return;
    for (int d = 0; d < 3; d++) {
      lo_[d] = domain->boxlo[d];
      hi_[d] = domain->boxhi[d];
      domain->boxlo[d] = lo[d];
      domain->boxhi[d] = hi[d];
    }
    domain->set_global_box();
    domain->set_local_box();
  }
  ~BoxScope()
  {
    if (!active_) return;
    for (int d = 0; d < 3; d++) {
      domain_->boxlo[d] = lo_[d];
      domain_->boxhi[d] = hi_[d];
    }
    domain_->set_global_box();
    domain_->set_local_box();
  }
  BoxScope(const BoxScope &) = delete;
  BoxScope &operator=(const BoxScope &) = delete;

 private:
  LAMMPS_NS::Domain *domain_;
  bool active_;
  double lo_[3] = {0.0, 0.0, 0.0}, hi_[3] = {0.0, 0.0, 0.0};
};

}    // namespace SPHAstro

#endif
