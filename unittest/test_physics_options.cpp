/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// LAMMPS-driven tests of the optional physics of SPH-ASTRO: physical heat conduction
// (pair_style sph/astro conduction KAPPA, its timestep criterion fix sph/astro conduction C),
// the timestep criterion of the artificial conductivity (fix sph/astro conductivity C),
// XSPH drift smoothing (fix sph/astro xsph EPS), and the errors for bad values of these
// keywords. The analytic diffusion test is examples/conduction (ctest conduction_short).

#include "lammps_fixture.h"

#include "fix.h"
#include "force.h"
#include "modify.h"
#include "pair.h"

#include <cmath>
#include <cstdio>

using namespace sph_astro_test;
using LAMMPS_NS::LAMMPS;

namespace {
enum { MASS, PX, PY, PZ, LX, LY, LZ, EKIN, ETHERM, EPOT, ETOT, DEREL };

double **fix_array(const std::unique_ptr<LAMMPS> &lmp, const char *id)
{
  return static_cast<double **>(
      lammps_extract_fix(lmp.get(), id, LMP_STYLE_ATOM, LMP_TYPE_ARRAY, 0, 0));
}
}    // namespace

// ---------------------------------------------------------------- conduction

// GetParam(): extra command (variable smoothing length) or ""
class Conduction : public ::testing::TestWithParam<std::string> {};

TEST_P(Conduction, ConservesThermalEnergyPairByPairAndFlowsFromHotToCold)
{
  auto lmp = open_lammps();
  // disordered gas at rest with u varying by +-20 %: with v = 0 the P dV term vanishes and
  // du/dt is the conduction alone
  gas(lmp, "box", 3, "sph/astro eos ideal $(5.0/3.0) viscosity none conduction 0.7", "sph/astro");
  if (!GetParam().empty()) commands(lmp, {GetParam()});
  commands(lmp, {"velocity all set 0.0 0.0 0.0", "run 0"});
  const auto u = per_atom(lmp, "u");
  const auto dudt = per_atom(lmp, "dudt");
  double sum = 0.0, sum_abs = 0.0;
  int hottest = 0, coldest = 0;
  for (const auto &[id, rate] : dudt) {
    sum += 0.25 * rate;
    sum_abs += 0.25 * std::fabs(rate);
    if (!hottest || u.at(id) > u.at(hottest)) hottest = id;
    if (!coldest || u.at(id) < u.at(coldest)) coldest = id;
  }
  printf("conduction: sum m du/dt = %.3e of sum |m du/dt| = %.3e\n", sum, sum_abs);
  ASSERT_GT(sum_abs, 0.0);
  EXPECT_LT(std::fabs(sum), 1e-13 * sum_abs);
  EXPECT_LT(dudt.at(hottest), 0.0);
  EXPECT_GT(dudt.at(coldest), 0.0);
}

INSTANTIATE_TEST_SUITE_P(PairSPHAstro, Conduction,
                         ::testing::Values("", "fix hvar all sph/astro/h iterate hfact 1.2"));

TEST(Conduction, RateIsKappaOverRhoTimesTheLaplacian)
{
  // u = 1 + 0.01 x^2 on a perfect periodic-free interior: d2u/dx2 = 0.02, so du/dt = kappa /
  // rho x 0.02 for particles away from the box edges (Brookshaw 1985)
  auto lmp = open_lammps();
  gas(lmp, "box", 6, "sph/astro kernel m6 eos ideal $(5.0/3.0) viscosity none conduction 0.5",
      "sph/astro", 1.0, 0.0);
  commands(lmp,
           {"set group all d_h " + num(1.0 * std::cbrt(0.25)),
            "variable uq atom 1.0+0.01*(x-3.0)^2", "set group all d_u v_uq",
            "velocity all set 0.0 0.0 0.0", "run 0"});
  const auto x = per_atom(lmp, "x");
  const auto dudt = per_atom(lmp, "dudt");
  int n = 0;
  double worst = 0.0;
  for (const auto &[id, rate] : dudt) {
    if (std::fabs(x.at(id) - 3.0) > 1.0) continue;    // the quadratic wraps at the box edge
    worst = std::max(worst, std::fabs(rate / (0.5 * 0.02) - 1.0));
    n++;
  }
  printf("conduction of a quadratic profile (m6): worst relative error %.3e over %d particles\n",
         worst, n);
  ASSERT_GT(n, 50);
  EXPECT_LT(worst, 0.01);
}

TEST(Conduction, TimestepCriterion)
{
  auto lmp = open_lammps();
  gas(lmp, "box", 3, "sph/astro eos ideal $(5.0/3.0) viscosity none conduction 40.0",
      "sph/astro conduction 0.05", 1.0, 0.0);
  commands(lmp, {"velocity all set 0.0 0.0 0.0", "run 1"});
  auto *fix = lmp->modify->get_fix_by_id("gas");
  const auto rho = per_atom(lmp, "rho");
  const auto h = per_atom(lmp, "h");
  double expected = INFINITY;
  for (const auto &[id, r] : rho)
    expected = std::min(expected, 0.05 * r * h.at(id) * h.at(id) / 40.0);
  EXPECT_NEAR(fix->compute_vector(3), expected, 1e-12 * expected);
  // kappa 40 makes conduction the limiting criterion
  EXPECT_DOUBLE_EQ(lmp->update->dt, fix->compute_vector(3));
  EXPECT_LT(fix->compute_vector(3), fix->compute_vector(0));
}

// ---------------------------------------------------------------- artificial conductivity

// the pair's sum_j k_ij, k_ij = m_j alpha_u v_sig |dW/dr| / rho_ij, by atom ID (null: none)
static std::map<int, double> conductivity_rates(const std::unique_ptr<LAMMPS> &lmp)
{
  int ncol;
  const auto *rate = static_cast<double *>(lmp->force->pair->extract_peratom("condrate", ncol));
  std::map<int, double> out;
  if (rate)
    for (int i = 0; i < lmp->atom->nlocal; i++) out[lmp->atom->tag[i]] = rate[i];
  return out;
}

TEST(ArtificialConductivity, TimestepCriterion)
{
  // dt_a = C_a / max_i sum_j k_ij; with C_a = 0.01 it is the limiting criterion
  const std::string pair = "sph/astro eos ideal $(5.0/3.0) viscosity classic 1.0 2.0 conductivity ";
  std::map<int, double> rates[2];
  int k = 0;
  for (const std::string alpha_u : {"1.0", "2.0"}) {
    auto lmp = open_lammps();
    gas(lmp, "box", 3, pair + alpha_u, "sph/astro conductivity 0.01");
    commands(lmp, {"run 1"});
    rates[k] = conductivity_rates(lmp);
    ASSERT_FALSE(rates[k].empty());
    double largest = 0.0;
    for (const auto &[id, r] : rates[k]) {
      EXPECT_GE(r, 0.0) << "atom " << id;
      largest = std::max(largest, r);
    }
    auto *fix = lmp->modify->get_fix_by_id("gas");
    ASSERT_GT(largest, 0.0);
    EXPECT_NEAR(fix->compute_vector(3), 0.01 / largest, 1e-13 * 0.01 / largest);
    EXPECT_DOUBLE_EQ(lmp->update->dt, fix->compute_vector(3));
    EXPECT_LT(fix->compute_vector(3), fix->compute_vector(0));
    printf("alpha_u %s: largest sum_j k_ij %.4e, dt_a (C 0.01) %.4e, Courant dt %.4e\n",
           alpha_u.c_str(), largest, fix->compute_vector(3), fix->compute_vector(0));
    k++;
  }
  // the rate is linear in alpha_u (same state after the one step: the first step's dt
  // differs, so compare the setup's rates instead)
  for (const std::string alpha_u : {"1.0", "2.0"}) {
    auto lmp = open_lammps();
    gas(lmp, "box", 3, pair + alpha_u, "sph/astro dt fixed");
    commands(lmp, {"run 0"});
    rates[alpha_u == "1.0" ? 0 : 1] = conductivity_rates(lmp);
  }
  for (const auto &[id, r] : rates[0]) EXPECT_NEAR(rates[1].at(id), 2.0 * r, 1e-13 * r) << id;
}

TEST(ArtificialConductivity, NoPressureDifferenceNoRateNoCriterion)
{
  // uniform u on the perfect lattice: P_i = P_j up to round-off, v_sig = sqrt(|P_i - P_j| /
  // rho_ij) ~ 1e-8, so k_ij ~ 1e-8 (against ~1 with u varying by 20 %) and the criterion sets
  // no practical bound; without conductivity there is no rate at all
  auto lmp = open_lammps();
  gas(lmp, "box", 3, "sph/astro eos ideal $(5.0/3.0) viscosity classic 1.0 2.0 conductivity 1.0",
      "sph/astro", 1.0, 0.0);
  commands(lmp, {"set group all d_u 1.0", "velocity all set 0.0 0.0 0.0", "run 0"});
  for (const auto &[id, r] : conductivity_rates(lmp)) EXPECT_LT(r, 1e-6) << "atom " << id;
  auto *fix = lmp->modify->get_fix_by_id("gas");
  EXPECT_GT(fix->compute_vector(3), 1e4 * fix->compute_vector(0));
  commands(lmp, {"pair_style sph/astro eos ideal $(5.0/3.0)", "pair_coeff * *", "run 0"});
  EXPECT_TRUE(conductivity_rates(lmp).empty());
}

// ---------------------------------------------------------------- XSPH

TEST(XSPH, UniformMotionIsUnchanged)
{
  // perfect periodic lattice, uniform u, uniform velocity: the correction is exactly zero and
  // the positions follow those of a run without XSPH
  std::map<int, double> x_plain, x_xsph;
  for (const std::string eps : {"0.0", "0.5"}) {
    auto lmp = open_lammps();
    gas(lmp, "box", 3, "sph/astro eos ideal $(5.0/3.0) viscosity classic 1 2",
        "sph/astro xsph " + eps, 1.0, 0.0);
    commands(lmp, {"set group all d_u 1.0", "velocity all set 0.3 -0.2 0.1", "run 0"});
    if (eps == "0.5") {
      double **dv = fix_array(lmp, "gas");
      ASSERT_NE(dv, nullptr);
      for (int i = 0; i < lmp->atom->nlocal; i++)
        for (int d = 0; d < 3; d++) EXPECT_EQ(dv[i][d], 0.0);
    }
    commands(lmp, {"run 20"});
    (eps == "0.5" ? x_xsph : x_plain) = per_atom(lmp, "x");
  }
  double worst = 0.0;
  for (const auto &[id, value] : x_plain) worst = std::max(worst, std::fabs(x_xsph[id] - value));
  EXPECT_LT(worst, 1e-12);
}

TEST(XSPH, CorrectionCarriesNoMomentumAndSmoothsTheVelocity)
{
  auto lmp = open_lammps();
  gas(lmp, "box", 3, "sph/astro eos ideal $(5.0/3.0) viscosity classic 1 2", "sph/astro xsph 0.5");
  commands(lmp, {"velocity all create 1.0 4928459 dist gaussian", "run 0"});
  double **dv = fix_array(lmp, "gas");
  ASSERT_NE(dv, nullptr);
  double p[3] = {0, 0, 0}, pabs = 0.0, ekin = 0.0, ekin_smoothed = 0.0;
  double **v = lmp->atom->v;
  for (int i = 0; i < lmp->atom->nlocal; i++)
    for (int d = 0; d < 3; d++) {
      p[d] += 0.25 * dv[i][d];
      pabs += 0.25 * std::fabs(dv[i][d]);
      ekin += v[i][d] * v[i][d];
      ekin_smoothed += (v[i][d] + dv[i][d]) * (v[i][d] + dv[i][d]);
    }
  printf("XSPH: sum m dv = (%.2e %.2e %.2e) of sum m |dv| = %.3e; sum (v+dv)^2 / sum v^2 = %.4f\n",
         p[0], p[1], p[2], pabs, ekin_smoothed / ekin);
  ASSERT_GT(pabs, 0.0);
  for (double pd : p) EXPECT_LT(std::fabs(pd), 1e-13 * pabs);
  // random velocities: the smoothed drift velocity has less variance than v
  EXPECT_LT(ekin_smoothed, ekin);
}

// A gas box with random velocities (rms Mach ~ 1) and no dissipation, run to t = 0.2 with fixed
// dt. Returns the relative total energy error and the mean |A/A0 - 1| of the entropic function
// A = (gamma - 1) u / rho^(gamma - 1), which the equations keep constant without viscosity.
static std::pair<double, double> xsph_run(double dt, const std::string &xsph)
{
  auto lmp = open_lammps();
  gas(lmp, "box", 4, "sph/astro kernel m4 eos ideal $(5.0/3.0) viscosity none",
      "sph/astro dt fixed xsph " + xsph);
  const int nsteps = static_cast<int>(std::lround(0.2 / dt));
  commands(lmp, {"velocity all create 0.1 4928459 dist gaussian", "run 0"});
  auto entropy = [&]() {
    std::map<int, double> A;
    const auto u = per_atom(lmp, "u"), rho = per_atom(lmp, "rho");
    for (const auto &[id, ui] : u) A[id] = (2.0 / 3.0) * ui / std::pow(rho.at(id), 2.0 / 3.0);
    return A;
  };
  const auto A0 = entropy();
  commands(
      lmp,
      {"timestep " + num(dt), "thermo " + std::to_string(nsteps), "run " + std::to_string(nsteps)});
  const auto A1 = entropy();
  double drift = 0.0;
  for (const auto &[id, a] : A0) drift += std::fabs(A1.at(id) / a - 1.0);
  return {std::fabs(global_vector(lmp, "sum", 12)[DEREL]), drift / A0.size()};
}

TEST(XSPH, EnergyIsKeptButTheFlowIsNoLongerAdiabatic)
{
  // v and u follow the unmodified equations, whose force work and P dV term cancel pair by
  // pair whatever x does: the total energy error still falls as dt^2. x however moves with
  // v + dv while du/dt assumes it moves with v, so u no longer follows the density: without
  // dissipation the entropy A drifts by an eps-dependent amount that does not vanish with dt
  const auto [e1, a1] = xsph_run(0.01, "0.0");
  const auto [e2, a2] = xsph_run(0.005, "0.0");
  const auto [x1, xa1] = xsph_run(0.01, "0.5");
  const auto [x2, xa2] = xsph_run(0.005, "0.5");
  printf("random-velocity box, t = 0.2, dt 0.01 / 0.005: |dE/E| plain %.3e / %.3e, xsph 0.5 "
         "%.3e / %.3e; mean |dA/A| plain %.3e / %.3e, xsph 0.5 %.3e / %.3e\n",
         e1, e2, x1, x2, a1, a2, xa1, xa2);
  EXPECT_NEAR(e1 / e2, 4.0, 1.0);
  EXPECT_NEAR(x1 / x2, 4.0, 1.0);
  EXPECT_GT(xa2, 10.0 * a2);    // entropy drift far above the plain run's
  EXPECT_GT(xa2, 0.5 * xa1);    // and not falling with dt
}

// ---------------------------------------------------------------- bad input

class BadPhysicsInput : public BadInputTest {};

TEST_F(BadPhysicsInput, KeywordValues)
{
  expect_error("pair_style sph/astro conduction -1",
               "pair_style sph/astro: conduction kappa = -1 must be finite and >= 0");
  expect_error("pair_style sph/astro conduction hot", "Expected floating point");
  expect_error("pair_style sph/astro conduction", "Illegal pair_style sph/astro conduction");
  expect_error("pair_style sph/astro kernel gauss",
               "unknown kernel 'gauss'; allowed: m4 (cubic), m6 (quintic), wendland/c2, "
               "wendland/c4, gaussian");
  expect_error("fix gas all sph/astro conduction 0",
               "fix sph/astro: conduction = 0 must be in (0, 1]");
  expect_error("fix gas all sph/astro conduction 1.5", "conduction = 1.5 must be in (0, 1]");
  expect_error("fix gas all sph/astro conductivity 0",
               "fix sph/astro: conductivity = 0 must be in (0, 1] (C in dt = C / the artificial "
               "conductivity's diffusion rate; 1 is the stability limit)");
  expect_error("fix gas all sph/astro conductivity 2", "conductivity = 2 must be in (0, 1]");
  expect_error("fix gas all sph/astro xsph -0.5",
               "fix sph/astro: xsph = -0.5 must be in [0, 1] (0: off; 0.5 is usual)");
  expect_error("fix gas all sph/astro xsph 2", "xsph = 2 must be in [0, 1]");
  expect_error("fix gas all sph/astro xsph", "Illegal fix sph/astro xsph");
}

TEST_F(BadPhysicsInput, ConductionNeedsTheIdealGas)
{
  commands(lmp,
           {"pair_style sph/astro eos isothermal 1.0 conduction 1.0", "pair_coeff * *",
            "fix gas all sph/astro", "set group all d_h 0.75"});
  expect_error("run 0",
               "pair_style sph/astro: conduction 1 needs eos ideal (the energy equation); eos "
               "isothermal does not evolve u");
}
