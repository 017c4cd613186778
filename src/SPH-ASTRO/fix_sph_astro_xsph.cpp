/* ----------------------------------------------------------------------
   SPH-ASTRO: XSPH velocity smoothing of fix sph/astro (keyword xsph EPS)
------------------------------------------------------------------------- */

// XSPH (Monaghan 1989, J. Comput. Phys. 82, 1; Monaghan 1992, ARA&A 30, 543, eq. 4.1;
// seed 000 "XSPH"): particles drift with the smoothed velocity
//   dx_i/dt = v_i + dv_i,  dv_i = eps sum_j m_j / rho_ij (v_j - v_i) W(r_ij, h_ij)
// with rho_ij = (rho_i + rho_j)/2 and h_ij = (h_i + h_j)/2 (seed 000, "some notation"). The
// seed prints (v_i - v_j), which would push a particle away from the mean velocity of its
// neighbours; Monaghan's (v_j - v_i) is used. W_ij is symmetric and v_j - v_i antisymmetric,
// so sum_i m_i dv_i = 0: the momentum of the drift correction vanishes pair by pair. The
// velocities are the predicted ones of the last force evaluation (d2_vest; ghosts receive them
// with the pair style's forward communication), so the correction belongs to the same time as
// the forces. v itself (and so the momentum equation) is unchanged; since x no longer moves
// with v, the total energy is conserved only approximately (doc/fix_sph_astro.rst).
//
// Computed after every force evaluation (post_force, and setup for the first drift) over a
// full neighbour list that is requested only when xsph > 0: runs without XSPH have no list,
// no pass and no extra term in the drift.

#include "fix_sph_astro.h"

#include "pair_sph_astro.h"
#include "sph_astro_kernel.h"

#include "atom.h"
#include "domain.h"
#include "memory.h"
#include "neigh_list.h"

#include <cmath>

using namespace LAMMPS_NS;
using namespace SPHAstro;

void FixSPHAstro::init_list(int /*id*/, NeighList *ptr)
{
  xsph_list_ = ptr;
}

void FixSPHAstro::post_force(int /*vflag*/)
{
  xsph_correction();
}

template <class KERNEL, int DIM> void FixSPHAstro::xsph_loop()
{
  using K = Kernel<KERNEL, DIM>;
  double **x = atom->x;
  const int *type = atom->type;
  const double *rmass = atom->rmass;
  const double *mass = atom->mass;
  const double *rho = pair_->eval_density();    // that of the force evaluation (ghosts too)
  const double *h = atom->dvector[state_.h];
  double **vest = atom->darray[state_.vest];
  const double sigma = K::sigma();
  const double R2 = K::radius * K::radius;
  const double eps = xsph_eps_;
  NeighList *nl = xsph_list_;

  for (int ii = 0; ii < nl->inum; ii++) {
    const int i = nl->ilist[ii];
    const double xi = x[i][0], yi = x[i][1], zi = x[i][2];
    const double hi = h[i], rhoi = rho[i];
    const double vxi = vest[i][0], vyi = vest[i][1], vzi = vest[i][2];
    const int *jlist = nl->firstneigh[i];
    const int jnum = nl->numneigh[i];
    double sx = 0.0, sy = 0.0, sz = 0.0;
    for (int jj = 0; jj < jnum; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      const double dx = xi - x[j][0], dy = yi - x[j][1], dz = zi - x[j][2];
      const double r2 = dx * dx + dy * dy + dz * dz;
      const double hij = 0.5 * (hi + h[j]);
      if (r2 >= R2 * hij * hij) continue;
      const double hinv = 1.0 / hij;
      const double wij = sigma * inv_h_pow_dim<DIM>(hinv) * K::w(std::sqrt(r2) * hinv);
      const double mj = rmass ? rmass[j] : mass[type[j]];
      const double fac = mj * wij / (0.5 * (rhoi + rho[j]));
      sx += fac * (vest[j][0] - vxi);
      sy += fac * (vest[j][1] - vyi);
      sz += fac * (vest[j][2] - vzi);
    }
    xsph_[i][0] = eps * sx;
    xsph_[i][1] = eps * sy;
    xsph_[i][2] = eps * sz;
  }
}

void FixSPHAstro::xsph_correction()
{
  if (atom->nmax > xsph_nmax_) {
    xsph_nmax_ = atom->nmax;
    memory->destroy(xsph_);
    memory->create(xsph_, xsph_nmax_, 3, "fix_sph_astro:xsph");
    array_atom = xsph_;
  }
  // atoms outside the list (none for a list of all atoms) keep a zero correction
  for (int i = 0; i < atom->nlocal; i++) xsph_[i][0] = xsph_[i][1] = xsph_[i][2] = 0.0;
  const bool d2 = domain->dimension == 2;
#define SPH_ASTRO_XSPH(KT) \
  {                        \
    if (d2)                \
      xsph_loop<KT, 2>();  \
    else                   \
      xsph_loop<KT, 3>();  \
  }
  switch (pair_->kernel_type()) {
    case KernelType::CUBIC:
      SPH_ASTRO_XSPH(KernelCubic);
      break;
    case KernelType::QUINTIC:
      SPH_ASTRO_XSPH(KernelQuintic);
      break;
    case KernelType::WENDLAND_C2:
      SPH_ASTRO_XSPH(KernelWendlandC2);
      break;
    case KernelType::WENDLAND_C4:
      SPH_ASTRO_XSPH(KernelWendlandC4);
      break;
    case KernelType::GAUSSIAN:
      SPH_ASTRO_XSPH(KernelGaussian);
      break;
  }
#undef SPH_ASTRO_XSPH
}
