/* ----------------------------------------------------------------------
   SPH-ASTRO: physical heat conduction of pair sph/astro (keyword conduction KAPPA)
------------------------------------------------------------------------- */

// A separate neighbour pass after the force pass, run only when kappa > 0, so that scenes
// without conduction do not pay for it. Pair term and its sources: sph_astro_conduction.h
//   du_i/dt += sum_j m_j (kappa_i + kappa_j) (u_i - u_j) / (rho_i rho_j) (dW/dr)_ij / r_ij
// over the half list, with (dW/dr)_ij at h_ij = (h_i + h_j)/2 (fixed h, dh/dt) or the mean
// of dW/dr at h_i and h_j (variable h with grad-h terms, or symmetrise kernel): symmetric in
// i and j, so each pair
// conserves sum m u exactly. u is the predicted u_est of the end of the step (ghost values
// arrive with the density-stage forward communication). With the entropy formulation the
// rate goes to dA/dt = (gamma - 1) rho^(1-gamma) du/dt as well.

#include "pair_sph_astro.h"

#include "sph_astro_conduction.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "force.h"
#include "memory.h"
#include "neigh_list.h"

#include <cmath>

using namespace LAMMPS_NS;
using namespace SPHAstro;

// the ghosts' u_est travels with the density-stage forward communication when a term of the
// force or conduction pass reads the partner's u (with formulation pressure-energy it has
// travelled already, before the pressure pass, and has not changed since)
bool PairSPHAstro::ghosts_need_u() const
{
  return eos_.uses_energy() && (cond_alpha_ > 0.0 || cond_kappa_ > 0.0) && !pressure_energy_;
}

template <class KERNEL, int DIM, bool GRADH> void PairSPHAstro::conduction_loop()
{
  using K = Kernel<KERNEL, DIM>;
  double **x = atom->x;
  const int *type = atom->type;
  const double *rmass = atom->rmass;
  const double *mass = atom->mass;
  const double *rho = eval_density();    // the density of this force evaluation
  const double *h = atom->dvector[state_.h];
  const double *uest = atom->dvector[state_.uest];
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const int newton_pair = force->newton_pair;
  const int nzero = newton_pair ? nall : nlocal;
  const double sigma = K::sigma();
  const double R2 = K::radius * K::radius;
  const double kappa = cond_kappa_;    // constant conductivity: kappa_i = kappa_j

  for (int i = 0; i < nzero; i++) conduct_[i] = 0.0;
  const SPHAstro::NeighView nl = half_view();
  for (int ii = 0; ii < nl.inum; ii++) {
    const int i = nl.ilist[ii];
    const double xi = x[i][0], yi = x[i][1], zi = x[i][2];
    const double hi = h[i];
    const double mi = rmass ? rmass[i] : mass[type[i]];
    const double rhoi = rho[i], ui = uest[i];
    const int *jlist = nl.firstneigh[i];
    const int jnum = nl.numneigh[i];
    double qi = 0.0;
    for (int jj = 0; jj < jnum; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      const double dx = xi - x[j][0], dy = yi - x[j][1], dz = zi - x[j][2];
      const double r2 = dx * dx + dy * dy + dz * dz;
      const double hj = h[j];
      double dwdr_r;    // (dW/dr) / r, symmetric in i and j
      if (GRADH) {
        const double hR2i = R2 * hi * hi, hR2j = R2 * hj * hj;
        if ((r2 >= hR2i && r2 >= hR2j) || r2 == 0.0) continue;
        const double r = std::sqrt(r2);
        const double hinvi = 1.0 / hi, hinvj = 1.0 / hj;
        const double dwi = r2 < hR2i ? sigma * inv_h_pow_dim<DIM>(hinvi) * hinvi * K::dw(r * hinvi)
                                     : 0.0;
        const double dwj = r2 < hR2j ? sigma * inv_h_pow_dim<DIM>(hinvj) * hinvj * K::dw(r * hinvj)
                                     : 0.0;
        dwdr_r = 0.5 * (dwi + dwj) / r;
      } else {
        const double hij = 0.5 * (hi + hj);
        if (r2 >= R2 * hij * hij || r2 == 0.0) continue;
        const double r = std::sqrt(r2);
        const double hinv = 1.0 / hij;
        dwdr_r = sigma * inv_h_pow_dim<DIM>(hinv) * hinv * K::dw(r * hinv) / r;
      }
      const double mj = rmass ? rmass[j] : mass[type[j]];
      const double q = conduction_pair(kappa, kappa, ui, uest[j], rhoi, rho[j], dwdr_r);
      qi += mj * q;
      if (newton_pair || j < nlocal) conduct_[j] -= mi * q;
    }
    conduct_[i] += qi;
  }
  if (newton_pair) {
    comm_stage_ = Stage::CONDUCTION;
    comm->reverse_comm(this, 1);
  }
}

void PairSPHAstro::conduction_pass()
{
  if (atom->nmax > conduct_nmax_) {
    conduct_nmax_ = atom->nmax;
    memory->destroy(conduct_);
    memory->create(conduct_, conduct_nmax_, "pair:sph/astro:conduct");
  }
  // the mean of dW/dr at h_i and h_j: grad-h terms or the averaged kernel
  const bool gradh = hmode_ == HMode::GRADH || symmetrise_kernel_;
  const bool d2 = domain->dimension == 2;
#define SPH_ASTRO_COND(KT)                                                    \
  {                                                                           \
    if (gradh)                                                                \
      d2 ? conduction_loop<KT, 2, true>() : conduction_loop<KT, 3, true>();   \
    else                                                                      \
      d2 ? conduction_loop<KT, 2, false>() : conduction_loop<KT, 3, false>(); \
  }
  switch (kernel_) {
    case KernelType::CUBIC:
      SPH_ASTRO_COND(KernelCubic);
      break;
    case KernelType::QUINTIC:
      SPH_ASTRO_COND(KernelQuintic);
      break;
    case KernelType::WENDLAND_C2:
      SPH_ASTRO_COND(KernelWendlandC2);
      break;
    case KernelType::WENDLAND_C4:
      SPH_ASTRO_COND(KernelWendlandC4);
      break;
    case KernelType::GAUSSIAN:
      SPH_ASTRO_COND(KernelGaussian);
      break;
  }
#undef SPH_ASTRO_COND

  const int nlocal = atom->nlocal;
  double *dudt = atom->dvector[state_.dudt];
  for (int i = 0; i < nlocal; i++) dudt[i] += conduct_[i];
  if (entropy_) {
    const double *rho = eval_density();
    double *dAdt = atom->dvector[entropy_index_.dAdt];
    const double g1 = eos_.gamma - 1.0;
    for (int i = 0; i < nlocal; i++) dAdt[i] += g1 * std::pow(rho[i], -g1) * conduct_[i];
  }
}
