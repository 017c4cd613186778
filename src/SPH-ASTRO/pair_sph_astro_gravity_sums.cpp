/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Pair sph/astro/gravity (pair_sph_astro_gravity.cpp), its sums before the forces: the
// gathered atoms of direct summation and the zeta terms of adaptive softening (and whether they
// apply)
// (Price & Monaghan 2007, MNRAS 374, 1347, eq. 26).

#include "pair_sph_astro_gravity.h"

#include "pair_sph_astro.h"
#include "sph_astro_gravity_kernel.h"
#include "sph_astro_state.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "memory.h"
#include "update.h"

#include <vector>

using namespace LAMMPS_NS;
using namespace SPHAstro;

/* ----------------------------------------------------------------------
   direct summation: every rank gathers position, mass and h of all atoms (5 values each) and
   sums over all of them for its owned atoms, without ghosts or a neighbour list: in-rank pairs
   once (Newton's third law), pairs with atoms of other ranks on both ranks (half the energy
   each). Ghost atoms and neighbour lists then only serve the other pair styles.
------------------------------------------------------------------------- */

void PairSPHAstroGravity::gather_all()
{
  const int nlocal = atom->nlocal;
  const int nprocs = comm->nprocs;
  double **x = atom->x;
  const int *type = atom->type;
  const double *rmass = atom->rmass;
  const double *mass = atom->mass;
  std::vector<int> counts(nprocs), displs(nprocs);
  MPI_Allgather(&nlocal, 1, MPI_INT, counts.data(), 1, MPI_INT, world);
  int ntotal = 0;
  for (int p = 0; p < nprocs; p++) {
    displs[p] = ntotal;
    ntotal += counts[p];
  }
  offset_ = displs[comm->me];
  ntotal_ = ntotal;
  std::vector<double> mine(5 * nlocal);
  for (int i = 0; i < nlocal; i++) {
    mine[5 * i + 0] = x[i][0];
    mine[5 * i + 1] = x[i][1];
    mine[5 * i + 2] = x[i][2];
    mine[5 * i + 3] = rmass ? rmass[i] : mass[type[i]];
    mine[5 * i + 4] = softening_length(i);
  }
  all_.resize(5 * (size_t) ntotal);
  std::vector<int> counts5(nprocs), displs5(nprocs);
  for (int p = 0; p < nprocs; p++) {
    counts5[p] = 5 * counts[p];
    displs5[p] = 5 * displs[p];
  }
  MPI_Allgatherv(mine.data(), 5 * nlocal, MPI_DOUBLE, all_.data(), counts5.data(), displs5.data(),
                 MPI_DOUBLE, world);
  // the same, one array per quantity (contiguous for the vector lanes of eval)
  gx_.resize(ntotal);
  gy_.resize(ntotal);
  gz_.resize(ntotal);
  gm_.resize(ntotal);
  gh_.resize(ntotal);
  for (int j = 0; j < ntotal; j++) {
    gx_[j] = all_[5 * j + 0];
    gy_[j] = all_[5 * j + 1];
    gz_[j] = all_[5 * j + 2];
    gm_[j] = all_[5 * j + 3];
    gh_[j] = all_[5 * j + 4];
  }
  gather_counts_ = counts;
  gather_displs_ = displs;
  if (!active_.all()) {
    std::vector<char> active(nlocal);
    for (int i = 0; i < nlocal; i++) active[i] = active_.active(i, atom->mask) ? 1 : 0;
    active_all_.resize(ntotal);
    MPI_Allgatherv(active.data(), nlocal, MPI_CHAR, active_all_.data(), counts.data(),
                   displs.data(), MPI_CHAR, world);
  }
}

// zeta_i = dh_i/drho_i S_i, S_i = sum_{j != i} m_j dphi(r_ij, h_i)/dh_i, dh/drho = -h/(3 rho);
// S_i is summed by pair sph/astro's h iteration over the same kernel neighbours (with
// individual timesteps an inactive atom's is that of its last evaluation carried with its
// drifted h, ForceEvaluation::keep_softening_sums()); stored as zeta_i (zeta_; ghosts: 0 with
// direct summation) and zeta_i/Omega_i of all atoms (gathered, direct summation) or of owned +
// ghost atoms (zeta_over_omega_, kspace split)
void PairSPHAstroGravity::compute_zeta()
{
  if (atom->nmax > nmax_) {
    nmax_ = atom->nmax;
    memory->destroy(zeta_);
    memory->create(zeta_, nmax_, "pair:sph/astro/gravity:zeta");
    memory->destroy(zeta_over_omega_);
    memory->create(zeta_over_omega_, nmax_, "pair:sph/astro/gravity:zeta_over_omega");
  }
  const double *h = state_h();
  const double *rho = atom->dvector[state_->rho];
  const double *omega = sph_->omega();
  const double *sums = sph_->dphidh_sums();
  if (!sums)
    error->all(FLERR,
               "pair_style sph/astro/gravity: pair sph/astro has no zeta sums of step {} (a "
               "bug: please report it)",
               update->ntimestep);
  const int nlocal = atom->nlocal;
  // 0 for h held at the cap (it does not follow rho), atoms without SPH smoothing length and
  // atoms that are not SPH gas of pair sph/astro (point masses: the sums are not theirs)
  const int *type = atom->type;
  for (int i = 0; i < nlocal; i++) {
    if (!(h[i] > 0.0) || h[i] >= sph_->h_cap() || !(rho[i] > 0.0) ||
        !sph_->setflag[type[i]][type[i]])
      zeta_[i] = 0.0;
    else
      zeta_[i] = -h[i] / (3.0 * rho[i]) * sums[i];
  }
  // zeta_i / Omega_i; 0 where zeta_i is (point masses have no Omega)
  auto over_omega = [&](int i) { return zeta_[i] != 0.0 ? zeta_[i] / omega[i] : 0.0; };
  // zeta/Omega of the partners (the tree sends the owned atoms' values itself)
  if (split_ == Split::TREE && !periodic_tree()) {
    for (int i = 0; i < nlocal; i++) zeta_over_omega_[i] = over_omega(i);
  } else if (split_ == Split::NONE) {
    for (int i = nlocal; i < nlocal + atom->nghost; i++) zeta_[i] = 0.0;
    std::vector<double> mine(nlocal);
    for (int i = 0; i < nlocal; i++) mine[i] = over_omega(i);
    zo_all_.resize(ntotal_);
    MPI_Allgatherv(mine.data(), nlocal, MPI_DOUBLE, zo_all_.data(), gather_counts_.data(),
                   gather_displs_.data(), MPI_DOUBLE, world);
  } else {    // (the owners' values: pair sph/astro need not send Omega to every ghost)
    for (int i = 0; i < nlocal; i++) zeta_over_omega_[i] = over_omega(i);
    comm_stage_ = Stage::ZETA;
    comm->forward_comm(this, 2);
  }
}

/* ----------------------------------------------------------------------
   the zeta terms apply with pair sph/astro in grad-h mode (its Omega is non-null), unless
   switched off; its Omega and rho must be of this step
------------------------------------------------------------------------- */

bool PairSPHAstroGravity::zeta_terms_apply()
{
  if (!zeta_on_ || !have_state_ || !sph_) return false;
  if (!sph_->omega()) return false;
  if (sph_->computed_step() != update->ntimestep || sph_->computed_nlocal() != atom->nlocal)
    error->all(FLERR,
               "pair_style sph/astro/gravity: the density and grad-h factors of pair sph/astro "
               "are not of step {} (zeta terms); list sph/astro before sph/astro/gravity in "
               "pair_style hybrid/overlay, or use zeta no",
               update->ntimestep);
  return true;
}
