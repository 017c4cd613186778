/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The interaction list of one group of targets of the gravity tree (sph_astro_gravity_tree.h)
// and its sums for one target: the accepted multipoles and the particles of the opened leaves,
// gathered into contiguous arrays so that each target's sums run in vector lanes.
//
// Multipole (node of mass M, centre of mass X, second moment S_ab = sum m s_a s_b about X) at
// r = x - X, to quadrupole order (the dipole vanishes about the centre of mass), for the
// Newtonian g(r) = -1/r with D1 = g'/r = 1/r^3, D2 = (D1)'/r = -3/r^5, D3 = (D2)'/r = 15/r^7:
//   phi(x) = M g(r) + 1/2 [D2 r.S.r + D1 tr S]
//   a(x)   = -grad phi = -[(M D1 + 1/2 D3 r.S.r + 1/2 D2 tr S) r + D2 S.r]
// (the Taylor expansion of g(|r - s|) summed over the node's particles; Hernquist 1987,
// ApJS 64, 715, eqs. 2.3-2.6 in traceless form). Per unit G.
//
// Particles: beyond the pair's softening support (r >= R max(h_i, h_j)) the Newtonian
// -m/r and -m r/r^3; inside it the softened phi_ij and dphi_ij/dr and the zeta term of
// sph_astro_gravity_pair.h, as pair sph/astro/gravity sums them. The target itself is left out;
// a particle at the same position gives its softened potential and no force.

#ifndef LMP_SPH_ASTRO_GRAVITY_INTERACTIONS_H
#define LMP_SPH_ASTRO_GRAVITY_INTERACTIONS_H

#include "sph_astro_gravity_pair.h"
#include "sph_astro_gravity_tree.h"
#include "sph_astro_kernel.h"

#include <cmath>
#include <vector>

namespace SPHAstro {

class GravityInteractions {
 public:
  static constexpr int LANES = 8;

  void clear() { nm_ = np_ = 0; }
  // pad the lists to whole lanes (before evaluate): massless multipoles and particles far away;
  // and the particles that may be inside the softening support of a target in box (kernel
  // radius R): those closer to it than R max(h of the box, their h); the sums inside the
  // support look only at them (all of them without a box)
  void finish(const TargetBox *box = nullptr, double R = 0.0)
  {
    near_.resize(np_);
    int nn = 0;
    for (int k = 0; k < np_; k++) {
      double d2 = 0.0;
      if (box) {
        const double c[3] = {px_[k], py_[k], pz_[k]};
        for (int d = 0; d < 3; d++) {
          const double e = std::max(std::max(box->lo[d] - c[d], c[d] - box->hi[d]), 0.0);
          d2 += e * e;
        }
      }
      const double rs = box ? R * std::max(box->hmax, ph_[k]) : 1.0;
      near_[nn] = k;
      nn += static_cast<int>(d2 < rs * rs);
    }
    nnear_ = nn;
    grow_multipoles(nm_ + LANES);
    grow_particles(np_ + LANES);
    const double q0[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    int nm = nm_, np = np_;
    while (nm % LANES) {
      mx_[nm] = my_[nm] = mz_[nm] = FAR;
      mm_[nm] = 0.0;
      qxx_[nm] = qyy_[nm] = qzz_[nm] = qxy_[nm] = qxz_[nm] = qyz_[nm] = q0[0];
      nm++;
    }
    while (np % LANES) {
      px_[np] = py_[np] = pz_[np] = FAR;
      pm_[np] = ph_[np] = pzo_[np] = 0.0;
      pid_[np] = -1;
      np++;
    }
    // (the counts stay those of the real entries: the loops run to whole lanes)
    nm_pad_ = nm;
    np_pad_ = np;
  }
  int multipoles() const { return nm_; }
  int particles() const { return np_; }

  void add_node(const GravityNode &n)
  {
    grow_multipoles(nm_ + 1);
    put_multipole(n.x, n.y, n.z, n.m, n.q);
  }
  // the items of leaf n of tree t; self_base >= 0: t is the targets' tree and source k's
  // identity is self_base + k (the target's own tree position with the same base is left out)
  void add_leaf(const GravityTree &t, const GravityNode &n, int self_base)
  {
    const int np = n.nparticles;
    grow_particles(np_ + np);
    const double *x = t.x(), *y = t.y(), *z = t.z(), *m = t.m(), *h = t.h(), *zo = t.zo();
    for (int k = n.first; k < n.first + np; k++) {
      px_[np_] = x[k];
      py_[np_] = y[k];
      pz_[np_] = z[k];
      pm_[np_] = m[k];
      ph_[np_] = h[k];
      pzo_[np_] = zo[k];
      pid_[np_] = self_base >= 0 ? self_base + k : -1;
      np_++;
    }
    const int nmp = n.count - np;
    if (nmp > 0) {
      grow_multipoles(nm_ + nmp);
      for (int k = n.first + np; k < n.first + n.count; k++)
        put_multipole(x[k], y[k], z[k], m[k], t.item_q(k));
    }
  }

  // acceleration and potential per unit G of a target at (xi, yi, zi) with softening length hi,
  // zeta/Omega zoi and identity self (-1: none); R: kernel radius. The sums over the lists run
  // in LANES partial sums (k mod LANES), added in a fixed order at the end: the same roundings
  // whatever the vector width the compiler uses
  template <bool CUBIC, bool ZETA>
  void evaluate(double xi, double yi, double zi, double hi, double zoi, int self,
                const SoftenedKernel &soft, KernelType kernel, double R, double acc[3], double &pot)
  {
    double ax[LANES] = {0.0}, ay[LANES] = {0.0}, az[LANES] = {0.0}, phi[LANES] = {0.0};
    const int nm = nm_pad_, np = np_pad_;
    // multipoles
    {
      const double *__restrict mx = mx_.data(), *__restrict my = my_.data();
      const double *__restrict mz = mz_.data(), *__restrict mm = mm_.data();
      const double *__restrict qxx = qxx_.data(), *__restrict qyy = qyy_.data();
      const double *__restrict qzz = qzz_.data(), *__restrict qxy = qxy_.data();
      const double *__restrict qxz = qxz_.data(), *__restrict qyz = qyz_.data();
      for (int k0 = 0; k0 < nm; k0 += LANES) {
        // (the lists are padded to whole lanes with massless far multipoles)
        for (int l = 0; l < LANES; l++) {
          const int k = k0 + l;
          const double dx = xi - mx[k], dy = yi - my[k], dz = zi - mz[k];
          const double r2 = dx * dx + dy * dy + dz * dz;
          const double rinv = 1.0 / std::sqrt(r2);
          const double rinv2 = rinv * rinv;
          const double D1 = rinv * rinv2;
          const double D2 = -3.0 * D1 * rinv2;
          const double D3 = -5.0 * D2 * rinv2;
          const double sx = qxx[k] * dx + qxy[k] * dy + qxz[k] * dz;
          const double sy = qxy[k] * dx + qyy[k] * dy + qyz[k] * dz;
          const double sz = qxz[k] * dx + qyz[k] * dy + qzz[k] * dz;
          const double rsr = dx * sx + dy * sy + dz * sz;
          const double tr = qxx[k] + qyy[k] + qzz[k];
          phi[l] += -mm[k] * rinv + 0.5 * (D2 * rsr + D1 * tr);
          const double c = mm[k] * D1 + 0.5 * (D3 * rsr + D2 * tr);
          ax[l] -= c * dx + D2 * sx;
          ay[l] -= c * dy + D2 * sy;
          az[l] -= c * dz + D2 * sz;
        }
      }
    }
    // particles beyond the softening support; those inside are marked
    {
      const double *__restrict px = px_.data(), *__restrict py = py_.data();
      const double *__restrict pz = pz_.data(), *__restrict pm = pm_.data();
      const double *__restrict ph = ph_.data();
      double *__restrict inside = inside_.data();
      for (int k0 = 0; k0 < np; k0 += LANES) {
        for (int l = 0; l < LANES; l++) {
          const int k = k0 + l;
          const double dx = xi - px[k], dy = yi - py[k], dz = zi - pz[k];
          const double r2 = dx * dx + dy * dy + dz * dz;
          const double rs = R * std::max(hi, ph[k]);
          // (w: 1 beyond the support, 0 inside it; as arithmetic, for the vector lanes)
          const double w = static_cast<double>(r2 >= rs * rs);
          inside[k] = 1.0 - w;
          const double rinv = 1.0 / std::sqrt(r2 * w + (1.0 - w));
          const double mr = w * pm[k] * rinv;
          const double mr3 = mr * rinv * rinv;
          phi[l] -= mr;
          ax[l] -= mr3 * dx;
          ay[l] -= mr3 * dy;
          az[l] -= mr3 * dz;
        }
      }
    }
    double sx = 0.0, sy = 0.0, sz = 0.0, sp = 0.0;
    for (int l = 0; l < LANES; l++) {
      sx += ax[l];
      sy += ay[l];
      sz += az[l];
      sp += phi[l];
    }
    // particles inside the softening support
    if (CUBIC) {
      inside_cubic<ZETA>(xi, yi, zi, hi, zoi, self, sx, sy, sz, sp);
    } else {
      for (int n = 0; n < nnear_; n++) {
        const int k = near_[n];
        if (inside_[k] == 0.0 || (self >= 0 && pid_[k] == self)) continue;
        const double dx = xi - px_[k], dy = yi - py_[k], dz = zi - pz_[k];
        const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
        double phij, dphi;
        softened_pair_inside<false>(soft, r, hi, ph_[k], phij, dphi);
        sp += pm_[k] * phij;
        if (r == 0.0) continue;    // coincident: finite potential, no force
        double D = dphi;
        if (ZETA) D += zeta_pair_term(kernel, r, hi, ph_[k], zoi, pzo_[k]);
        D *= pm_[k] / r;
        sx -= D * dx;
        sy -= D * dy;
        sz -= D * dz;
      }
    }
    acc[0] = sx;
    acc[1] = sy;
    acc[2] = sz;
    pot = sp;
  }

  // the same for the short-range part of a TreePM split (periodic boxes, kspace
  // tree/sph/astro/gravity with PPPM for the long range): the Newtonian -1/r replaced by
  // g(r) = -erfc(g_e r)/r (Bagla 2002, J. Astrophys. Astron. 23, 185; Springel 2005, MNRAS 364,
  // 1105, eq. 21), the multipoles expanded in it with, for E = 2 g_e/sqrt(pi) exp(-g_e^2 r^2),
  //   D1 = (erfc + r E)/r^3,  D2 = -N/r^5,  N = 3 erfc + (3 r + 2 g_e^2 r^3) E,
  //   D3 = (5 N + 4 g_e^4 r^5 E)/r^7
  // (g_e -> 0: 1/r^3, -3/r^5, 15/r^7); particles and multipoles beyond rcut left out (a node
  // across the cutoff is taken whole: erfc(g_e rcut) is of the order of PPPM's accuracy);
  // inside the softening support the softened pair minus the long range -erf(g_e r)/r that
  // PPPM supplies, as pair sph/astro/gravity's short range with PPPM. Scalar sums (erfc and exp
  // in each term).
  template <bool CUBIC, bool ZETA>
  void evaluate_split(double xi, double yi, double zi, double hi, double zoi, int self,
                      const SoftenedKernel &soft, KernelType kernel, double R, double g,
                      double rcut, double acc[3], double &pot, double *virial = nullptr)
  {
    // virial: sum over the terms of r (x) a (per unit G and target mass), r = x_i - x_source
    double v[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    auto tally = [&](double dx, double dy, double dz, double fx, double fy, double fz) {
      v[0] += dx * fx;
      v[1] += dy * fy;
      v[2] += dz * fz;
      v[3] += dx * fy;
      v[4] += dx * fz;
      v[5] += dy * fz;
    };
    constexpr double two_over_sqrtpi = 1.1283791670955126;
    const double g2 = g * g;
    double ax = 0.0, ay = 0.0, az = 0.0, phi = 0.0;
    const double rcut2 = rcut * rcut;
    for (int k = 0; k < nm_; k++) {
      const double dx = xi - mx_[k], dy = yi - my_[k], dz = zi - mz_[k];
      const double r2 = dx * dx + dy * dy + dz * dz;
      if (r2 >= rcut2) continue;    // (as a particle beyond the cutoff)
      const double r = std::sqrt(r2), rinv = 1.0 / r, rinv2 = rinv * rinv;
      const double erfc = std::erfc(g * r);
      const double E = two_over_sqrtpi * g * std::exp(-g2 * r2);
      const double D1 = (erfc + r * E) * rinv * rinv2;
      const double N = 3.0 * erfc + (3.0 * r + 2.0 * g2 * r2 * r) * E;
      const double D2 = -N * rinv2 * rinv2 * rinv;
      const double D3 = (5.0 * N + 4.0 * g2 * g2 * r2 * r2 * r * E) * rinv2 * rinv2 * rinv2 * rinv;
      const double sx = qxx_[k] * dx + qxy_[k] * dy + qxz_[k] * dz;
      const double sy = qxy_[k] * dx + qyy_[k] * dy + qyz_[k] * dz;
      const double sz = qxz_[k] * dx + qyz_[k] * dy + qzz_[k] * dz;
      const double rsr = dx * sx + dy * sy + dz * sz;
      const double tr = qxx_[k] + qyy_[k] + qzz_[k];
      phi += -mm_[k] * erfc * rinv + 0.5 * (D2 * rsr + D1 * tr);
      const double c = mm_[k] * D1 + 0.5 * (D3 * rsr + D2 * tr);
      const double fx = -(c * dx + D2 * sx), fy = -(c * dy + D2 * sy), fz = -(c * dz + D2 * sz);
      ax += fx;
      ay += fy;
      az += fz;
      if (virial) tally(dx, dy, dz, fx, fy, fz);
    }
    for (int k = 0; k < np_; k++) {
      if (self >= 0 && pid_[k] == self) continue;
      const double dx = xi - px_[k], dy = yi - py_[k], dz = zi - pz_[k];
      const double r2 = dx * dx + dy * dy + dz * dz;
      if (r2 >= rcut2) continue;
      const double r = std::sqrt(r2);
      const double hj = ph_[k], rs = R * std::max(hi, hj);
      double e, D;
      if (r < rs) {
        double phij, dphi;
        softened_pair_inside<CUBIC>(soft, r, hi, hj, phij, dphi);
        if (r == 0.0) {    // coincident: finite potential, no force
          phi += pm_[k] * (phij + two_over_sqrtpi * g);
          continue;
        }
        const double erfc_r = std::erfc(g * r) / r;
        e = phij + 1.0 / r - erfc_r;
        D = dphi - 1.0 / r2 + erfc_r / r + two_over_sqrtpi * g * std::exp(-g2 * r2) / r;
        if (ZETA) D += zeta_pair_term(kernel, r, hi, hj, zoi, pzo_[k]);
      } else {
        const double erfc_r = std::erfc(g * r) / r;
        e = -erfc_r;
        D = erfc_r / r + two_over_sqrtpi * g * std::exp(-g2 * r2) / r;
      }
      D *= pm_[k] / r;
      phi += pm_[k] * e;
      ax -= D * dx;
      ay -= D * dy;
      az -= D * dz;
      if (virial) tally(dx, dy, dz, -D * dx, -D * dy, -D * dz);
    }
    acc[0] = ax;
    acc[1] = ay;
    acc[2] = az;
    pot = phi;
    if (virial)
      for (int c = 0; c < 6; c++) virial[c] = v[c];
  }

  // M4: the pairs inside the softening support gathered, then summed in vector lanes with the
  // closed forms of SoftenedCubic and KernelCubic::dw evaluated without branches (the same
  // polynomials; a pair at r = 0 has its potential and no force)
  template <bool ZETA>
  void inside_cubic(double xi, double yi, double zi, double hi, double zoi, int self, double &sx,
                    double &sy, double &sz, double &sp)
  {
    // (the list of those inside, without branches, among the group's near ones)
    int ni = 0;
    const double *inside = inside_.data();
    const int *pid = pid_.data();
    int *idx = idx_.data();
    const int anyone = self < 0;
    for (int n = 0; n < nnear_; n++) {
      const int k = near_[n];
      idx[ni] = k;
      ni += static_cast<int>(inside[k] != 0.0) & (anyone | static_cast<int>(pid[k] != self));
    }
    if (ni == 0) return;
    if (static_cast<int>(gx_.size()) < ni + LANES)
      for (auto *v : {&gx_, &gy_, &gz_, &gm_, &gh_, &gzo_}) v->resize(2 * (ni + LANES));
    for (int t = 0; t < ni; t++) {
      const int k = idx_[t];
      gx_[t] = xi - px_[k];
      gy_[t] = yi - py_[k];
      gz_[t] = zi - pz_[k];
      gm_[t] = pm_[k];
      gh_[t] = ph_[k];
      gzo_[t] = pzo_[k];
    }
    int npad = ni;
    while (npad % LANES) {    // massless, at one kernel radius
      gx_[npad] = 2.0 * hi;
      gy_[npad] = gz_[npad] = 0.0;
      gm_[npad] = gzo_[npad] = 0.0;
      gh_[npad] = hi;
      npad++;
    }
    const double *__restrict dxs = gx_.data(), *__restrict dys = gy_.data();
    const double *__restrict dzs = gz_.data(), *__restrict ms = gm_.data();
    const double *__restrict hs = gh_.data(), *__restrict zos = gzo_.data();
    const double hiinv = 1.0 / hi;
    const double sigma = KernelCubic::sigma(3);
    double ax[LANES] = {0.0}, ay[LANES] = {0.0}, az[LANES] = {0.0}, phi[LANES] = {0.0};
    for (int k0 = 0; k0 < npad; k0 += LANES) {
      for (int l = 0; l < LANES; l++) {
        const int k = k0 + l;
        const double dx = dxs[k], dy = dys[k], dz = dzs[k];
        const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
        const double hjinv = 1.0 / hs[k];
        double fpi, ffi, fpj, ffj;
        cubic_softened(r * hiinv, fpi, ffi);
        cubic_softened(r * hjinv, fpj, ffj);
        const double phij = 0.5 * (fpi * hiinv + fpj * hjinv);
        double D = 0.5 * (ffi * hiinv * hiinv + ffj * hjinv * hjinv);
        if (ZETA) {
          const double h4i = hiinv * hiinv * hiinv * hiinv, h4j = hjinv * hjinv * hjinv * hjinv;
          D += 0.5 *
              (zoi * sigma * cubic_dw(r * hiinv) * h4i +
               zos[k] * sigma * cubic_dw(r * hjinv) * h4j);
        }
        const double rinv = r > 0.0 ? 1.0 / r : 0.0;
        D *= ms[k] * rinv;
        phi[l] += ms[k] * phij;
        ax[l] -= D * dx;
        ay[l] -= D * dy;
        az[l] -= D * dz;
      }
    }
    for (int l = 0; l < LANES; l++) {
      sx += ax[l];
      sy += ay[l];
      sz += az[l];
      sp += phi[l];
    }
  }

  // SoftenedCubic::eval and KernelCubic::dw as selects (no branches, for the vector lanes), with
  // one division (the same polynomials; SoftenedCubic's divisions by constants become products
  // with their reciprocals: round-off apart)
  static inline void cubic_softened(double q, double &fpot, double &fforce)
  {
    constexpr double third = 1.0 / 3.0, sixth = 1.0 / 6.0, thirtieth = 1.0 / 30.0;
    constexpr double fifteenth = 1.0 / 15.0;
    const double q2 = q * q;
    const double qinv = 1.0 / (q < 1.0 ? 1.0 : q);
    const double qinv2 = qinv * qinv;
    const double fp1 = q2 * (2.0 * third + q2 * (-0.3 + 0.1 * q)) - 1.4;
    const double ff1 = q * (4.0 * third + q2 * (-1.2 + 0.5 * q));
    const double fp2 =
        q2 * (4.0 * third + q * (-1.0 + q * (0.3 - q * thirtieth))) - 1.6 + fifteenth * qinv;
    const double ff2 = q * (8.0 * third + q * (-3.0 + q * (1.2 - q * sixth))) - fifteenth * qinv2;
    fpot = q < 1.0 ? fp1 : (q < 2.0 ? fp2 : -qinv);
    fforce = q < 1.0 ? ff1 : (q < 2.0 ? ff2 : qinv2);
  }
  static inline double cubic_dw(double q)
  {
    const double t = 2.0 - q;
    return q < 1.0 ? q * (-3.0 + 2.25 * q) : (q < 2.0 ? -0.75 * t * t : 0.0);
  }

  double memory_usage() const
  {
    return (mx_.capacity() * 10 + px_.capacity() * 6) * sizeof(double) +
        (pid_.capacity() + idx_.capacity() + near_.capacity()) * sizeof(int) +
        (inside_.capacity() + 6 * gx_.capacity()) * sizeof(double);
  }

 private:
  static constexpr double FAR = 1e150;    // padding: 1/r^3 of it is 0, its mass 0 too
  int nm_ = 0, np_ = 0, nm_pad_ = 0, np_pad_ = 0;
  std::vector<double> mx_, my_, mz_, mm_, qxx_, qyy_, qzz_, qxy_, qxz_, qyz_;
  std::vector<double> px_, py_, pz_, pm_, ph_, pzo_;
  std::vector<int> pid_, idx_;
  std::vector<int> near_;    // the particles that may be inside a target's softening support
  int nnear_ = 0;
  std::vector<double> inside_;
  std::vector<double> gx_, gy_, gz_, gm_, gh_, gzo_;    // the pairs inside the support

  void grow_multipoles(int n)
  {
    if (n <= static_cast<int>(mx_.size())) return;
    const size_t cap = std::max<size_t>(2 * mx_.size(), n);
    for (auto *v : {&mx_, &my_, &mz_, &mm_, &qxx_, &qyy_, &qzz_, &qxy_, &qxz_, &qyz_})
      v->resize(cap);
  }
  void grow_particles(int n)
  {
    if (n <= static_cast<int>(px_.size())) return;
    const size_t cap = std::max<size_t>(2 * px_.size(), n);
    for (auto *v : {&px_, &py_, &pz_, &pm_, &ph_, &pzo_}) v->resize(cap);
    pid_.resize(cap);
    idx_.resize(cap);
    inside_.resize(cap);
  }
  void put_multipole(double x, double y, double z, double m, const double *q)
  {
    mx_[nm_] = x;
    my_[nm_] = y;
    mz_[nm_] = z;
    mm_[nm_] = m;
    qxx_[nm_] = q[0];
    qyy_[nm_] = q[1];
    qzz_[nm_] = q[2];
    qxy_[nm_] = q[3];
    qxz_[nm_] = q[4];
    qyz_[nm_] = q[5];
    nm_++;
  }
};

}    // namespace SPHAstro

#endif
