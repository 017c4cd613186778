/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Pair sph/astro/gravity (pair_sph_astro_gravity.cpp), its sums before the forces: the
// gathered atoms of direct summation and the zeta terms of adaptive softening
// (Price & Monaghan 2007, MNRAS 374, 1347, eq. 26).

#include "pair_sph_astro_gravity.h"

#include "pair_sph_astro.h"
#include "sph_astro_gravity_kernel.h"
#include "sph_astro_neighbour_tree.h"
#include "sph_astro_state.h"

#include "atom.h"
#include "comm.h"
#include "force.h"
#include "memory.h"
#include "neigh_list.h"

#include <algorithm>
#include <cmath>
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
  const double *h = state_h();
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
    mine[5 * i + 4] = (h && h[i] > 0.0) ? h[i] : hfixed_;
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
  const char *active = sph_ ? sph_->active_flags() : nullptr;
  if (active) {
    active_all_.resize(ntotal);
    MPI_Allgatherv(active, nlocal, MPI_CHAR, active_all_.data(), counts.data(), displs.data(),
                   MPI_CHAR, world);
  }
}

// zeta_i = dh_i/drho_i S_i, S_i = sum_{j != i} m_j dphi(r_ij, h_i)/dh_i, dh/drho = -h/(3 rho);
// stored as zeta_i (zeta_) and zeta_i/Omega_i of all atoms (gathered, direct summation) or of
// owned + ghost atoms (zeta_over_omega_, kspace split)
void PairSPHAstroGravity::compute_zeta()
{
  if (atom->nmax > nmax_) {
    nmax_ = atom->nmax;
    memory->destroy(zeta_);
    memory->create(zeta_, nmax_, "pair:sph/astro/gravity:zeta");
    memory->destroy(zeta_over_omega_);
    memory->create(zeta_over_omega_, nmax_, "pair:sph/astro/gravity:zeta_over_omega");
  }
  double **x = atom->x;
  const int *type = atom->type;
  const double *rmass = atom->rmass;
  const double *mass = atom->mass;
  const double *h = state_h();
  const double *rho = atom->dvector[state_->rho];
  int ncol;
  const double *omega = static_cast<const double *>(sph_->extract_peratom("omega_valid", ncol));
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const int newton_pair = force->newton_pair;
  const double R = kernel_radius(kernel_);
  const double hfix = hfixed_;
  const KernelType kernel = kernel_;
  for (int i = 0; i < nall; i++) zeta_[i] = 0.0;

  if (split_ == Split::NONE) {
    // the kernel neighbours of each owned atom among all gathered atoms, found by a tree over
    // their positions and summed in the order of their index
    double *all = all_.data();
    const int n = ntotal_;
    zeta_points_.resize(n);
    zeta_index_.resize(n);
    zeta_radii_.assign(n, 0.0);
    for (int gj = 0; gj < n; gj++) {
      zeta_points_[gj] = all + 5 * gj;
      zeta_index_[gj] = gj;
    }
    // individual timesteps: eval() sums only pairs with an active atom, and uses zeta_j only
    // within R max(h_i, h_j) of one: zeta of the active atoms and of those within that reach of
    // one (each active atom's gather and scatter neighbours, found by the tree with the radii
    // R h_j), unless the virial or per-atom energies are tallied or most atoms are active
    const char *active_all = active_pairs_only_ ? active_all_.data() : nullptr;
    int nactive = n;
    if (active_all) nactive = static_cast<int>(n - std::count(active_all, active_all + n, 0));
    const bool select = 2 * nactive < n;
    if (select)
      for (int gj = 0; gj < n; gj++) zeta_radii_[gj] = R * all[5 * gj + 4] * (1.0 + 1e-10);
    zeta_tree_->build(zeta_points_.data(), zeta_radii_.data(), zeta_index_.data(), n);
    if (select) {
      const int first = offset_, last = offset_ + nlocal;
      zeta_needed_.assign(nlocal, 0);
      for (int gk = 0; gk < n; gk++) {
        if (!active_all[gk]) continue;
        zeta_tree_->query(zeta_points_.data(), zeta_radii_.data(), all + 5 * gk, zeta_radii_[gk],
                          0.0, 0.0, [&](int gj, double) {
                            if (gj >= first && gj < last) zeta_needed_[gj - first] = 1;
                          });
      }
      zeta_radii_.assign(n, 0.0);    // the gathers below: within R h_i alone
      zeta_tree_->update_radii(zeta_radii_.data());
    }
    for (int i = 0; i < nlocal; i++) {
      if (select && !zeta_needed_[i] && !active_all[offset_ + i]) {
        zeta_[i] = 0.0;    // not used this step
        continue;
      }
      const double xi = x[i][0], yi = x[i][1], zi = x[i][2];
      const double hi = h[i] > 0.0 ? h[i] : hfix;
      const double Rhsq = R * R * hi * hi;
      const int gi = offset_ + i;
      // candidates a little beyond R h_i, so that the test below alone decides
      const double c[3] = {xi, yi, zi};
      zeta_found_.clear();
      zeta_tree_->query(zeta_points_.data(), zeta_radii_.data(), c, R * hi * (1.0 + 1e-10), 0.0,
                        0.0, [&](int gj, double) {
                          zeta_found_.push_back(gj);
                        });
      std::sort(zeta_found_.begin(), zeta_found_.end());
      double sum = 0.0;
      for (const int gj : zeta_found_) {
        const double *aj = all + 5 * gj;
        const double dx = xi - aj[0], dy = yi - aj[1], dz = zi - aj[2];
        const double rsq = dx * dx + dy * dy + dz * dz;
        if (rsq >= Rhsq || gj == gi) continue;
        sum += aj[3] * softened_dphidh(kernel, std::sqrt(rsq), hi);
      }
      zeta_[i] = sum;
    }
  } else {
    const int inum = list->inum;
    const int *ilist = list->ilist;
    const int *numneigh = list->numneigh;
    int **firstneigh = list->firstneigh;
    for (int ii = 0; ii < inum; ii++) {
      const int i = ilist[ii];
      const double hi = h[i] > 0.0 ? h[i] : hfix;
      const double mi = rmass ? rmass[i] : mass[type[i]];
      const int *jlist = firstneigh[i];
      const int jnum = numneigh[i];
      for (int jj = 0; jj < jnum; jj++) {
        const int j = jlist[jj] & NEIGHMASK;
        const double hj = h[j] > 0.0 ? h[j] : hfix;
        const double dx = x[i][0] - x[j][0], dy = x[i][1] - x[j][1], dz = x[i][2] - x[j][2];
        const double rsq = dx * dx + dy * dy + dz * dz;
        const double Rh = R * MAX(hi, hj);
        if (rsq >= Rh * Rh) continue;
        const double r = std::sqrt(rsq);
        zeta_[i] += (rmass ? rmass[j] : mass[type[j]]) * softened_dphidh(kernel, r, hi);
        if (newton_pair || j < nlocal) zeta_[j] += mi * softened_dphidh(kernel, r, hj);
      }
    }
    if (newton_pair) {
      comm_stage_ = Stage::ZETA;
      comm->reverse_comm(this);
    }
  }
  // 0 for h held at the cap (it does not follow rho) and atoms without SPH smoothing length
  for (int i = 0; i < nlocal; i++) {
    if (!(h[i] > 0.0) || h[i] >= sph_->h_cap() || !(rho[i] > 0.0))
      zeta_[i] = 0.0;
    else
      zeta_[i] *= -h[i] / (3.0 * rho[i]);
  }
  // zeta/Omega of the partners
  if (split_ == Split::NONE) {
    std::vector<double> mine(nlocal);
    for (int i = 0; i < nlocal; i++) mine[i] = zeta_[i] / omega[i];
    zo_all_.resize(ntotal_);
    MPI_Allgatherv(mine.data(), nlocal, MPI_DOUBLE, zo_all_.data(), gather_counts_.data(),
                   gather_displs_.data(), MPI_DOUBLE, world);
  } else {    // (the owners' values: pair sph/astro need not send Omega to every ghost)
    for (int i = 0; i < nlocal; i++) zeta_over_omega_[i] = zeta_[i] / omega[i];
    comm_stage_ = Stage::ZETA;
    comm->forward_comm(this, 2);
  }
}
