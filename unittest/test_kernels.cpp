/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Kernel properties for every kernel in 1, 2 and 3D: normalisation (integral of
// W over space = 1), compact support, W decreasing, and dW/dr against a
// numerical derivative.

#include "sph_astro_kernel.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace SPHAstro;

namespace {
const KernelType all_kernels[] = {KernelType::CUBIC, KernelType::QUINTIC, KernelType::WENDLAND_C2,
                                  KernelType::WENDLAND_C4, KernelType::GAUSSIAN};

// integral over d-dimensional space of a radial function: surface area of the
// unit sphere times r^(d-1), by composite Simpson on [0, R h] with n intervals
double radial_integral(KernelType k, int dim, double h, int n)
{
  const double R = kernel_radius(k) * h;
  const double surface = dim == 1 ? 2.0 : (dim == 2 ? 2.0 * M_PI : 4.0 * M_PI);
  const double dr = R / n;
  double sum = 0.0;
  for (int i = 0; i <= n; i++) {
    const double r = i * dr;
    const double wgt = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    sum += wgt * kernel_W(k, dim, r, h) * std::pow(r, dim - 1);
  }
  return surface * sum * dr / 3.0;
}
}    // namespace

class KernelTest : public ::testing::TestWithParam<std::tuple<KernelType, int>> {};

TEST_P(KernelTest, Normalised)
{
  const auto [k, dim] = GetParam();
  for (double h : {0.1, 1.0, 3.7}) {
    EXPECT_NEAR(radial_integral(k, dim, h, 20000), 1.0, 1e-9)
        << kernel_name(k) << " dim " << dim << " h " << h;
  }
}

TEST_P(KernelTest, CompactSupportAndPositive)
{
  const auto [k, dim] = GetParam();
  const double h = 0.7, R = kernel_radius(k) * h;
  // q = R up to round-off (the shifted Gaussian is exp(-q^2) - exp(-9): round-off of q
  // leaves ~1e-19 W(0))
  EXPECT_NEAR(kernel_W(k, dim, R, h), 0.0, 1e-15 * kernel_W(k, dim, 0.0, h));
  EXPECT_EQ(kernel_W(k, dim, R * (1.0 + 1e-12), h), 0.0);
  EXPECT_EQ(kernel_W(k, dim, 1.5 * R, h), 0.0);
  EXPECT_EQ(kernel_dWdr(k, dim, R * 1.01, h), 0.0);
  EXPECT_GT(kernel_W(k, dim, 0.0, h), 0.0);
  EXPECT_DOUBLE_EQ(kernel_dWdr(k, dim, 0.0, h), 0.0);
  double previous = kernel_W(k, dim, 0.0, h);
  for (int i = 1; i < 200; i++) {
    const double r = R * i / 200.0;
    const double w = kernel_W(k, dim, r, h);
    EXPECT_GT(w, 0.0) << "r = " << r;
    EXPECT_LT(w, previous) << "W must decrease, r = " << r;
    EXPECT_LT(kernel_dWdr(k, dim, r, h), 0.0) << "r = " << r;
    previous = w;
  }
}

TEST_P(KernelTest, GradientMatchesNumericalDerivative)
{
  const auto [k, dim] = GetParam();
  const double h = 1.3, R = kernel_radius(k) * h, eps = 1e-6;
  double worst = 0.0, scale = 0.0;
  for (int i = 1; i < 400; i++) {
    const double r = R * i / 400.0;
    const double numeric =
        (kernel_W(k, dim, r + eps, h) - kernel_W(k, dim, r - eps, h)) / (2 * eps);
    worst = std::max(worst, std::fabs(numeric - kernel_dWdr(k, dim, r, h)));
    scale = std::max(scale, std::fabs(kernel_dWdr(k, dim, r, h)));
  }
  EXPECT_LT(worst, 1e-7 * scale) << kernel_name(k) << " dim " << dim;
}

TEST_P(KernelTest, ScalesWithH)
{
  // W(r, h) = h^-d W(r/h, 1)
  const auto [k, dim] = GetParam();
  for (double q : {0.0, 0.3, 0.99, 1.5, 2.2})
    EXPECT_NEAR(kernel_W(k, dim, q * 2.5, 2.5), kernel_W(k, dim, q, 1.0) / std::pow(2.5, dim),
                1e-14);
}

INSTANTIATE_TEST_SUITE_P(AllKernels, KernelTest,
                         ::testing::Combine(::testing::ValuesIn(all_kernels),
                                            ::testing::Values(1, 2, 3)));

TEST(KernelNames, RoundTripAndAliases)
{
  for (auto k : all_kernels) {
    KernelType parsed;
    ASSERT_TRUE(kernel_from_name(kernel_name(k), parsed));
    EXPECT_EQ(parsed, k);
  }
  KernelType parsed;
  EXPECT_TRUE(kernel_from_name("cubic", parsed));
  EXPECT_EQ(parsed, KernelType::CUBIC);
  EXPECT_TRUE(kernel_from_name("quintic", parsed));
  EXPECT_EQ(parsed, KernelType::QUINTIC);
  EXPECT_FALSE(kernel_from_name("lucy", parsed));
}

TEST(KernelValues, CubicSplineMatchesMonaghanLattanzio)
{
  // Monaghan & Lattanzio 1985 (A&A 149, 135): W = 1/(pi h^3) [1 - 3/2 q^2 + 3/4 q^3] for
  // q <= 1, 1/4 (2-q)^3 for 1 <= q <= 2
  const double h = 2.0;
  EXPECT_NEAR(kernel_W(KernelType::CUBIC, 3, 1.0, h),
              (1 - 1.5 * 0.25 + 0.75 * 0.125) / (M_PI * 8.0), 1e-15);
  EXPECT_NEAR(kernel_W(KernelType::CUBIC, 3, 3.0, h), 0.25 * 0.125 / (M_PI * 8.0), 1e-15);
}

TEST(KernelValues, GaussianMatchesUntruncatedInsideTheSupport)
{
  // Gingold & Monaghan 1977 (MNRAS 181, 375): W = (h sqrt(pi))^-d exp(-r^2/h^2); the
  // truncated, shifted kernel is
  // sigma_d h^-d (exp(-q^2) - exp(-9)) with sigma_d 0.04-0.3 % above pi^(-d/2)
  const double h = 0.8, e9 = std::exp(-9.0);
  for (int dim : {1, 2, 3}) {
    const double w0 = std::pow(h * std::sqrt(M_PI), -dim);
    const double sigma_ratio = kernel_W(KernelType::GAUSSIAN, dim, 0.0, h) / (w0 * (1.0 - e9));
    EXPECT_NEAR(sigma_ratio, 1.0, 3.5e-3) << dim;
    EXPECT_GT(sigma_ratio, 1.0) << "truncation removes mass: sigma must grow";
    for (double q : {0.3, 1.0, 2.0, 2.9})
      EXPECT_NEAR(kernel_W(KernelType::GAUSSIAN, dim, q * h, h),
                  sigma_ratio * w0 * (std::exp(-q * q) - e9), 1e-14 * w0);
  }
  // the slope at the edge is not zero: -6 exp(-9) (in units of sigma / h^(d+1))
  const double sigma3 = kernel_W(KernelType::GAUSSIAN, 3, 0.0, 1.0) / (1.0 - e9);
  EXPECT_NEAR(kernel_dWdr(KernelType::GAUSSIAN, 3, 3.0 * (1.0 - 1e-12), 1.0) / sigma3, -6.0 * e9,
              1e-12);
  EXPECT_EQ(kernel_dWdr(KernelType::GAUSSIAN, 3, 3.0, 1.0), 0.0);
}

TEST(KernelValues, NeighbourCountForHfact)
{
  // with h = 1.2 (m/rho)^(1/3) the cubic kernel's support sphere holds about 58
  // particles
  const double n = 4.0 / 3.0 * M_PI * std::pow(KernelCubic::radius * 1.2, 3);
  EXPECT_NEAR(n, 57.9, 0.1);
}
