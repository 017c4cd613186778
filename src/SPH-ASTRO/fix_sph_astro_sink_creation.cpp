/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Fix sph/astro/sink: the creation of sinks from dense collapsing gas (Bate, Bonnell & Price
// 1995, MNRAS 277, 362, sec. 2.3: BBP95; Price et al. 2018, PASA 35, e031, sec. 2.8.4: P18;
// Federrath et al. 2010, ApJ 713, 269, sec. 2.2). Accretion, output and restart:
// fix_sph_astro_sink.cpp.

#include "fix_sph_astro_sink.h"

#include "fix_sph_astro.h"
#include "pair_sph_astro.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "memory.h"
#include "modify.h"
#include "pair.h"
#include "sph_astro_fields.h"
#include "sph_astro_gravity_kernel.h"
#include "sph_astro_options.h"
#include "sph_astro_sink_records.h"
#include "sph_astro_state.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace SPHAstro::SinkRecords;
/* ----------------------------------------------------------------------
   creation (BBP95 sec. 2.3; P18 sec. 2.8.4; Federrath et al. 2010 sec. 2.2): one candidate per
   step, the densest (then the smallest ID); true if it became a sink
------------------------------------------------------------------------- */

bool FixSPHAstroSink::try_create()
{
  gather_sinks();
  const int nlocal = atom->nlocal;
  double **x = atom->x;
  const int *mask = atom->mask;
  const double *rho = atom->dvector[rho_index_];
  const double *h = atom->dvector[h_index_];
  const SPHAstro::Fields &fields = pair_->fields();
  const double R = pair_->kernel_radius();
  const double racc2 = racc_ * racc_;

  // the densest candidate of this rank
  double best_rho = -1.0;
  tagint best_tag = 0;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & gasbit_) || !(rho[i] > rho_create_)) continue;
    if (!(R * h[i] <= racc_)) continue;                      // support inside r_acc
    if (!(fields.divv && fields.divv[i] < 0.0)) continue;    // converging flow
    bool near = false;                                       // not inside a sink's r_acc
    for (const Sink &s : sinks_) {
      double dx[3] = {x[i][0] - s.x[0], x[i][1] - s.x[1], x[i][2] - s.x[2]};
      domain->minimum_image(dx);
      if (dot(dx, dx) < racc2) near = true;
    }
    if (near) continue;
    if (rho[i] > best_rho || (rho[i] == best_rho && atom->tag[i] < best_tag)) {
      best_rho = rho[i];
      best_tag = atom->tag[i];
    }
  }
  double top_rho;
  MPI_Allreduce(&best_rho, &top_rho, 1, MPI_DOUBLE, MPI_MAX, world);
  if (!(top_rho > 0.0)) return false;
  tagint mine = (best_rho == top_rho) ? best_tag : MAXTAGINT, cand;
  MPI_Allreduce(&mine, &cand, 1, MPI_LMP_TAGINT, MPI_MIN, world);
  // the candidate's position, from its owner
  double xc[3] = {0.0, 0.0, 0.0}, xc_all[3];
  int owner = -1;
  for (int i = 0; i < nlocal; i++)
    if (atom->tag[i] == cand && (mask[i] & gasbit_)) {
      for (int d = 0; d < 3; d++) xc[d] = x[i][d];
      owner = comm->me;
    }
  int owner_all;
  MPI_Allreduce(&owner, &owner_all, 1, MPI_INT, MPI_MAX, world);
  MPI_Bcast(xc, 3, MPI_DOUBLE, owner_all, world);
  for (int d = 0; d < 3; d++) xc_all[d] = xc[d];

  std::vector<double> group_data;
  int reason = 0;
  const int ok = check_creation(cand, xc_all, group_data, reason);
  if (!ok) return false;

  // the candidate becomes a sink: sink type and group, out of the gas group, no SPH h (the
  // gravity's fixed softening)
  for (int i = 0; i < nlocal; i++) {
    if (atom->tag[i] != cand || !(mask[i] & gasbit_)) continue;
    atom->type[i] = create_type_;
    atom->mask[i] = (atom->mask[i] & ~gasbit_) | groupbit;
    atom->dvector[h_index_][i] = 0.0;
    spin_[i][0] = spin_[i][1] = spin_[i][2] = 0.0;
    macc_[i] = nacc_[i] = mlow_[i] = 0.0;
  }
  newborn_.push_back(cand);
  total_created_ += 1.0;
  if (comm->me == 0)
    utils::logmesg(lmp,
                   "fix {} sph/astro/sink: atom {} became a sink at step {} (rho = {:.6g}) at "
                   "{:.6g} {:.6g} {:.6g}\n",
                   id, cand, update->ntimestep, top_rho, xc_all[0], xc_all[1], xc_all[2]);
  return true;
}

// the checks of BBP95 sec. 2.3 (P18 sec. 2.8.4) over the gas within r_acc of the candidate,
// gathered onto every rank and summed in ID order (the same decision on any number of ranks)
int FixSPHAstroSink::check_creation(tagint cand, const double *xc, std::vector<double> &all,
                                    int &reason)
{
  const int nlocal = atom->nlocal;
  double **x = atom->x;
  double **v = atom->v;
  const int *mask = atom->mask;
  const double *h = atom->dvector[h_index_];
  const double *u = atom->dvector[u_index_];
  const double *rho = atom->dvector[rho_index_];
  const SPHAstro::PairOptions &opt = pair_->options();
  const double racc2 = racc_ * racc_;
  std::vector<double> mine;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & gasbit_)) continue;
    double dx[3] = {x[i][0] - xc[0], x[i][1] - xc[1], x[i][2] - xc[2]};
    domain->minimum_image(dx);
    if (!(dot(dx, dx) < racc2)) continue;
    // thermal energy per mass: u (ideal gas), (d/2) c_s^2 (isothermal), P/((gamma-1) rho)
    // (polytrope)
    double eth;
    if (opt.eos.type == SPHAstro::EOSType::ISOTHERMAL)
      eth = 0.5 * domain->dimension * opt.eos.cs * opt.eos.cs;
    else
      eth = opt.eos.energy_of(rho[i], u[i]);
    const double rec[MEMBER_DOUBLES] = {static_cast<double>(atom->tag[i]),
                                        atom->rmass[i],
                                        dx[0],
                                        dx[1],
                                        dx[2],
                                        v[i][0],
                                        v[i][1],
                                        v[i][2],
                                        eth,
                                        h[i]};
    mine.insert(mine.end(), rec, rec + MEMBER_DOUBLES);
  }
  all = allgather(mine, world, comm->nprocs);
  const int n = static_cast<int>(all.size() / MEMBER_DOUBLES);
  std::vector<int> order(n);
  for (int k = 0; k < n; k++) order[k] = k;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return all[a * MEMBER_DOUBLES] < all[b * MEMBER_DOUBLES];
  });
  auto rec = [&](int k) {
    return &all[order[k] * MEMBER_DOUBLES];
  };
  // centre of mass
  double M = 0.0, xcm[3] = {0, 0, 0}, vcm[3] = {0, 0, 0};
  int icand = -1;
  for (int k = 0; k < n; k++) {
    const double *r = rec(k);
    if (static_cast<tagint>(r[0]) == cand) icand = k;
    M += r[1];
    for (int d = 0; d < 3; d++) {
      xcm[d] += r[1] * r[2 + d];
      vcm[d] += r[1] * r[5 + d];
    }
  }
  if (icand < 0 || !(M > 0.0)) {
    reason = 1;
    return 0;
  }
  for (int d = 0; d < 3; d++) {
    xcm[d] /= M;
    vcm[d] /= M;
  }
  // energies: kinetic, thermal, rotational about the centre of mass; softened gravity of the
  // pairs (the kernel softening of pair sph/astro/gravity, Price & Monaghan 2007)
  double ekin = 0.0, eth = 0.0, erot = 0.0, egrav = 0.0;
  std::vector<double> phi(n, 0.0);
  for (int k = 0; k < n; k++) {
    const double *r = rec(k);
    double dr[3], dv[3], L[3];
    for (int d = 0; d < 3; d++) {
      dr[d] = r[2 + d] - xcm[d];
      dv[d] = r[5 + d] - vcm[d];
    }
    ekin += 0.5 * r[1] * dot(dv, dv);
    eth += r[1] * r[8];
    const double r2 = dot(dr, dr);
    if (r2 > 0.0) {
      cross(dr, dv, L);
      erot += 0.5 * r[1] * dot(L, L) / r2;    // m |r x v|^2 / (2 r^2): the rotational part
    }
    for (int q = k + 1; q < n; q++) {
      const double *s = rec(q);
      double dd[3] = {r[2] - s[2], r[3] - s[3], r[4] - s[4]};
      const double rij = std::sqrt(dot(dd, dd));
      double p, dp;
      SPHAstro::softened_pair(opt.kernel, rij, r[9], s[9], p, dp);
      egrav += G_ * r[1] * s[1] * p;
      phi[k] += G_ * s[1] * p;
      phi[q] += G_ * r[1] * p;
    }
  }
  // the sinks' potential at the members (softened with the gravity's fixed h where given)
  for (const Sink &s : sinks_) {
    double ds[3] = {s.x[0] - xc[0], s.x[1] - xc[1], s.x[2] - xc[2]};
    domain->minimum_image(ds);
    for (int k = 0; k < n; k++) {
      const double *r = rec(k);
      double dd[3] = {r[2] - ds[0], r[3] - ds[1], r[4] - ds[2]};
      const double rij = std::sqrt(dot(dd, dd));
      double p = -1.0 / rij, dp;
      if (hsoft_ > 0.0) SPHAstro::softened(opt.kernel, rij, hsoft_, p, dp);
      phi[k] += G_ * s.m * p;
    }
  }
  if (!(egrav < 0.0)) {
    reason = 2;
    return 0;
  }
  const double alpha = eth / -egrav, beta = erot / -egrav;
  if (alpha > 0.5) {
    reason = 3;    // thermal support (BBP95 sec. 2.3 (i))
    return 0;
  }
  if (alpha + beta > 1.0) {
    reason = 4;    // thermal and rotational support (BBP95 sec. 2.3 (ii))
    return 0;
  }
  if (!(ekin + eth + egrav < 0.0)) {
    reason = 5;    // not bound (BBP95 sec. 2.3 (iii))
    return 0;
  }
  for (int k = 0; k < n; k++)
    if (phi[k] < phi[icand]) {
      reason = 6;    // not the potential minimum (Federrath et al. 2010 sec. 2.2)
      return 0;
    }
  return 1;
}
