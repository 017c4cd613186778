/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The dissipative pair terms and the viscosity switch as plain functions.

#include "sph_astro_pair_terms.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace SPHAstro;

TEST(Viscosity, ClassicOnlyForApproachingPairs)
{
  EXPECT_EQ(viscosity_classic(+0.3, 1.0, 1.0, 1.0, 2.0, 0.01, 1.0, 1.0), 0.0);
  // mu = h v.r / (r^2 + eps h^2) = -0.5 / 1.01; Pi = (-alpha c mu + beta mu^2)
  // / rho
  const double mu = -0.5 / 1.01;
  EXPECT_NEAR(viscosity_classic(-0.5, 1.0, 1.0, 1.0, 2.0, 0.01, 1.3, 0.8),
              (-1.3 * mu + 2.0 * mu * mu) / 0.8, 1e-15);
  EXPECT_GT(viscosity_classic(-0.5, 1.0, 1.0, 1.0, 2.0, 0.01, 1.3, 0.8), 0.0);
}

TEST(Conductivity, CoefficientIsTheSignalOverTheMeanDensityForBothPartners)
{
  // alpha_u sqrt(|P_i - P_j| / rho_ij) / rho_ij, the same seen from i and from j (so the flux
  // coefficient x (u_i - u_j) runs from hot to cold and is antisymmetric)
  const double k = conductivity_coefficient(1.5, 1.0, 0.5, 0.8);
  EXPECT_NEAR(k, 1.5 * std::sqrt(0.5 / 0.8) / 0.8, 1e-15);
  EXPECT_GT(k, 0.0);
  EXPECT_DOUBLE_EQ(conductivity_coefficient(1.5, 0.5, 1.0, 0.8), k);
  EXPECT_DOUBLE_EQ(conductivity_coefficient(3.0, 1.0, 0.5, 0.8), 2.0 * k);
  // no pressure difference: no signal, no flux (a contact in pressure balance
  // keeps its u jump only through the pressure noise it creates)
  EXPECT_EQ(conductivity_coefficient(1.0, 0.7, 0.7, 1.0), 0.0);
}

// the per-particle factor of the geometric-mean pressure term, g = sqrt(P)/rho (the term
// itself and its energy: test_iact.cpp, which calls the interaction the pair loop runs)
TEST(PressureGeometric, FactorIsTheRootOfPOverRhoSquared)
{
  EXPECT_NEAR(pressure_geometric_factor(1.3, 0.9), std::sqrt(1.3) / 0.9, 1e-15);
  const double g = pressure_geometric_factor(0.7, 1.1);
  EXPECT_NEAR(g * g, 0.7 / (1.1 * 1.1), 1e-15);
}

// Continuity equation (Monaghan 1992, ARA&A 30, 543): zero for equal velocities whatever the
// kernel; a pair
// approaching (v_ij . r_ij < 0, dW/dr < 0) raises the density of both
TEST(Continuity, RateVanishesForUniformMotionAndGrowsUnderCompression)
{
  EXPECT_EQ(continuity_rate(0.5, 0.0, -2.0), 0.0);
  EXPECT_GT(continuity_rate(0.5, -0.3, -2.0), 0.0);
  EXPECT_LT(continuity_rate(0.5, +0.3, -2.0), 0.0);
}

// reference: RK4 with tiny steps of the switch ODE for a prescribed div v(t)
static double ode_reference(double alpha, double t_end, double cs, double h, double amin,
                            double amax, double ell)
{
  auto divv = [](double t) {
    return -3.0 * std::sin(2.0 * t) * std::exp(-t);
  };
  auto rhs = [&](double t, double a) {
    const double s = divv(t) < 0.0 ? -divv(t) : 0.0;
    return -(a - amin) * ell * cs / h + s * (amax - a);
  };
  const int n = 200000;
  const double dt = t_end / n;
  for (int k = 0; k < n; k++) {
    const double t = k * dt;
    const double k1 = rhs(t, alpha), k2 = rhs(t + 0.5 * dt, alpha + 0.5 * dt * k1);
    const double k3 = rhs(t + 0.5 * dt, alpha + 0.5 * dt * k2), k4 = rhs(t + dt, alpha + dt * k3);
    alpha += dt / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  return alpha;
}

static double switch_march(double alpha, double t_end, int n, double cs, double h, double amin,
                           double amax, double ell)
{
  auto divv = [](double t) {
    return -3.0 * std::sin(2.0 * t) * std::exp(-t);
  };
  const double dt = t_end / n;
  for (int k = 0; k < n; k++)    // div v at the end of the step, as after a force evaluation
    alpha = switch_morris_monaghan(alpha, divv((k + 1) * dt), cs, h, dt, amin, amax, ell);
  return alpha;
}

TEST(MorrisMonaghanSwitch, DecaysExponentiallyWithoutCompression)
{
  // alpha = alpha_min + (alpha_0 - alpha_min) exp(-t l c / h), any step size
  const double a = switch_morris_monaghan(1.0, 0.3, 2.0, 0.5, 0.7, 0.1, 1.5, 0.2);
  EXPECT_NEAR(a, 0.1 + 0.9 * std::exp(-0.7 * 0.2 * 2.0 / 0.5), 1e-14);
}

TEST(MorrisMonaghanSwitch, FollowsItsODEForAPrescribedDivergence)
{
  const double ref = ode_reference(0.1, 1.0, 1.0, 0.1, 0.1, 1.5, 0.2);
  const double e1 = std::fabs(switch_march(0.1, 1.0, 300, 1.0, 0.1, 0.1, 1.5, 0.2) - ref);
  const double e2 = std::fabs(switch_march(0.1, 1.0, 600, 1.0, 0.1, 0.1, 1.5, 0.2) - ref);
  printf("switch ODE: alpha(1) = %.6f, error %.2e (300 steps), %.2e (600 steps)\n", ref, e1, e2);
  EXPECT_GT(ref, 0.5);    // well above alpha_min: the source term acts
  EXPECT_LT(e1, 2e-2);
  EXPECT_NEAR(e1 / e2, 2.0,
              0.3);    // first order in dt with div v sampled once per step
}

TEST(MorrisMonaghanSwitch, StaysWithinBoundsForHugeSteps)
{
  for (double dt : {1e-3, 1.0, 1e3})
    for (double divv : {-1e6, -1.0, 0.0, 5.0}) {
      const double a = switch_morris_monaghan(0.7, divv, 1.0, 0.1, dt, 0.1, 1.5, 0.2);
      EXPECT_GE(a, 0.1);
      EXPECT_LE(a, 1.5);
    }
}

TEST(Viscosity, SignalVelocityFormOfMonaghan1997)
{
  // receding pairs: nothing
  EXPECT_EQ(viscosity_signal(+0.3, 1.0, 1.0, 3.0, 1.0, 1.0, 1.0), 0.0);
  // w = v.r / r = -0.5 / 2; v_sig = c_i + c_j - 3 w; Pi = -alpha/2 v_sig w / rho
  const double w = -0.25, vsig = 1.3 + 0.7 - 3.0 * w;
  EXPECT_DOUBLE_EQ(signal_velocity(w, 1.3, 0.7, 3.0), vsig);
  EXPECT_NEAR(viscosity_signal(-0.5, 2.0, 0.8, 3.0, 1.3, 0.7, 0.9), -0.4 * vsig * w / 0.9, 1e-15);
  // receding pairs still carry the sound speeds (Courant criterion)
  EXPECT_DOUBLE_EQ(signal_velocity(+0.4, 1.3, 0.7, 3.0), 2.0);
  // symmetric in i and j; the Balsara factor scales Pi itself
  EXPECT_DOUBLE_EQ(viscosity_signal(-0.5, 2.0, 1.0, 3.0, 1.3, 0.7, 0.9),
                   viscosity_signal(-0.5, 2.0, 1.0, 3.0, 0.7, 1.3, 0.9));
  EXPECT_NEAR(viscosity_signal(-0.5, 2.0, 1.0, 3.0, 1.3, 0.7, 0.9, 0.25),
              0.25 * viscosity_signal(-0.5, 2.0, 1.0, 3.0, 1.3, 0.7, 0.9), 1e-15);
}

TEST(CullenDehnenSwitch, LimiterSeparatesCompressionFromShearAndExpansion)
{
  EXPECT_DOUBLE_EQ(cullen_dehnen_limiter(-2.0, 0.0), 1.0);    // pure compression
  EXPECT_DOUBLE_EQ(cullen_dehnen_limiter(0.0, 3.0), 0.0);     // pure shear/rotation
  EXPECT_DOUBLE_EQ(cullen_dehnen_limiter(+2.0, 1.0), 0.0);    // expansion
  EXPECT_DOUBLE_EQ(cullen_dehnen_limiter(-1.0, 1.0), 0.5);
  EXPECT_DOUBLE_EQ(cullen_dehnen_limiter(0.0, 0.0), 1.0);    // no flow: no veto
}

TEST(CullenDehnenSwitch, LocalAlphaFromTheGrowthOfCompression)
{
  // alpha_loc = 10 h^2 xi max(-d(div v)/dt, 0) / c^2, clamped to [alpha_min, alpha_max]
  EXPECT_NEAR(cullen_dehnen_alpha_loc(-2.0, 1.0, 1.0, 0.1, 0.0, 1.5), 10 * 0.01 * 2.0, 1e-15);
  EXPECT_DOUBLE_EQ(cullen_dehnen_alpha_loc(-2e4, 1.0, 1.0, 0.1, 0.0, 1.5), 1.5);
  EXPECT_DOUBLE_EQ(cullen_dehnen_alpha_loc(+2.0, 1.0, 1.0, 0.1, 0.05, 1.5), 0.05);
  EXPECT_DOUBLE_EQ(cullen_dehnen_alpha_loc(-2.0, 0.0, 1.0, 0.1, 0.05, 1.5), 0.05);
  EXPECT_DOUBLE_EQ(cullen_dehnen_alpha_loc(-2.0, 1.0, 0.0, 0.1, 0.05, 1.5), 1.5);    // cold
}

TEST(CullenDehnenSwitch, JumpsUpAtOnceAndDecaysExponentially)
{
  // a growing compression lifts alpha to alpha_loc in one step, whatever dt
  const double aloc = cullen_dehnen_alpha_loc(-5.0, 1.0, 1.0, 0.1, 0.1, 1.5);
  EXPECT_DOUBLE_EQ(switch_cullen_dehnen(0.1, -1.0, -5.0, 0.0, 1.0, 0.1, 1e-6, 0.1, 1.5, 0.2), aloc);
  // no source: alpha = alpha_min + (alpha_0 - alpha_min) exp(-t l c / h) for any step size
  for (int n : {1, 7, 100}) {
    double a = 1.2;
    for (int k = 0; k < n; k++)
      a = switch_cullen_dehnen(a, 0.5, 0.0, 1.0, 2.0, 0.5, 0.7 / n, 0.1, 1.5, 0.2);
    EXPECT_NEAR(a, 0.1 + 1.1 * std::exp(-0.7 * 0.2 * 2.0 / 0.5), 1e-14) << n;
  }
  // in [alpha_min, alpha_max] for any input
  for (double dt : {1e-3, 1.0, 1e3})
    for (double ddivvdt : {-1e9, -1.0, 0.0, 5.0}) {
      const double a = switch_cullen_dehnen(0.7, -1.0, ddivvdt, 0.3, 1.0, 0.1, dt, 0.1, 1.5, 0.2);
      EXPECT_GE(a, 0.1);
      EXPECT_LE(a, 1.5);
    }
}

// ---- slope-limited reconstruction of the viscosity's velocities (sph_astro_reconstruction.h)

#include "sph_astro_reconstruction.h"

#include <random>

namespace {
// sums M, G of a linear field v = A r around a particle at the origin, over random neighbours
// with kernel-like weights (any weights: the gradient must come out exact)
template <int DIM> void linear_field_sums(const double A[3][3], double *sums, int n, int seed)
{
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < VGRAD_SUMS; k++) sums[k] = 0.0;
  for (int p = 0; p < n; p++) {
    double r[3] = {u(gen), u(gen), DIM == 3 ? u(gen) : 0.0};
    const double q = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    const double w = -(2.0 - q) * (2.0 - q) / (q + 1e-3);    // (dW/dr)/r < 0, as in the pair
    // r_ij = x_i - x_j = -r, v_ij = v_i - v_j = -A r
    double dv[3];
    for (int a = 0; a < 3; a++) dv[a] = -(A[a][0] * r[0] + A[a][1] * r[1] + A[a][2] * r[2]);
    velocity_gradient_add(sums, w, dv[0], dv[1], dv[2], -r[0], -r[1], -r[2]);
  }
}
}    // namespace

TEST(Reconstruction, LinearlyExactGradient3D)
{
  const double A[3][3] = {{-1.0, 0.3, 0.2}, {0.7, -0.5, -0.4}, {0.1, 0.9, 2.0}};
  double sums[VGRAD_SUMS], sym[6];
  linear_field_sums<3>(A, sums, 40, 1);
  ASSERT_TRUE(velocity_gradient_symmetric<3>(sums, sym));
  EXPECT_NEAR(sym[0], A[0][0], 1e-12);
  EXPECT_NEAR(sym[1], A[1][1], 1e-12);
  EXPECT_NEAR(sym[2], A[2][2], 1e-12);
  EXPECT_NEAR(sym[3], 0.5 * (A[0][1] + A[1][0]), 1e-12);
  EXPECT_NEAR(sym[4], 0.5 * (A[0][2] + A[2][0]), 1e-12);
  EXPECT_NEAR(sym[5], 0.5 * (A[1][2] + A[2][1]), 1e-12);
}

TEST(Reconstruction, LinearlyExactGradient2D)
{
  const double A[3][3] = {{0.4, -1.2, 0.0}, {0.6, -2.0, 0.0}, {0.0, 0.0, 0.0}};
  double sums[VGRAD_SUMS], sym[6];
  linear_field_sums<2>(A, sums, 12, 2);
  ASSERT_TRUE(velocity_gradient_symmetric<2>(sums, sym));
  EXPECT_NEAR(sym[0], 0.4, 1e-12);
  EXPECT_NEAR(sym[1], -2.0, 1e-12);
  EXPECT_NEAR(sym[3], -0.3, 1e-12);
  EXPECT_EQ(sym[2], 0.0);
  EXPECT_EQ(sym[4], 0.0);
  EXPECT_EQ(sym[5], 0.0);
}

TEST(Reconstruction, SingularNeighbourhoodGivesNoGradient)
{
  // 3D particle whose neighbours all lie in one plane (z = 0), and one without neighbours
  const double A[3][3] = {{-1.0, 0.0, 0.0}, {0.0, -1.0, 0.0}, {0.0, 0.0, -1.0}};
  double sums[VGRAD_SUMS], sym[6] = {1, 1, 1, 1, 1, 1};
  linear_field_sums<2>(A, sums, 20, 3);
  EXPECT_FALSE(velocity_gradient_symmetric<3>(sums, sym));
  for (double s : sym) EXPECT_EQ(s, 0.0);
  double none[VGRAD_SUMS] = {};
  EXPECT_FALSE(velocity_gradient_symmetric<3>(none, sym));
  EXPECT_FALSE(velocity_gradient_symmetric<2>(none, sym));
}

TEST(Reconstruction, VanLeerLimiter)
{
  EXPECT_DOUBLE_EQ(van_leer_limiter(-0.3, -0.3), 1.0);
  EXPECT_EQ(van_leer_limiter(-0.3, 0.2), 0.0);    // slopes of opposite sign: no reconstruction
  EXPECT_EQ(van_leer_limiter(0.0, -1.0), 0.0);
  EXPECT_DOUBLE_EQ(van_leer_limiter(-1.0, -3.0), 4.0 * 3.0 / 16.0);
  EXPECT_DOUBLE_EQ(van_leer_limiter(-1.0, -3.0), van_leer_limiter(-3.0, -1.0));
  for (double a : {1e-6, 0.1, 0.5, 0.9, 1.1, 3.0, 1e6}) EXPECT_LE(van_leer_limiter(a, 1.0), 1.0);
}

TEST(Reconstruction, LinearFlowLeavesNoApproachSpeed)
{
  // a pair in the linear flow v = -x: v_ij . r_ij = -r^2 = s_i = s_j; beyond the spacing
  // the reconstructed approach vanishes, well inside it the full one comes back
  const double r = 0.8;
  EXPECT_NEAR(reconstructed_vdotr(-r * r, -r * r, -r * r, r, 0.5, 1.0), 0.0, 1e-15);
  EXPECT_NEAR(reconstructed_vdotr(-r * r, -r * r, -r * r, r, 0.8, 1.0), 0.0, 1e-15);
  const double close = 0.1;    // (0.1 - 0.9) / 0.2 = -4: Phi = exp(-16)
  EXPECT_NEAR(reconstructed_vdotr(-close * close, -close * close, -close * close, close, 0.9, 1.0),
              -close * close, 1e-8);
  // across a shock the slopes differ in sign: the plain approach speed
  EXPECT_EQ(reconstructed_vdotr(-0.5, -0.4, 0.1, r, 0.5, 1.0), -0.5);
}
