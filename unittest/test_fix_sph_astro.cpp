/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// LAMMPS-driven tests of fix sph/astro and fix sph/astro/switch: time-integration order,
// entropy, timestep criteria, tend, restart, data files and the errors for bad input.

#include "styles_fixture.h"

#include "compute.h"
#include "fix.h"
#include "force.h"
#include "pair.h"

#include <cmath>
#include <cstdio>

using namespace sph_astro_test;
using LAMMPS_NS::LAMMPS;

TEST(FixSPHAstro, EnergyErrorIsSecondOrderInTimestep)
{
  const double e1 = energy_error(0.02), e2 = energy_error(0.01), e3 = energy_error(0.005);
  ASSERT_GT(e3, 0.0);
  EXPECT_LT(e1, 1e-2);
  EXPECT_NEAR(e1 / e2, 4.0, 1.0) << e1 << " " << e2 << " " << e3;
  EXPECT_NEAR(e2 / e3, 4.0, 1.0) << e1 << " " << e2 << " " << e3;
}

TEST(FixSPHAstroSwitch, AlphaDecaysInGasAtRest)
{
  auto lmp = open_lammps();
  gas(lmp, "box", 3, PAIR, "sph/astro dt fixed", 1.0, 0.0);
  commands(lmp,
           {"velocity all set 0 0 0", "set group all d_u 1.5",
            "fix av all sph/astro/switch morris-monaghan 0.1 1.0 0.2", "timestep 0.01",
            "compute sph all sph/astro/atom alpha cs h", "thermo 50", "run 50"});
  // alpha = 0.1 + 0.9 exp(-t l c / h) with c and h fixed in the uniform gas at
  // rest
  const double c = std::sqrt(5.0 / 3.0 * 2.0 / 3.0 * 1.5), h = 1.2 * std::cbrt(0.25);
  const double expected = 0.1 + 0.9 * std::exp(-0.5 * 0.2 * c / h);
  auto *array = static_cast<double **>(
      lammps_extract_compute(lmp.get(), "sph", LMP_STYLE_ATOM, LMP_TYPE_ARRAY));
  ASSERT_NE(array, nullptr);
  for (int i = 0; i < lmp->atom->nlocal; i++) EXPECT_NEAR(array[i][0], expected, 1e-9);
  auto *fix = lmp->modify->get_fix_by_id("av");
  EXPECT_NEAR(fix->compute_vector(0), expected, 1e-9);
}

TEST(FixSPHAstroSwitch, AlphaRisesUnderCompressionAndConservesMomentum)
{
  auto lmp = open_lammps();
  gas(lmp, "ball", 6, PAIR, "sph/astro courant 0.3", 0.05, 0.0);
  commands(lmp,
           {"fix av all sph/astro/switch morris-monaghan 0.1 1.5 0.2", "set group all d_alpha 0.1",
            "variable vx atom -0.5*x", "variable vy atom -0.5*y", "variable vz atom -0.5*z",
            "velocity all set v_vx v_vy v_vz", "compute sph all sph/astro/atom alpha", "run 40"});
  auto *fix = lmp->modify->get_fix_by_id("av");
  // converging flow: div v = -1.5, the source drives alpha towards alpha_max
  EXPECT_GT(fix->compute_vector(0), 0.8);
  EXPECT_LE(fix->compute_vector(1), 1.5);
  const auto end = global_vector(lmp, "sum", 12);
  for (int k : {PX, PY, PZ}) EXPECT_LT(std::fabs(end[k]), 1e-12) << k;
  EXPECT_LT(std::fabs(end[DEREL]), 1e-2);
}

TEST(FixSPHAstroSwitch, AlphaComesBackFromARestart)
{
  const std::string restart = "test_switch.restart";
  std::map<int, double> alpha_ref;
  {
    auto lmp = open_lammps();
    gas(lmp, "box", 3, PAIR, "sph/astro courant 0.3");
    commands(lmp,
             {"fix av all sph/astro/switch morris-monaghan 0.1 1.5 0.2", "run 10",
              "write_restart " + restart});
    alpha_ref = per_atom(lmp, "alpha");
  }
  auto lmp = open_lammps();
  commands(lmp,
           {"read_restart " + restart, "fix gas all sph/astro courant 0.3",
            "fix av all sph/astro/switch morris-monaghan 0.1 1.5 0.2"});
  auto alpha = per_atom(lmp, "alpha");
  ASSERT_EQ(alpha.size(), alpha_ref.size());
  for (const auto &[id, a] : alpha_ref) {
    EXPECT_LT(a, 1.5);    // it has decayed from alpha_max
    EXPECT_EQ(alpha[id], a) << "atom " << id;
  }
  std::remove(restart.c_str());
}

TEST(FixSPHAstroSwitch, CullenDehnenRisesWhenCompressionGrowsAndIgnoresRotation)
{
  // converging flow v = -0.5 r: the compression of the cold ball steepens (d(div v)/dt < 0),
  // alpha jumps up; a rigidly rotating ball (div v ~ 0, curl v = 2) decays to alpha_min
  for (bool rotate : {false, true}) {
    auto lmp = open_lammps();
    gas(lmp, "ball", 6, PAIR, "sph/astro courant 0.3", 0.05, 0.0);
    commands(
        lmp,
        {"fix av all sph/astro/switch cullen-dehnen 0.05 1.5 0.2", "set group all d_alpha 0.05"});
    if (rotate)
      commands(lmp, {"variable vx atom -y", "variable vy atom x", "variable vz atom 0.0"});
    else
      commands(lmp,
               {"variable vx atom -0.5*x", "variable vy atom -0.5*y", "variable vz atom -0.5*z"});
    commands(lmp, {"velocity all set v_vx v_vy v_vz", "run 40"});
    auto *fix = lmp->modify->get_fix_by_id("av");
    // mean over the inner particles (the surface of the ball is neither)
    auto alpha = per_atom(lmp, "alpha");
    auto x = per_atom(lmp, "xwrapped", 0), y = per_atom(lmp, "xwrapped", 1),
         z = per_atom(lmp, "xwrapped", 2);
    double sum = 0.0;
    int n = 0;
    for (const auto &[id, a] : alpha)
      if (x[id] * x[id] + y[id] * y[id] + z[id] * z[id] < 1.0) {
        sum += a;
        n++;
      }
    ASSERT_GT(n, 0);
    if (rotate)
      EXPECT_LT(sum / n, 0.1) << "rotation";
    else
      EXPECT_GT(sum / n, 0.5) << "compression";
    EXPECT_LE(fix->compute_vector(1), 1.5);
    EXPECT_GE(sum / n, 0.05);
    const auto end = global_vector(lmp, "sum", 12);
    for (int k : {PX, PY, PZ}) EXPECT_LT(std::fabs(end[k]), 1e-12) << k;
  }
}

// mean of a per-atom value of pair sph/astro (extract_peratom NAME) over the central
// particles, with the Balsara limiter on (so curl v is computed)

TEST(FixSPHAstro, EntropyIsConstantWithoutDissipation)
{
  auto lmp = open_lammps();
  gas(lmp, "ball", 6, "sph/astro eos ideal $(5.0/3.0) viscosity none",
      "sph/astro thermal entropy courant 0.3");
  commands(lmp, {"fix hvar all sph/astro/h iterate", "run 0"});
  auto A0 = per_atom(lmp, "entropy");
  auto u0 = per_atom(lmp, "u");
  auto rho0 = per_atom(lmp, "rho");
  // A = (gamma - 1) u / rho^(gamma-1) at the start
  for (const auto &[id, a] : A0)
    EXPECT_NEAR(a, (2.0 / 3.0) * u0[id] * std::pow(rho0[id], -2.0 / 3.0), 1e-12 * a);
  commands(lmp, {"run 100"});
  auto A = per_atom(lmp, "entropy");
  auto u = per_atom(lmp, "u");
  auto rho = per_atom(lmp, "rho");
  for (const auto &[id, a] : A0) {
    EXPECT_EQ(A[id], a) << "atom " << id;    // adiabatic: dA/dt = 0 exactly
    EXPECT_NEAR(u[id], 1.5 * a * std::pow(rho[id], 2.0 / 3.0), 1e-12 * u[id]);
  }
  const auto end = global_vector(lmp, "sum", 12);
  EXPECT_LT(std::fabs(end[DEREL]),
            1e-3);    // energy: conserved to integration error
}

TEST(FixSPHAstro, EntropyRisesInShocksAndRestartsBitForBit)
{
  const std::string restart = "test_entropy.restart";
  std::map<int, double> A_ref;
  double mean_rise = 0.0;
  {
    auto lmp = open_lammps();
    gas(lmp, "ball", 6, PAIR, "sph/astro thermal entropy courant 0.3", 0.05);
    commands(lmp,
             {"variable vx atom -x", "variable vy atom -y", "variable vz atom -z",
              "velocity all set v_vx v_vy v_vz", "run 0"});
    auto A0 = per_atom(lmp, "entropy");
    commands(lmp, {"run 10", "write_restart " + restart, "run 10"});
    A_ref = per_atom(lmp, "entropy");
    for (const auto &[id, a] : A_ref) {
      EXPECT_GE(a, A0[id] * (1.0 - 1e-12));    // viscous heating only raises A
      mean_rise += a / A0[id] / A_ref.size();
    }
  }
  EXPECT_GT(mean_rise, 1.1);    // the cold converging flow is shock-heated
  auto lmp = open_lammps();
  commands(lmp,
           {"read_restart " + restart, "fix gas all sph/astro thermal entropy courant 0.3",
            "neighbor " + num(0.3 * 1.2 * std::cbrt(0.25)) + " bin",
            "neigh_modify every 1 delay 0 check yes", "run 10"});
  auto A = per_atom(lmp, "entropy");
  for (const auto &[id, a] : A_ref) EXPECT_EQ(A[id], a) << "atom " << id;
  std::remove(restart.c_str());
}

TEST(FixSPHAstro, AdaptiveTimestepFollowsCourantCriterion)
{
  auto lmp = open_lammps();
  gas(lmp, "box", 3, PAIR, "sph/astro courant 0.2 force 0.3");
  commands(lmp, {"velocity all set 0 0 0", "set group all d_u 1.0", "run 0"});
  // uniform gas at rest: dt = C h / (c (1 + 1.2 alpha)), c^2 = gamma (gamma-1)
  // u
  const double h = 1.2 * std::cbrt(0.25);
  const double c = std::sqrt(5.0 / 3.0 * 2.0 / 3.0);
  const double expected = 0.2 * h / (c * (1.0 + 1.2 * 1.0));
  // div v and the force of a slightly disordered lattice lower it a little
  EXPECT_LE(lmp->update->dt, expected * 1.0000001);
  EXPECT_GT(lmp->update->dt, 0.8 * expected);
}

TEST(FixSPHAstro, SignalViscosityTimestepUsesTheLargestSignalVelocity)
{
  auto lmp = open_lammps();
  gas(lmp, "box", 3, "sph/astro kernel m4 eos ideal $(5.0/3.0) viscosity signal 1.0",
      "sph/astro courant 0.2 force 0.3");
  commands(lmp, {"velocity all set 0 0 0", "set group all d_u 1.0", "run 0"});
  // gas at rest: max_j v_sig,ij = c_i + c_j = 2 c (Monaghan 1997), dt = C h / (2 c)
  const double h = 1.2 * std::cbrt(0.25);
  const double c = std::sqrt(5.0 / 3.0 * 2.0 / 3.0);
  const double expected = 0.2 * h / (2.0 * c);
  EXPECT_LE(lmp->update->dt, expected * 1.0000001);
  EXPECT_GT(lmp->update->dt, 0.8 * expected);
}

// vsig pairs with classic viscosity: dt_i = C h / max_j (c_i + c_j - 3 min(0, v_ij . r_ij / r))
// over the pairs inside the kernel support (Springel 2005, eqs. 13 and 16), against the pairs
// summed here by brute force; the default (the classic viscosity's own estimate) differs
TEST(FixSPHAstro, PairwiseSignalSpeedSetsTheCourantStep)
{
  const double C = 0.2, h = 1.2 * std::cbrt(0.25), L = 4.0;
  double courant[2];
  for (int pairs = 0; pairs < 2; pairs++) {
    auto lmp = open_lammps();
    gas(lmp, "box", 4, PAIR,
        std::string("sph/astro courant 0.2 force 1.0 vsig ") + (pairs ? "pairs" : "viscosity"));
    // fast random motion: the approaching pairs' -3 w_ij dominates the sound speeds
    commands(lmp, {"velocity all create 2.0 4321 dist gaussian", "run 0"});
    auto *fix = lmp->modify->get_fix_by_id("gas");
    courant[pairs] = fix->compute_vector(0);
    if (!pairs) continue;
    int ncol = 0;
    const auto *c = static_cast<double *>(lmp->force->pair->extract_peratom("soundspeed", ncol));
    ASSERT_NE(c, nullptr);
    const int n = lmp->atom->nlocal;
    double **x = lmp->atom->x, **v = lmp->atom->v;
    double expected = INFINITY;
    for (int i = 0; i < n; i++) {
      double vmax = 2.0 * c[i];
      for (int j = 0; j < n; j++) {
        if (j == i) continue;
        double d[3], r2 = 0.0, vdotr = 0.0;
        for (int k = 0; k < 3; k++) {
          d[k] = x[i][k] - x[j][k];
          d[k] -= L * std::round(d[k] / L);    // nearest image (support 2h < L/2)
          r2 += d[k] * d[k];
          vdotr += (v[i][k] - v[j][k]) * d[k];
        }
        if (r2 >= 4.0 * h * h) continue;
        const double w = vdotr / std::sqrt(r2);
        vmax = std::max(vmax, c[i] + c[j] - 3.0 * std::min(w, 0.0));
      }
      expected = std::min(expected, C * h / vmax);
    }
    EXPECT_NEAR(courant[pairs], expected, 1e-12 * expected);
  }
  EXPECT_GT(std::fabs(courant[0] / courant[1] - 1.0), 0.05) << courant[0] << " " << courant[1];
}

TEST(FixSPHAstro, TimestepIsTheSmallestOfItsThreeCriteria)
{
  // an expanding hot ball: its outer particles cool (du/dt < 0), so dt_u is
  // finite
  auto lmp = open_lammps();
  gas(lmp, "ball", 6, PAIR, "sph/astro courant 0.3 force 0.25 energy 0.2");
  commands(lmp, {"fix hvar all sph/astro/h iterate margin 2.0", "run 30"});
  auto *fix = lmp->modify->get_fix_by_id("gas");
  const double dtcv = fix->compute_vector(0), dtf = fix->compute_vector(1),
               dtu = fix->compute_vector(2);
  ASSERT_TRUE(std::isfinite(dtcv) && std::isfinite(dtf) && std::isfinite(dtu));
  EXPECT_DOUBLE_EQ(lmp->update->dt, std::min(dtcv, std::min(dtf, dtu)));
  EXPECT_DOUBLE_EQ(fix->compute_scalar(), lmp->update->dt);
  // the global compute reports the h range and the iteration statistics
  const auto g = global_vector(lmp, "sum", 18);
  ASSERT_EQ(g.size(), 18u);
  EXPECT_GT(g[12], 0.0);
  EXPECT_GT(g[13], g[12]);    // the rarefied surface has the largest h
  EXPECT_GE(g[14], 1.0);      // mean Newton iterations
  EXPECT_EQ(g[16], 0.0);      // no failures
}

// compute sph/astro/atom dt: each particle's own step; the global step is their smallest, and
// the particles of the dense centre need shorter steps than those of the rarefied surface
TEST(FixSPHAstro, EachParticlesOwnStepIsGivenAndTheGlobalStepIsTheSmallest)
{
  auto lmp = open_lammps();
  gas(lmp, "ball", 6, PAIR, "sph/astro courant 0.3 force 0.25 energy 0.2");
  commands(lmp,
           {"fix hvar all sph/astro/h iterate margin 2.0", "compute own all sph/astro/atom dt",
            "compute ownmin all reduce min c_own", "compute ownmax all reduce max c_own",
            "thermo_style custom step dt c_ownmin c_ownmax", "run 30"});
  const double lo = lmp->modify->get_compute_by_id("ownmin")->compute_scalar();
  const double hi = lmp->modify->get_compute_by_id("ownmax")->compute_scalar();
  EXPECT_DOUBLE_EQ(lo, lmp->update->dt);
  EXPECT_GT(hi, 1.2 * lo);
  // with dtmax no particle's own step is longer
  commands(
      lmp,
      {"fix gas all sph/astro courant 0.3 force 0.25 energy 0.2 dtmax " + num(1.2 * lo), "run 1"});
  EXPECT_LE(lmp->modify->get_compute_by_id("ownmax")->compute_scalar(), 1.2 * lo);
}

TEST(FixSPHAstro, StopsAtTend)
{
  auto lmp = open_lammps();
  gas(lmp, "box", 3, PAIR, "sph/astro tend 0.0375");
  commands(lmp, {"run 100000"});
  EXPECT_NEAR(lmp->update->atime +
                  (lmp->update->ntimestep - lmp->update->atimestep) * lmp->update->dt,
              0.0375, 1e-12);
  EXPECT_LT(lmp->update->ntimestep, 1000);
}

TEST(FixSPHAstro, ChangesBetweenRunsReachTheFirstForceEvaluation)
{
  // `set d_u` between two runs must be seen by the next run's first pressure,
  // although the predictions of the previous run are kept when nothing changed
  auto lmp = open_lammps();
  gas(lmp, "box", 3, PAIR, "sph/astro", 1.0, 0.0);
  commands(lmp,
           {"velocity all set 0 0 0", "set group all d_u 1.0",
            "compute sph all sph/astro/atom pressure rho", "run 3", "set group all d_u 2.0",
            "run 0"});
  auto *array = static_cast<double **>(
      lammps_extract_compute(lmp.get(), "sph", LMP_STYLE_ATOM, LMP_TYPE_ARRAY));
  ASSERT_NE(array, nullptr);
  for (int i = 0; i < lmp->atom->nlocal; i++)
    EXPECT_NEAR(array[i][0], (2.0 / 3.0) * array[i][1] * 2.0, 1e-12);
}

TEST(FixSPHAstro, ThermoReportsTheStepThatReachesTend)
{
  // also with a dump every step, whose output resets the computes' invoked flags
  for (bool dump : {false, true}) {
    auto lmp = open_lammps();
    gas(lmp, "box", 3, PAIR, "sph/astro tend 0.3");
    if (dump) commands(lmp, {"dump every all custom 1 test_every.dump id x"});
    commands(lmp, {"thermo 1000", "run 100000"});
    EXPECT_GT(lmp->update->ntimestep, 2);
    // the compute was evaluated by thermo on the final step, with the energy
    // tallied
    const auto end = global_vector(lmp, "sum", 12);
    ASSERT_EQ(end.size(), 12u);
    auto *compute = lmp->modify->get_compute_by_id("sum");
    ASSERT_NE(compute, nullptr);
    EXPECT_EQ(compute->invoked_vector, lmp->update->ntimestep);
  }
  std::remove("test_every.dump");
}

TEST(FixSPHAstro, ThermoReportsTheStepThatReachesTendWithAFixEvaluatedEveryStep)
{
  // fix vector clears the computes' invoked flags every step (Modify::clearstep_compute):
  // the final thermo's compute must still have its energy tallied (was: "energy was not
  // tallied on step N", examples/noh/in.noh)
  auto lmp = open_lammps();
  gas(lmp, "box", 3, PAIR, "sph/astro tend 0.3");
  commands(lmp,
           {"variable one equal 1", "fix every all vector 1 v_one", "thermo 1000", "run 100000"});
  EXPECT_GT(lmp->update->ntimestep, 2);
  auto *compute = lmp->modify->get_compute_by_id("sum");
  ASSERT_NE(compute, nullptr);
  EXPECT_EQ(compute->invoked_vector, lmp->update->ntimestep);
}

TEST(FixSPHAstro, ThermoReportsTheStepThatReachesTendAfterAThermoStep)
{
  // fixed dt 0.002, tend 0.011: step 5 (a thermo step) shortens the next step, which reaches
  // tend; thermo's own schedule after step 5 (step 10) must not hide step 6
  auto lmp = open_lammps();
  gas(lmp, "box", 3, PAIR, "sph/astro dt fixed tend 0.011");
  commands(lmp, {"thermo 5", "run 100000"});
  EXPECT_EQ(lmp->update->ntimestep, 6);
  auto *compute = lmp->modify->get_compute_by_id("sum");
  ASSERT_NE(compute, nullptr);
  EXPECT_EQ(compute->invoked_vector, 6);
  EXPECT_EQ(global_vector(lmp, "sum", 12).size(), 12u);
}

TEST(FixSPHAstro, OnlyOneInstance)
{
  auto lmp = open_lammps();
  gas(lmp, "box", 2, PAIR, "sph/astro");
  commands(lmp, {"fix gas2 all sph/astro"});
  EXPECT_NE(error_of(lmp, "run 0").find("only one instance"), std::string::npos);
}

class Restart : public ::testing::TestWithParam<std::string> {};

TEST_P(Restart, ContinuesBitForBit)
{
  // GetParam(): extra command (variable smoothing length) or ""
  const std::string extra = GetParam();
  const std::string restart = "test_restart_sph_astro.restart";
  std::map<int, double> x_ref, v_ref, u_ref, h_ref;
  {
    auto lmp = open_lammps();
    gas(lmp, "box", 3, PAIR, "sph/astro courant 0.3");
    if (!extra.empty()) commands(lmp, {extra});
    commands(lmp, {"run 20", "write_restart " + restart, "run 20"});
    x_ref = per_atom(lmp, "x", 0);
    v_ref = per_atom(lmp, "v", 1);
    u_ref = per_atom(lmp, "u");
    h_ref = per_atom(lmp, "h");
  }
  auto lmp = open_lammps();
  commands(lmp,
           {"read_restart " + restart, "fix gas all sph/astro courant 0.3",
            "neighbor " + num(0.3 * 1.2 * std::cbrt(0.25)) + " bin",
            "neigh_modify every 1 delay 0 check yes"});
  if (!extra.empty()) commands(lmp, {extra});
  commands(lmp, {"run 20"});
  auto x = per_atom(lmp, "x", 0);
  auto v = per_atom(lmp, "v", 1);
  auto u = per_atom(lmp, "u");
  auto h = per_atom(lmp, "h");
  ASSERT_EQ(x.size(), x_ref.size());
  for (const auto &[id, value] : x_ref) {
    EXPECT_EQ(x[id], value) << "atom " << id;
    EXPECT_EQ(v[id], v_ref[id]) << "atom " << id;
    EXPECT_EQ(u[id], u_ref[id]) << "atom " << id;
    EXPECT_EQ(h[id], h_ref[id]) << "atom " << id;
  }
  std::remove(restart.c_str());
}

INSTANTIATE_TEST_SUITE_P(
    FixSPHAstro, Restart,
    ::testing::Values("", "fix hvar all sph/astro/h iterate hfact 1.2",
                      "fix hvar all sph/astro/h dhdt",
                      "fix av all sph/astro/switch cullen-dehnen 0.1 1.5 0.2"));

TEST(FixSPHAstro, RestartWrittenDuringARunContinuesBitForBit)
{
  std::map<int, double> x_ref, u_ref;
  {
    auto lmp = open_lammps();
    gas(lmp, "box", 3, PAIR, "sph/astro courant 0.3");
    commands(lmp, {"fix hvar all sph/astro/h iterate", "restart 20 test_mid.*.restart", "run 40"});
    x_ref = per_atom(lmp, "x", 0);
    u_ref = per_atom(lmp, "u");
  }
  auto lmp = open_lammps();
  commands(lmp,
           {"read_restart test_mid.20.restart", "fix gas all sph/astro courant 0.3",
            "fix hvar all sph/astro/h iterate",
            "neighbor " + num(0.3 * 1.2 * std::cbrt(0.25)) + " bin",
            "neigh_modify every 1 delay 0 check yes", "run 20"});
  auto x = per_atom(lmp, "x", 0);
  auto u = per_atom(lmp, "u");
  ASSERT_EQ(x.size(), x_ref.size());
  // u is bit for bit; x up to the round-off of wrapping into the periodic box,
  // which the continued run does at other re-neighbouring steps
  for (const auto &[id, value] : x_ref) {
    EXPECT_NEAR(x[id], value, 1e-14) << "atom " << id;
    EXPECT_EQ(u[id], u_ref[id]) << "atom " << id;
  }
  std::remove("test_mid.20.restart");
  std::remove("test_mid.40.restart");
}

TEST(SPHAstroState, DataFileRoundTrip)
{
  const std::string data = "test_state_sph_astro.data";
  std::map<int, double> h_ref, u_ref, v_ref;
  {
    auto lmp = open_lammps();
    gas(lmp, "box", 2, PAIR, "sph/astro");
    commands(lmp, {"run 5", "write_data " + data});
    h_ref = per_atom(lmp, "h");
    u_ref = per_atom(lmp, "u");
    v_ref = per_atom(lmp, "vest", 0);
  }
  auto lmp = open_lammps();
  commands(lmp,
           {"units lj", "atom_style atomic", "atom_modify map array", "sph/astro/state",
            "read_data " + data + " fix SPH_ASTRO_STATE NULL SPH_ASTRO_STATE",
            "pair_style " + std::string(PAIR), "pair_coeff * *", "fix gas all sph/astro", "run 0"});
  auto h = per_atom(lmp, "h");
  auto u = per_atom(lmp, "u");
  ASSERT_EQ(h.size(), h_ref.size());
  for (const auto &[id, value] : h_ref) {
    EXPECT_DOUBLE_EQ(h[id], value);
    EXPECT_DOUBLE_EQ(u[id], u_ref[id]);
  }
  std::remove(data.c_str());
}

// ---------------------------------------------------------------- bad input

class BadInput : public BadInputTest {
 protected:
  void valid_setup()
  {
    commands(lmp,
             {std::string("pair_style ") + PAIR, "pair_coeff * *", "fix gas all sph/astro",
              "set group all d_h 0.75", "set group all d_u 1.0"});
  }
};

TEST_F(BadInput, PairStyleArguments)
{
  expect_error("pair_style sph/astro kernel lucy", "unknown kernel 'lucy'");
  expect_error("pair_style sph/astro eos ideal 0.9", "gamma = 0.9 must be > 1");
  expect_error("pair_style sph/astro eos ideal abc", "Expected floating point");
  expect_error("pair_style sph/astro eos vdw 1", "unknown eos 'vdw'");
  expect_error("pair_style sph/astro eos isothermal -1", "sound speed -1 must be > 0");
  expect_error("pair_style sph/astro eos polytropic 1.0",
               "Illegal pair_style sph/astro eos polytropic");
  expect_error("pair_style sph/astro eos barotropic 0.2 1e-3",
               "Illegal pair_style sph/astro eos barotropic");
  expect_error("pair_style sph/astro eos barotropic 0 1e-3 1.4",
               "eos barotropic: sound speed 0 must be finite and > 0");
  expect_error("pair_style sph/astro eos barotropic 0.2 -1 1.4",
               "eos barotropic: critical density -1 must be finite and > 0");
  expect_error("pair_style sph/astro eos barotropic 0.2 1e-3 1.0",
               "eos barotropic: gamma = 1.0 must be finite and > 1");
  expect_error("pair_style sph/astro viscosity classic -1 2", "must be >= 0");
  expect_error("pair_style sph/astro viscosity monaghan", "unknown viscosity 'monaghan'");
  expect_error("pair_style sph/astro viscosity signal 0", "alpha = 0 must be > 0");
  expect_error("pair_style sph/astro viscosity signal",
               "Illegal pair_style sph/astro viscosity signal");
  expect_error("pair_style sph/astro colour blue", "unknown keyword 'colour'");
  expect_error("pair_style sph/astro reconstruct maybe", "Expected boolean parameter");
  expect_error("pair_style sph/astro viscosity none reconstruct yes",
               "reconstruct yes needs viscosity classic or signal");
  expect_error("pair_style sph/astro balsara yes reconstruct yes",
               "reconstruct yes and balsara yes cannot be combined");
  commands(lmp, {"pair_style sph/astro"});
  expect_error("pair_coeff * * 1.0", "takes only two type ranges");
}

TEST_F(BadInput, FixArguments)
{
  expect_error("fix gas all sph/astro courant 2", "courant = 2 must be in (0, 1]");
  expect_error("fix gas all sph/astro force 0", "force = 0 must be in (0, 1]");
  expect_error("fix gas all sph/astro dt sometimes", "dt 'sometimes' is not one of");
  expect_error("fix gas all sph/astro tend -1", "tend = -1 must be > 0");
  expect_error("fix gas all sph/astro dtmin 1 dtmax 0.1", "dtmin 1 is larger than dtmax 0.1");
  expect_error("fix gas all sph/astro speed 1", "unknown keyword 'speed'");
  expect_error("fix gas all sph/astro thermal heat", "thermal 'heat' is not one of");
  expect_error("fix gas all sph/astro vsig max", "vsig 'max' is not one of: viscosity, pairs");
  expect_error("fix gas all sph/astro courant", "Illegal fix sph/astro courant");
}

TEST_F(BadInput, RunStyleRespaIsRefused)
{
  valid_setup();
  commands(lmp, {"run_style respa 2 2"});
  expect_error("run 1", "fix sph/astro: run_style respa is not supported; use run_style verlet");
}

TEST_F(BadInput, SmoothingLengthFixArguments)
{
  expect_error("fix hvar all sph/astro/h iterate margin 0.9", "margin = 0.9 must be >= 1");
  expect_error("fix hvar all sph/astro/h iterate rebuild 0.9",
               "unknown keyword 'rebuild'; allowed: hfact, tol, maxiter, margin, hmax, ghosts (the "
               "package's neighbour search follows h within a run");
  expect_error("fix hvar all sph/astro/h dhdt collections auto",
               "unknown keyword 'collections'; allowed: margin, hmax, ghosts (the package's "
               "neighbour");
  expect_error("fix hvar all sph/astro/h dhdt hfact 1.2",
               "unknown keyword 'hfact'; allowed: margin, hmax, ghosts");
  expect_error("fix hvar all sph/astro/h iterate ghosts thin",
               "ghosts = thin is not one of: narrow, full");
  expect_error("fix hvar all sph/astro/h iterate hmax 0", "hmax = 0 must be > 0");
}

TEST_F(BadInput, SwitchArguments)
{
  expect_error("fix av all sph/astro/switch balsara 0.1 1 0.1",
               "switch 'balsara' is not one of: morris-monaghan, cullen-dehnen");
  expect_error("fix av all sph/astro/switch cullen-dehnen 0.1 1",
               "cullen-dehnen takes ALPHA_MIN ALPHA_MAX L (got 2 values)");
  expect_error("fix av all sph/astro/switch cullen-dehnen 1.0 0.5 0.1",
               "need 0 <= alpha_min < alpha_max (got alpha_min = 1.0, alpha_max = 0.5)");
  expect_error("fix av all sph/astro/switch morris-monaghan 0.1 1.0 0", "L = 0 must be > 0");
  commands(lmp,
           {"pair_style sph/astro viscosity none", "pair_coeff * *", "fix gas all sph/astro",
            "set group all d_h 0.75", "set group all d_u 1.0",
            "fix av all sph/astro/switch cullen-dehnen 0.1 1.0 0.1"});
  expect_error("run 0", "needs pair_style sph/astro viscosity classic or signal");
}

TEST_F(BadInput, MissingPartners)
{
  commands(lmp, {"pair_style lj/cut 1.0", "pair_coeff * * 1 1", "fix gas all sph/astro"});
  expect_error("run 0", "fix sph/astro requires pair_style sph/astro");
}

TEST_F(BadInput, PairWithoutFix)
{
  commands(
      lmp,
      {std::string("pair_style ") + PAIR, "pair_coeff * *", "sph/astro/state", "fix nve all nve"});
  expect_error("run 0", "pair_style sph/astro requires fix sph/astro");
}

TEST_F(BadInput, SmoothingLengthMustBePositive)
{
  valid_setup();
  commands(lmp, {"set atom 5 d_h 0.0"});
  expect_error("run 0", "atom 5 has smoothing length h = 0");
}

TEST_F(BadInput, NegativeEnergyIsReportedWithAtomID)
{
  valid_setup();
  commands(lmp, {"set atom 7 d_u -0.5"});
  expect_error("run 0", "atom 7 has specific internal energy u = -0.5");
}

TEST_F(BadInput, RejectsAtomStyleSPH)
{
  lmp.reset();    // one LAMMPS instance at a time: deleting one unloads all
                  // plugins
  lmp = open_lammps();
  commands(lmp, {"units lj", "atom_style sph", "region box block 0 2 0 2 0 2", "create_box 1 box"});
  expect_error("fix gas all sph/astro", "atom_style sph");
}

TEST_F(BadInput, RejectsUnitsWithConversionFactors)
{
  lmp.reset();
  lmp = open_lammps();
  commands(lmp,
           {"units metal", "atom_style atomic", "lattice fcc 4.0", "region box block 0 2 0 2 0 2",
            "create_box 1 box", "create_atoms 1 box", "mass 1 1.0"});
  valid_setup();
  expect_error("run 0", "units metal");
}

TEST_F(BadInput, TimestepCollapseStopsTheRun)
{
  valid_setup();
  commands(lmp, {"unfix gas", "fix gas all sph/astro dtmin 1.0"});
  expect_error("run 10", "fell below dtmin = 1");
}

// the stability sentinel: a run whose h iteration fails for most particles, whose particles
// have no neighbour, or whose timestep collapses by more than the set share, stops with the
// cause and an atom ID (sentinel stop); a sound run does not
TEST(FixSPHAstroSentinel, StopsOnFailedHIterationAndOnATimestepCollapse)
{
  {
    auto lmp = open_lammps();
    gas(lmp, "box", 3, PAIR, "sph/astro courant 0.3 sentinel stop");
    commands(lmp, {"fix hvar all sph/astro/h iterate", "run 20"});    // sound: no report
    EXPECT_EQ(lmp->update->ntimestep, 20);
  }
  {
    auto lmp = open_lammps();
    gas(lmp, "box", 3, PAIR, "sph/astro courant 0.3 sentinel stop");
    commands(lmp, {"fix hvar all sph/astro/h iterate maxiter 1", "set group all d_h 0.3"});
    const std::string message = error_of(lmp, "run 20");
    EXPECT_NE(message.find("did not converge (first: atom"), std::string::npos) << message;
  }
  {    // fixed h far below the spacing: no particle has a neighbour
    auto lmp = open_lammps();
    gas(lmp, "box", 3, PAIR, "sph/astro courant 0.3 sentinel stop");
    commands(lmp, {"set group all d_h 0.05", "neighbor 0.02 bin"});
    const std::string message = error_of(lmp, "run 20");
    EXPECT_NE(message.find("108 of 108 particles (first: atom 1) have no neighbour"),
              std::string::npos)
        << message;
  }
  auto lmp = open_lammps();
  gas(lmp, "box", 3, PAIR, "sph/astro courant 0.3 sentinel stop hshare 1.0");
  commands(lmp, {"fix hvar all sph/astro/h iterate hfact 0.1", "set group all d_h 0.3"});
  const std::string message = error_of(lmp, "run 50");
  EXPECT_NE(message.find("fell below 1e-06 x the run's first timestep"), std::string::npos)
      << message;
  EXPECT_NE(message.find("limited by atom"), std::string::npos) << message;
}

TEST_F(BadInput, SentinelArguments)
{
  expect_error("fix gas all sph/astro sentinel loud", "sentinel 'loud' is not one of");
  expect_error("fix gas all sph/astro collapse 2", "collapse = 2 must be in [0, 1)");
  expect_error("fix gas all sph/astro hshare -1", "hshare = -1 must be in [0, 1]");
}

// velocities that are not finite are reported with the atom at the run's start; a huge finite
// one that collapses the timestep names the limiting atom; a second integrator on the same
// particles, a timestep setter and an empty group are reported
TEST_F(BadInput, VelocitiesAndOtherIntegrators)
{
  commands(lmp,
           {"pair_style " + std::string(PAIR), "pair_coeff * *", "fix gas all sph/astro",
            "set group all d_h 0.9", "set group all d_u 1.0", "velocity all set 0 0 0"});
  lmp->atom->v[lmp->atom->map(5)][0] = NAN;    // (set takes no NaN)
  expect_error("run 1", "atom 5 has velocity (nan, 0, 0) at the start of the run");
  commands(lmp, {"set atom 5 vx 1e300", "set atom 5 vy 1e300"});
  expect_error("run 1",
               "atom 5 has velocity (1e+300, 1e+300, 0) at the start of the run (step 0); "
               "velocities must be finite, with a finite square");
  commands(lmp, {"set atom 5 vx 0.0 vy 0.0", "fix reset all dt/reset 1 NULL 0.1 0.1"});
  expect_error("run 0", "fix reset (dt/reset) also sets the timestep");
  commands(lmp, {"unfix reset", "fix twice all nve"});
  EXPECT_EQ(error_of(lmp, "run 0"), "");    // a warning, not an error
}

// a particle created between runs starts with an empty SPH state, not with the h and u a ghost
// left in its memory slot: the next run names it and asks for its h
TEST(FixSPHAstro, ParticleCreatedBetweenRunsStartsEmpty)
{
  auto lmp = open_lammps();
  gas(lmp, "box", 3, PAIR, "sph/astro courant 0.3");
  commands(lmp, {"run 5", "create_atoms 1 single 1.3 1.3 1.3 units box"});
  const int i = lmp->atom->map(static_cast<int>(lmp->atom->natoms));
  ASSERT_GE(i, 0);
  EXPECT_EQ(per_atom(lmp, "h").at(static_cast<int>(lmp->atom->natoms)), 0.0);
  EXPECT_EQ(per_atom(lmp, "u").at(static_cast<int>(lmp->atom->natoms)), 0.0);
  const std::string message = error_of(lmp, "run 5");
  EXPECT_NE(
      message.find("atom " + std::to_string(lmp->atom->natoms) + " has smoothing length h = 0"),
      std::string::npos)
      << message;
}

// the switch's alpha in a flow where the viscosity acts: a restart and a run split in two
// continue bit for bit, because the setup forces of the continued run use the alpha of the
// last step's forces (d_alpha_force), not the alpha advanced since (the particles move fast
// enough for LAMMPS to re-neighbour at every step, so the split costs no round-off)
class SwitchRestart : public ::testing::TestWithParam<std::string> {};

TEST_P(SwitchRestart, RestartAndSplitRunContinueBitForBit)
{
  const std::string restart = "test_switch_restart.restart";
  const std::string av = "fix av all sph/astro/switch " + GetParam() + " 0.1 1.0 0.2";
  const std::vector<std::string> hvar = {"fix hvar all sph/astro/h iterate"};
  std::map<int, double> v_ref, u_ref, alpha_ref;
  auto start = [&](const std::unique_ptr<LAMMPS> &lmp) {
    gas(lmp, "box", 3, PAIR, "sph/astro courant 0.3");
    commands(lmp, hvar);
    commands(lmp, {av, "velocity all create 0.5 4928459"});
  };
  {
    auto lmp = open_lammps();
    start(lmp);
    commands(lmp, {"run 20", "write_restart " + restart, "run 20"});
    v_ref = per_atom(lmp, "v", 1);
    u_ref = per_atom(lmp, "u");
    alpha_ref = per_atom(lmp, "alpha");
  }
  auto expect_equal = [&](const std::unique_ptr<LAMMPS> &lmp, const char *what) {
    auto v = per_atom(lmp, "v", 1);
    auto u = per_atom(lmp, "u");
    auto alpha = per_atom(lmp, "alpha");
    ASSERT_EQ(v.size(), v_ref.size());
    int differ = 0;
    for (const auto &[id, value] : v_ref)
      if (v[id] != value || u[id] != u_ref[id] || alpha[id] != alpha_ref[id]) ++differ;
    EXPECT_EQ(differ, 0) << what << ": particles whose v, u or alpha differ";
  };
  {
    auto lmp = open_lammps();
    start(lmp);
    commands(lmp, {"run 40"});
    expect_equal(lmp, "run 40 against run 20 + run 20");
  }
  auto lmp = open_lammps();
  commands(lmp,
           {"read_restart " + restart, "fix gas all sph/astro courant 0.3",
            "neighbor " + num(0.3 * 1.2 * std::cbrt(0.25)) + " bin",
            "neigh_modify every 1 delay 0 check yes"});
  commands(lmp, hvar);
  commands(lmp, {av, "run 20"});
  expect_equal(lmp, "restart");
  std::remove(restart.c_str());
}

INSTANTIATE_TEST_SUITE_P(FixSPHAstroSwitch, SwitchRestart,
                         ::testing::Values("morris-monaghan", "cullen-dehnen"));
