/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: reference self-gravity by direct (or Ewald) summation
------------------------------------------------------------------------- */

// compute ID group sph/astro/gravity/direct -> per-atom array (fx fy fz phi) and a scalar
//
// The reference for pair sph/astro/gravity and the gravity kspace styles: every atom of the
// group feels every other atom of the system, gathered from all MPI ranks, O(N^2), with the
// kernel-softened pair potential of the pair style (same kernel, G and softening lengths):
//   open boundaries:  phi_i = G sum_{j != i} m_j phi_ij(r_ij),  F_i = -m_i grad phi_i
//   periodic boxes:   Ewald summation (Ewald 1921) of the Newtonian part over all images with
//     a neutralising background (as PPPM: k = 0 dropped, background term -pi/(alpha^2 V)),
//     plus the softening correction phi_ij + 1/r for image pairs inside the kernel support:
//     psi(r) = sum_n erfc(alpha |r+n|)/|r+n| + 4 pi/V sum_{k != 0} exp(-k^2/4 alpha^2)/k^2
//              cos(k.r) - pi/(alpha^2 V),   phi_i = -G [sum_{j != i} m_j psi(r_ij) + m_i xi],
//     xi = lim_{r->0} [psi(r) - 1/r]; alpha = 5/L_min with real-space images up to L_min and
//     k-vectors up to exp(-k^2/4 alpha^2) < 1e-14: about 1e-10 relative accuracy.
// Columns: 1-3 force on the atom (force units), 4 potential phi_i per unit mass. Scalar: the
// potential energy 1/2 sum_i m_i phi_i of all atoms (as pair + kspace energy).

#include "compute_sph_astro_gravity_direct.h"

#include "pair_sph_astro_gravity.h"
#include "sph_astro_gravity_kernel.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "math_const.h"
#include "memory.h"
#include "update.h"

#include <cmath>

using namespace LAMMPS_NS;
using namespace SPHAstro;
using MathConst::MY_PIS;

ComputeSPHAstroGravityDirect::ComputeSPHAstroGravityDirect(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg)
{
  pair_ = nullptr;
  nmax_ = 0;
  result_ = nullptr;
  energy_ = 0.0;
  if (narg != 3)
    error->all(FLERR, "compute sph/astro/gravity/direct takes no arguments (got {})", narg - 3);
  peratom_flag = 1;
  size_peratom_cols = 4;
  scalar_flag = 1;
  extscalar = 1;
}

ComputeSPHAstroGravityDirect::~ComputeSPHAstroGravityDirect()
{
  memory->destroy(result_);
}

void ComputeSPHAstroGravityDirect::init()
{
  pair_ = dynamic_cast<PairSPHAstroGravity *>(force->pair_match("^sph/astro/gravity$", 0, 0));
  if (!pair_)
    error->all(FLERR,
               "compute sph/astro/gravity/direct requires pair_style sph/astro/gravity (its G, "
               "kernel and softening lengths)");
  const int periodic = domain->xperiodic + domain->yperiodic + domain->zperiodic;
  if (periodic != 0 && periodic != 3)
    error->all(FLERR,
               "compute sph/astro/gravity/direct: boundaries must be periodic in all of x, y, z "
               "(Ewald summation) or in none (direct summation)");
  if (domain->triclinic)
    error->all(FLERR, "compute sph/astro/gravity/direct: triclinic boxes are not supported");
  if (atom->natoms > 200000 && comm->me == 0)
    error->warning(FLERR,
                   "compute sph/astro/gravity/direct: O(N^2) reference with {} atoms will be slow",
                   atom->natoms);
}

void ComputeSPHAstroGravityDirect::gather()
{
  const int nlocal = atom->nlocal;
  const int nprocs = comm->nprocs;
  std::vector<int> counts(nprocs), displs(nprocs);
  MPI_Allgather(&nlocal, 1, MPI_INT, counts.data(), 1, MPI_INT, world);
  int ntotal = 0;
  for (int p = 0; p < nprocs; p++) {
    displs[p] = ntotal;
    ntotal += counts[p];
  }
  std::vector<double> mine(5 * nlocal);
  std::vector<tagint> mytags(nlocal);
  for (int i = 0; i < nlocal; i++) {
    for (int d = 0; d < 3; d++) mine[5 * i + d] = atom->x[i][d];
    mine[5 * i + 3] = atom->rmass ? atom->rmass[i] : atom->mass[atom->type[i]];
    mine[5 * i + 4] = pair_->softening_length(i);
    mytags[i] = atom->tag[i];
  }
  std::vector<int> counts5(nprocs), displs5(nprocs);
  for (int p = 0; p < nprocs; p++) {
    counts5[p] = 5 * counts[p];
    displs5[p] = 5 * displs[p];
  }
  std::vector<double> all(5 * ntotal);
  tag_.resize(ntotal);
  MPI_Allgatherv(mine.data(), 5 * nlocal, MPI_DOUBLE, all.data(), counts5.data(), displs5.data(),
                 MPI_DOUBLE, world);
  MPI_Allgatherv(mytags.data(), nlocal, MPI_LMP_TAGINT, tag_.data(), counts.data(), displs.data(),
                 MPI_LMP_TAGINT, world);
  x_.resize(3 * ntotal);
  m_.resize(ntotal);
  h_.resize(ntotal);
  for (int j = 0; j < ntotal; j++) {
    for (int d = 0; d < 3; d++) x_[3 * j + d] = all[5 * j + d];
    m_[j] = all[5 * j + 3];
    h_[j] = all[5 * j + 4];
  }
}

void ComputeSPHAstroGravityDirect::evaluate()
{
  if (atom->nmax > nmax_) {
    memory->destroy(result_);
    nmax_ = atom->nmax;
    memory->create(result_, nmax_, 4, "sph/astro/gravity/direct:result");
    array_atom = result_;
  }
  gather();
  if (domain->nonperiodic)
    direct_sum();
  else
    ewald_sum();
  // potential energy of the whole system (every atom, not only the group)
  double local = 0.0;
  for (int i = 0; i < atom->nlocal; i++)
    local += 0.5 * (atom->rmass ? atom->rmass[i] : atom->mass[atom->type[i]]) * result_[i][3];
  MPI_Allreduce(&local, &energy_, 1, MPI_DOUBLE, MPI_SUM, world);
}

// open boundaries: phi_i = G sum_{j != i} m_j phi_ij, F_i = -G m_i sum_j m_j dphi_ij/dr r_ij/r
void ComputeSPHAstroGravityDirect::direct_sum()
{
  const double G = pair_->gravity_constant();
  const KernelType kernel = pair_->kernel();
  const int ntotal = static_cast<int>(m_.size());
  for (int i = 0; i < atom->nlocal; i++) {
    const double mi = atom->rmass ? atom->rmass[i] : atom->mass[atom->type[i]];
    const double hi = pair_->softening_length(i);
    double fx = 0.0, fy = 0.0, fz = 0.0, phi = 0.0;
    for (int j = 0; j < ntotal; j++) {
      if (tag_[j] == atom->tag[i]) continue;
      const double dx = atom->x[i][0] - x_[3 * j], dy = atom->x[i][1] - x_[3 * j + 1],
                   dz = atom->x[i][2] - x_[3 * j + 2];
      const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
      double p, dp;
      softened_pair(kernel, r, hi, h_[j], p, dp);
      phi += m_[j] * p;
      if (r > 0.0) {
        const double s = -m_[j] * dp / r;
        fx += s * dx;
        fy += s * dy;
        fz += s * dz;
      }
    }
    result_[i][0] = G * mi * fx;
    result_[i][1] = G * mi * fy;
    result_[i][2] = G * mi * fz;
    result_[i][3] = G * phi;
  }
}

// periodic: Ewald summation with the softening correction (see the header of this file)
void ComputeSPHAstroGravityDirect::ewald_sum()
{
  const double G = pair_->gravity_constant();
  const KernelType kernel = pair_->kernel();
  const double R = SPHAstro::kernel_radius(kernel);
  const int ntotal = static_cast<int>(m_.size());
  const double L[3] = {domain->xprd, domain->yprd, domain->zprd};
  const double V = L[0] * L[1] * L[2];
  const double Lmin = MIN(L[0], MIN(L[1], L[2]));
  const double rc = Lmin, rcsq = rc * rc;
  const double alpha = 5.0 / rc;
  const double kmax = 2.0 * alpha * std::sqrt(std::log(1e14));
  int nimg[3], kmaxn[3];
  for (int d = 0; d < 3; d++) {
    nimg[d] = static_cast<int>(std::ceil(rc / L[d] + 0.5));
    kmaxn[d] = static_cast<int>(std::ceil(kmax * L[d] / (2.0 * M_PI)));
  }
  double mtotal = 0.0;
  for (double m : m_) mtotal += m;

  // k-vectors of the half space (k and -k give the same term): structure factors
  // C(k) = sum_j m_j cos(k.x_j), S(k) = sum_j m_j sin(k.x_j)
  struct KVec {
    double k[3], coef;    // coef = 2 x 4 pi/V exp(-k^2/4 alpha^2)/k^2 (factor 2: half space)
    double C, S;
  };
  std::vector<KVec> kv;
  for (int nx = 0; nx <= kmaxn[0]; nx++)
    for (int ny = -kmaxn[1]; ny <= kmaxn[1]; ny++)
      for (int nz = -kmaxn[2]; nz <= kmaxn[2]; nz++) {
        if (nx == 0 && (ny < 0 || (ny == 0 && nz <= 0))) continue;
        KVec v;
        v.k[0] = 2.0 * M_PI * nx / L[0];
        v.k[1] = 2.0 * M_PI * ny / L[1];
        v.k[2] = 2.0 * M_PI * nz / L[2];
        const double ksq = v.k[0] * v.k[0] + v.k[1] * v.k[1] + v.k[2] * v.k[2];
        if (ksq > kmax * kmax) continue;
        v.coef = 2.0 * 4.0 * M_PI / V * std::exp(-ksq / (4.0 * alpha * alpha)) / ksq;
        v.C = v.S = 0.0;
        kv.push_back(v);
      }
  for (auto &v : kv)
    for (int j = 0; j < ntotal; j++) {
      const double kx = v.k[0] * x_[3 * j] + v.k[1] * x_[3 * j + 1] + v.k[2] * x_[3 * j + 2];
      v.C += m_[j] * std::cos(kx);
      v.S += m_[j] * std::sin(kx);
    }
  // psi_i = sum_{j != i} m_j psi(r_ij) + m_i xi, regrouped as
  //   sum_k coef [cos(k.x_i) C + sin(k.x_i) S]   (reciprocal space, all j including i)
  //   + sum_{j,n != (i,0)} m_j erfc(alpha r)/r   (real space, with the softening correction)
  //   + m_i (own images - 2 alpha/sqrt(pi)) - M pi/(alpha^2 V)   (self and background)
  double xi_real = -2.0 * alpha / MY_PIS;
  for (int a = -nimg[0]; a <= nimg[0]; a++)
    for (int b = -nimg[1]; b <= nimg[1]; b++)
      for (int c = -nimg[2]; c <= nimg[2]; c++) {
        if (a == 0 && b == 0 && c == 0) continue;
        const double r = std::sqrt(a * a * L[0] * L[0] + b * b * L[1] * L[1] + c * c * L[2] * L[2]);
        if (r < rc) xi_real += std::erfc(alpha * r) / r;
      }

  for (int i = 0; i < atom->nlocal; i++) {
    const double *xi3 = atom->x[i];
    const double mi = atom->rmass ? atom->rmass[i] : atom->mass[atom->type[i]];
    const double hi = pair_->softening_length(i);
    // psi_i and grad psi_i (F_i = G m_i grad psi_i)
    double psi = mi * xi_real - mtotal * M_PI / (alpha * alpha * V);
    double gx = 0.0, gy = 0.0, gz = 0.0;
    for (const auto &v : kv) {
      const double kx = v.k[0] * xi3[0] + v.k[1] * xi3[1] + v.k[2] * xi3[2];
      const double c = std::cos(kx), s = std::sin(kx);
      psi += v.coef * (c * v.C + s * v.S);
      // grad_i cos(k.(x_i - x_j)) = -k sin(k.(x_i - x_j)); sum_j m_j sin(..) = s C - c S
      const double sn = s * v.C - c * v.S;
      gx -= v.coef * v.k[0] * sn;
      gy -= v.coef * v.k[1] * sn;
      gz -= v.coef * v.k[2] * sn;
    }
    // real space over images within rc, softening correction inside the kernel supports
    for (int j = 0; j < ntotal; j++) {
      const bool self = tag_[j] == atom->tag[i];
      double d0[3];
      for (int d = 0; d < 3; d++) {
        d0[d] = xi3[d] - x_[3 * j + d];
        d0[d] -= L[d] * std::round(d0[d] / L[d]);
      }
      for (int a = -nimg[0]; a <= nimg[0]; a++)
        for (int b = -nimg[1]; b <= nimg[1]; b++)
          for (int c = -nimg[2]; c <= nimg[2]; c++) {
            if (self && a == 0 && b == 0 && c == 0) continue;
            const double dx = d0[0] + a * L[0], dy = d0[1] + b * L[1], dz = d0[2] + c * L[2];
            const double rsq = dx * dx + dy * dy + dz * dz;
            if (rsq >= rcsq) continue;
            const double r = std::sqrt(rsq);
            if (self) continue;    // own images: already in xi, forces cancel
            const double erfc_r = std::erfc(alpha * r) / r;
            psi += m_[j] * erfc_r;
            // d/dr [erfc(alpha r)/r] = -(erfc/r + 2 alpha/sqrt(pi) exp(-alpha^2 r^2)) / r
            double dpsi = -(erfc_r + 2.0 * alpha / MY_PIS * std::exp(-alpha * alpha * rsq)) / r;
            if (r < R * MAX(hi, h_[j])) {
              // softened instead of Newtonian: psi gains -(phi_ij + 1/r)
              double p, dp;
              softened_pair(kernel, r, hi, h_[j], p, dp);
              psi -= m_[j] * (p + 1.0 / r);
              dpsi -= (dp - 1.0 / rsq);
            }
            if (r > 0.0) {
              gx += m_[j] * dpsi * dx / r;
              gy += m_[j] * dpsi * dy / r;
              gz += m_[j] * dpsi * dz / r;
            }
          }
    }
    // phi = -G psi, F = -m grad phi = G m grad psi
    result_[i][0] = G * mi * gx;
    result_[i][1] = G * mi * gy;
    result_[i][2] = G * mi * gz;
    result_[i][3] = -G * psi;
  }
}

double ComputeSPHAstroGravityDirect::compute_scalar()
{
  invoked_scalar = update->ntimestep;
  evaluate();
  scalar = energy_;
  return scalar;
}

void ComputeSPHAstroGravityDirect::compute_peratom()
{
  invoked_peratom = update->ntimestep;
  evaluate();
}

double ComputeSPHAstroGravityDirect::memory_usage()
{
  return 4.0 * nmax_ * sizeof(double) + (5.0 * sizeof(double) + sizeof(tagint)) * m_.size();
}
