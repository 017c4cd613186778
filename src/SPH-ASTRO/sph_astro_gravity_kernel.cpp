/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: kernel-softened gravity, coefficients of the closed forms
------------------------------------------------------------------------- */

#include "sph_astro_gravity_kernel.h"

#include <algorithm>

namespace SPHAstro {

namespace {
  // poly += c (a + b q)^n x (p0 + p1 q + p2 q^2): the kernels' pieces written out
  void add_term(double *poly, double c, double a, double b, int n, double p0, double p1 = 0.0,
                double p2 = 0.0)
  {
    double binom[SoftenedKernel::MAXDEG + 1] = {0.0};
    // (a + b q)^n = sum_k C(n,k) a^(n-k) b^k q^k
    double cnk = 1.0;
    for (int k = 0; k <= n; k++) {
      binom[k] = cnk * std::pow(a, n - k) * std::pow(b, k);
      cnk = cnk * (n - k) / (k + 1);
    }
    const double p[3] = {p0, p1, p2};
    for (int k = 0; k <= n; k++)
      for (int m = 0; m < 3; m++)
        if (p[m] != 0.0) poly[k + m] += c * binom[k] * p[m];
  }
}    // namespace

SoftenedKernel::SoftenedKernel(KernelType type)
{
  double sigma = 0.0;
  switch (type) {
    case KernelType::CUBIC:    // 1 - 3/2 q^2 + 3/4 q^3; 1/4 (2-q)^3
      radius_ = 2.0;
      npieces_ = 2;
      sigma = KernelCubic::sigma(3);
      w_[0][0] = 1.0;
      w_[0][2] = -1.5;
      w_[0][3] = 0.75;
      add_term(w_[1], 0.25, 2.0, -1.0, 3, 1.0);
      break;
    case KernelType::QUINTIC:    // (3-q)^5 - 6 (2-q)^5 + 15 (1-q)^5, terms dropping out
      radius_ = 3.0;
      npieces_ = 3;
      sigma = KernelQuintic::sigma(3);
      for (int k = 0; k < 3; k++) add_term(w_[k], 1.0, 3.0, -1.0, 5, 1.0);
      for (int k = 0; k < 2; k++) add_term(w_[k], -6.0, 2.0, -1.0, 5, 1.0);
      add_term(w_[0], 15.0, 1.0, -1.0, 5, 1.0);
      break;
    case KernelType::WENDLAND_C2:    // (1 - q/2)^4 (1 + 2q)
      radius_ = 2.0;
      npieces_ = 1;
      sigma = KernelWendlandC2::sigma(3);
      add_term(w_[0], 1.0, 1.0, -0.5, 4, 1.0, 2.0);
      break;
    case KernelType::WENDLAND_C4:    // (1 - q/2)^6 (1 + 3q + 35/12 q^2)
      radius_ = 2.0;
      npieces_ = 1;
      sigma = KernelWendlandC4::sigma(3);
      add_term(w_[0], 1.0, 1.0, -0.5, 6, 1.0, 3.0, 35.0 / 12.0);
      break;
    case KernelType::GAUSSIAN:    // not a polynomial: refused by pair sph/astro/gravity
      radius_ = 3.0;
      npieces_ = 1;
      sigma = 0.0;
      break;
  }
  for (int k = 0; k <= npieces_; k++) edge_[k] = radius_ * k / npieces_;
  deg_ = 0;
  for (int k = 0; k < npieces_; k++)
    for (int n = 0; n <= MAXDEG; n++)
      if (w_[k][n] != 0.0) deg_ = std::max(deg_, n);

  // mass fraction M(q) = 4 pi sigma int_0^q w s^2 ds = C_k + sum_n A_n q^(n+3) on piece k
  const double fourpisigma = 4.0 * M_PI * sigma;
  double mass_at_edge = 0.0;    // M(e_k)
  for (int k = 0; k < npieces_; k++) {
    const double e0 = edge_[k], e1 = edge_[k + 1];
    double sum0 = 0.0, sum1 = 0.0;
    for (int n = 0; n <= deg_; n++) {
      force_[k][n] = fourpisigma * w_[k][n] / (n + 3);
      pot_[k][n] = force_[k][n] / (n + 2);
      sum0 += force_[k][n] * std::pow(e0, n + 3);
      sum1 += force_[k][n] * std::pow(e1, n + 3);
    }
    C_[k] = (k == 0) ? 0.0 : mass_at_edge - sum0;
    mass_at_edge = C_[k] + sum1;
  }
  // potential from outside in: fpot(R) = -1/R (the whole mass, M(R) = 1 by normalisation)
  double fpot_outer = -1.0 / radius_;
  for (int k = npieces_ - 1; k >= 0; k--) {
    const double e1 = edge_[k + 1];
    double s = 0.0;
    for (int n = 0; n <= deg_; n++) s += pot_[k][n] * std::pow(e1, n + 2);
    E_[k] = fpot_outer + C_[k] / e1 - s;
    double fp, ff;
    eval(edge_[k] > 0.0 ? edge_[k] : 0.0, fp, ff);
    fpot_outer = fp;
  }
}

double SoftenedKernel::w_poly(double q) const
{
  if (q >= radius_) return 0.0;
  int k = 0;
  while (k < npieces_ - 1 && q >= edge_[k + 1]) k++;
  double s = w_[k][deg_];
  for (int n = deg_ - 1; n >= 0; n--) s = s * q + w_[k][n];
  return s;
}

const SoftenedKernel &softened_kernel(KernelType type)
{
  static const SoftenedKernel cubic(KernelType::CUBIC), quintic(KernelType::QUINTIC),
      c2(KernelType::WENDLAND_C2), c4(KernelType::WENDLAND_C4);
  switch (type) {
    case KernelType::CUBIC:
      return cubic;
    case KernelType::QUINTIC:
      return quintic;
    case KernelType::WENDLAND_C2:
      return c2;
    case KernelType::WENDLAND_C4:
      return c4;
    case KernelType::GAUSSIAN:
      break;
  }
  return cubic;
}

}    // namespace SPHAstro
