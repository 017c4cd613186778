/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Kernel-softened gravity (sph_astro_gravity_kernel.h) without LAMMPS: the closed forms of the
// softened force and potential of every kernel against numerical integration of the kernel's
// mass function M(<r) = 4 pi int W r^2 dr, the Newtonian limit beyond the support, finite
// values at r = 0, the M4 closed form against the generic one, and the pair symmetrisation.

#include "sph_astro_gravity_kernel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace SPHAstro;

namespace {
const KernelType all_kernels[] = {KernelType::CUBIC, KernelType::QUINTIC, KernelType::WENDLAND_C2,
                                  KernelType::WENDLAND_C4};

// M(<r)/r^2 with M by composite Simpson on [0, r] (n intervals) of 4 pi W r^2
double force_numerical(KernelType k, double r, double h, int n = 4000)
{
  if (r == 0.0) return 0.0;
  const double dr = r / n;
  double sum = 0.0;
  for (int i = 0; i <= n; i++) {
    const double s = i * dr;
    const double wgt = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    sum += wgt * kernel_W(k, 3, s, h) * s * s;
  }
  return 4.0 * M_PI * sum * dr / 3.0 / (r * r);
}

// phi(r) = -1/(R h) - int_r^{Rh} dphi/dr' dr' by Simpson over the numerical force
double potential_numerical(KernelType k, double r, double h, int n = 400)
{
  const double R = kernel_radius(k) * h;
  if (r >= R) return -1.0 / r;
  const double dr = (R - r) / n;
  double sum = 0.0;
  for (int i = 0; i <= n; i++) {
    const double s = r + i * dr;
    const double wgt = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    sum += wgt * force_numerical(k, s, h, 400);
  }
  return -1.0 / R - sum * dr / 3.0;
}
}    // namespace

class SoftenedGravityTest : public ::testing::TestWithParam<KernelType> {};

TEST_P(SoftenedGravityTest, PiecePolynomialsAreTheKernel)
{
  const KernelType k = GetParam();
  const auto &soft = softened_kernel(k);
  EXPECT_EQ(soft.radius(), kernel_radius(k));
  // w_poly is the unnormalised w(q); W(q, h = 1) = sigma w(q), sigma fixed by q = 0
  const double sigma = kernel_W(k, 3, 0.0, 1.0) / soft.w_poly(0.0);
  for (int i = 0; i <= 300; i++) {
    const double q = soft.radius() * i / 300.0;
    EXPECT_NEAR(sigma * soft.w_poly(q), kernel_W(k, 3, q, 1.0), 1e-12 * sigma)
        << kernel_name(k) << " q = " << q;
  }
}

TEST_P(SoftenedGravityTest, ForceAndPotentialMatchNumericalIntegration)
{
  const KernelType k = GetParam();
  for (double h : {0.3, 1.0, 2.5}) {
    const double R = kernel_radius(k) * h;
    for (int i = 1; i <= 40; i++) {
      const double r = 1.2 * R * i / 40.0;
      double phi, dphi;
      softened(k, r, h, phi, dphi);
      const double fref = force_numerical(k, r, h);
      EXPECT_NEAR(dphi, fref, 1e-10 * std::fabs(fref) + 1e-13 / (h * h))
          << kernel_name(k) << " h " << h << " r " << r;
      if (i % 4 == 0) {
        const double pref = potential_numerical(k, r, h);
        EXPECT_NEAR(phi, pref, 1e-9 * std::fabs(pref))
            << kernel_name(k) << " h " << h << " r " << r;
      }
    }
  }
}

TEST_P(SoftenedGravityTest, NewtonianBeyondSupportFiniteAtZero)
{
  const KernelType k = GetParam();
  const double h = 0.8, R = kernel_radius(k) * h;
  for (double r : {R, R * (1.0 + 1e-9), 1.5 * R, 10.0 * R}) {
    double phi, dphi;
    softened(k, r, h, phi, dphi);
    EXPECT_NEAR(phi, -1.0 / r, 1e-13 / r) << kernel_name(k) << " r " << r;
    EXPECT_NEAR(dphi, 1.0 / (r * r), 1e-12 / (r * r)) << kernel_name(k) << " r " << r;
  }
  // continuity just inside the support and at the piece edges
  const auto &soft = softened_kernel(k);
  for (int e = 1; e <= soft.npieces(); e++) {
    const double q = soft.edge(e);
    double p1, f1, p2, f2;
    soft.eval(q * (1.0 - 1e-12), p1, f1);
    soft.eval(q * (1.0 + 1e-12), p2, f2);
    EXPECT_NEAR(p1, p2, 1e-10) << kernel_name(k) << " edge " << q;
    EXPECT_NEAR(f1, f2, 1e-10) << kernel_name(k) << " edge " << q;
  }
  // finite at r = 0: zero force, potential -W-weighted mean of 1/r (finite, negative, the
  // deepest point), and dphi/dr -> 4 pi W(0) r / 3 for small r
  double phi0, dphi0;
  softened(k, 0.0, h, phi0, dphi0);
  EXPECT_TRUE(std::isfinite(phi0));
  EXPECT_EQ(dphi0, 0.0);
  EXPECT_LT(phi0, -1.0 / R);
  double phi_s, dphi_s;
  const double rs = 1e-4 * h;
  softened(k, rs, h, phi_s, dphi_s);
  EXPECT_NEAR(dphi_s, 4.0 * M_PI / 3.0 * kernel_W(k, 3, 0.0, h) * rs, 1e-6 * dphi_s);
  EXPECT_GT(phi_s, phi0);
}

TEST_P(SoftenedGravityTest, PairFormIsTheMeanOfBothSofteningLengths)
{
  const KernelType k = GetParam();
  for (double r : {0.1, 0.7, 1.3, 4.0}) {
    double pi, fi, pj, fj, p, f, pswap, fswap;
    softened(k, r, 0.5, pi, fi);
    softened(k, r, 1.1, pj, fj);
    softened_pair(k, r, 0.5, 1.1, p, f);
    softened_pair(k, r, 1.1, 0.5, pswap, fswap);
    EXPECT_DOUBLE_EQ(p, 0.5 * (pi + pj));
    EXPECT_DOUBLE_EQ(f, 0.5 * (fi + fj));
    EXPECT_DOUBLE_EQ(p, pswap);    // symmetric: Newton's third law holds pair by pair
    EXPECT_DOUBLE_EQ(f, fswap);
  }
}

TEST_P(SoftenedGravityTest, DphiDhMatchesFiniteDifferences)
{
  // dphi/dh = -(fpot + q fforce)/h^2 (adaptive-softening zeta terms) against the central
  // difference of phi(r, h) in h, O(eps^2) accurate, at points away from the piece edges
  const KernelType k = GetParam();
  const double h = 0.7, eps = 1e-5;
  const double R = kernel_radius(k);
  for (double q : {0.0, 0.13, 0.55, 0.93, 1.27, 1.71, 1.95, 2.4, 2.9, 3.5}) {
    const double r = q * h;
    double pp, pm, f;
    softened(k, r, h + eps, pp, f);
    softened(k, r, h - eps, pm, f);
    const double fd = (pp - pm) / (2.0 * eps);
    const double exact = softened_dphidh(k, r, h);
    if (q >= R) {
      EXPECT_EQ(exact, 0.0) << "q = " << q;    // outside the support phi = -1/r
      continue;
    }
    EXPECT_NEAR(exact, fd, 1e-7 * std::max(1.0, std::fabs(fd))) << "q = " << q;
  }
  // a wider kernel makes the potential at the centre shallower: dphi/dh(0) = -fpot(0)/h^2 > 0
  EXPECT_GT(softened_dphidh(k, 0.0, h), 0.0);
}

TEST_P(SoftenedGravityTest, KernelGradientOfTheZetaTermsIsDWdr)
{
  const KernelType k = GetParam();
  const double h = 0.8;
  for (double q : {0.1, 0.6, 1.2, 1.8, 2.5}) {
    const double r = q * h;
    EXPECT_NEAR(kernel_dwdr3(k, r, h), kernel_dWdr(k, 3, r, h), 1e-13) << "q = " << q;
  }
}

INSTANTIATE_TEST_SUITE_P(AllKernels, SoftenedGravityTest, ::testing::ValuesIn(all_kernels),
                         [](const ::testing::TestParamInfo<KernelType> &info) {
                           std::string name = kernel_name(info.param);
                           for (auto &c : name)
                             if (c == '/') c = '_';
                           return name;
                         });

TEST(SoftenedCubic, ClosedFormEqualsGenericForm)
{
  const auto &generic = softened_kernel(KernelType::CUBIC);
  for (int i = 0; i <= 500; i++) {
    const double q = 2.4 * i / 500.0;
    double p1, f1, p2, f2;
    SoftenedCubic::eval(q, p1, f1);
    generic.eval(q, p2, f2);
    EXPECT_NEAR(p1, p2, 1e-14) << "q = " << q;
    EXPECT_NEAR(f1, f2, 1e-14) << "q = " << q;
  }
  // known value: phi(0) = -7/5 h^-1 for M4 (Price & Monaghan 2007, appendix A)
  double p0, f0;
  SoftenedCubic::eval(0.0, p0, f0);
  EXPECT_DOUBLE_EQ(p0, -1.4);
}
