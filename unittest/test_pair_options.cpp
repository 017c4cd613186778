/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// LAMMPS-driven tests of the alternative formulations of pair_style sph/astro (issue 3):
// density continuity (rho integrated by fix sph/astro; Monaghan 1992), symmetrise kernel
// (Hernquist & Katz 1989) and pressure geometric: uniform
// motion, conservation, energy error order, restart (settings and bit-for-bit continuation),
// neighbour counts, and the errors for bad values and combinations; formulation
// pressure-energy (Saitoh & Makino 2013, Hopkins 2013): the same checks, its reduction to the
// standard equations for uniform u, and a contact in pressure balance that feels no force. The
// Sod figures of the options are ctests (sod_short_*).

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
const std::string GAS = "sph/astro kernel m4 eos ideal $(5.0/3.0) viscosity classic 1.0 2.0";
}    // namespace

// GetParam(): the option keywords appended to GAS
class PairOption : public ::testing::TestWithParam<std::string> {};

// smoothing lengths varying by +-25 % from particle to particle, so that W(h_ij) and the
// averaged kernel differ (with equal h they coincide)
static void vary_h(const std::unique_ptr<LAMMPS> &lmp)
{
  commands(lmp,
           {"variable hvary atom " + num(1.2 * std::cbrt(0.25)) + "*(1.0+0.25*random(-1,1,5077))",
            "set group all d_h v_hvary"});
}

// ---------------------------------------------------------------- uniform motion

TEST(DensityContinuity, UniformMotionLeavesTheDensityUnchanged)
{
  // perfect periodic fcc lattice, uniform u, uniform velocity: v_ij = 0 for every pair, so
  // drho/dt = sum_j m_j v_ij . grad W_ij vanishes exactly (Monaghan 1992; the form
  // sum_j m_j v_j . grad W_ij would not)
  for (const std::string hfix : {"", "fix hvar all sph/astro/h dhdt"}) {
    auto lmp = open_lammps();
    gas(lmp, "box", 3, GAS + " density continuity", "sph/astro", 1.0, 0.0);
    if (!hfix.empty()) commands(lmp, {hfix});
    commands(lmp, {"set group all d_u 1.0", "velocity all set 0.7 -0.4 0.2", "run 0"});
    const auto rho0 = per_atom(lmp, "rho");
    commands(lmp, {"run 50"});
    const auto rho = per_atom(lmp, "rho");
    const auto drhodt = per_atom(lmp, "drhodt");
    const auto vx = per_atom(lmp, "v", 0);
    double worst = 0.0, worst_rate = 0.0;
    for (const auto &[id, r] : rho0) {
      worst = std::max(worst, std::fabs(rho.at(id) / r - 1.0));
      worst_rate = std::max(worst_rate, std::fabs(drhodt.at(id)));
      EXPECT_NEAR(vx.at(id), 0.7, 1e-12) << "atom " << id;
    }
    printf("uniform motion (%s): largest |rho/rho0 - 1| %.2e, largest |drho/dt| %.2e after 50 "
           "steps\n",
           hfix.empty() ? "fixed h" : "dhdt", worst, worst_rate);
    EXPECT_LT(worst, 1e-13);
    EXPECT_LT(worst_rate, 1e-12);
  }
}

TEST(DensityContinuity, StartsFromOneSummationAndThenIntegrates)
{
  // the first force evaluation sums rho (any d_rho set before is overwritten); afterwards the
  // integrated rho departs from the summed one only by the truncation error of the scheme
  std::map<int, double> rho_sum, rho_cont;
  for (const std::string density : {"summation", "continuity"}) {
    auto lmp = open_lammps();
    gas(lmp, "box", 3, GAS + " density " + density, "sph/astro dt fixed");
    commands(
        lmp,
        {"set group all d_rho 123.0", "velocity all create 0.5 4928459 dist gaussian", "run 0"});
    const auto rho_start = per_atom(lmp, "rho");
    for (const auto &[id, r] : rho_start) EXPECT_LT(std::fabs(r - 1.0), 0.1) << "atom " << id;
    if (density == "continuity") {
      const auto rhoest = per_atom(lmp, "rhoest");
      for (const auto &[id, r] : rho_start) EXPECT_EQ(rhoest.at(id), r);
    }
    commands(lmp, {"timestep 0.002", "run 50"});
    (density == "summation" ? rho_sum : rho_cont) = per_atom(lmp, "rho");
  }
  double worst = 0.0, mean_change = 0.0;
  for (const auto &[id, r] : rho_sum) {
    worst = std::max(worst, std::fabs(rho_cont.at(id) / r - 1.0));
    mean_change += std::fabs(r - 1.0) / rho_sum.size();
  }
  printf("continuity vs summation after t = 0.1: largest relative difference %.3e (mean "
         "|rho - 1| %.3e)\n",
         worst, mean_change);
  EXPECT_GT(worst, 0.0);
  EXPECT_LT(worst, 0.05);
}

// ---------------------------------------------------------------- conservation

TEST_P(PairOption, ForcesAreAntisymmetricAndMomentumIsConserved)
{
  auto lmp = open_lammps();
  gas(lmp, "ball", 6, GAS + " " + GetParam(), "sph/astro courant 0.3");
  vary_h(lmp);
  commands(lmp, {"velocity all zero linear", "velocity all zero angular", "run 0"});
  expect_forces_sum_to_zero(lmp);
  const auto start = global_vector(lmp, "sum", 12);
  commands(lmp, {"run 200"});
  const auto end = global_vector(lmp, "sum", 12);
  const double pscale = momentum_scale(lmp);
  ASSERT_GT(pscale, 0.0);
  for (int k : {PX, PY, PZ}) EXPECT_LT(std::fabs(end[k] - start[k]), 1e-12 * pscale) << k;
  for (int k : {LX, LY, LZ}) EXPECT_LT(std::fabs(end[k] - start[k]), 1e-11 * pscale) << k;
  EXPECT_DOUBLE_EQ(end[MASS], start[MASS]);
  EXPECT_GT(end[EKIN], 10 * start[EKIN]);    // the ball expands
  EXPECT_LT(std::fabs(end[DEREL]), 1e-3);
}

// relative total energy error of an expanding ball after t = 0.4 with fixed dt
static double energy_error(double dt, const std::string &options, const std::string &hfix = "")
{
  auto lmp = open_lammps();
  gas(lmp, "ball", 6, GAS + " " + options, "sph/astro dt fixed");
  vary_h(lmp);
  if (!hfix.empty()) commands(lmp, {hfix});
  const int nsteps = static_cast<int>(std::lround(0.4 / dt));
  commands(
      lmp,
      {"timestep " + num(dt), "thermo " + std::to_string(nsteps), "run " + std::to_string(nsteps)});
  return std::fabs(global_vector(lmp, "sum", 12)[DEREL]);
}

TEST_P(PairOption, EnergyErrorIsSecondOrderInTimestep)
{
  // the pair terms conserve energy exactly; what remains is the leapfrog's error ~ dt^2
  for (const std::string hfix : {"", "fix hvar all sph/astro/h dhdt margin 2.0"}) {
    const double e1 = energy_error(0.02, GetParam(), hfix),
                 e2 = energy_error(0.01, GetParam(), hfix),
                 e3 = energy_error(0.005, GetParam(), hfix);
    printf("%s%s: energy error dt 0.02 %.3e, 0.01 %.3e, 0.005 %.3e (ratios %.2f %.2f)\n",
           GetParam().c_str(), hfix.empty() ? "" : ", dhdt", e1, e2, e3, e1 / e2, e2 / e3);
    ASSERT_GT(e3, 0.0);
    EXPECT_LT(e1, 1e-2);
    EXPECT_NEAR(e1 / e2, 4.0, 1.0);
    EXPECT_NEAR(e2 / e3, 4.0, 1.0);
  }
}

// ---------------------------------------------------------------- restart

TEST_P(PairOption, RestartContinuesBitForBit)
{
  // the pair settings come back from the restart file (no pair_style after read_restart);
  // with density continuity also the integrated rho and its prediction d_rhoest
  const std::string restart = "test_pair_options.restart";
  std::map<int, double> x_ref, v_ref, u_ref, rho_ref;
  {
    auto lmp = open_lammps();
    gas(lmp, "box", 3, GAS + " " + GetParam(), "sph/astro courant 0.3");
    vary_h(lmp);
    commands(lmp,
             {"fix hvar all sph/astro/h dhdt", "velocity all create 0.5 4928459", "run 20",
              "write_restart " + restart, "run 20"});
    x_ref = per_atom(lmp, "x", 0);
    v_ref = per_atom(lmp, "v", 1);
    u_ref = per_atom(lmp, "u");
    rho_ref = per_atom(lmp, "rho");
  }
  auto lmp = open_lammps();
  commands(lmp,
           {"read_restart " + restart, "fix gas all sph/astro courant 0.3",
            "fix hvar all sph/astro/h dhdt",
            "neighbor " + num(0.3 * 1.2 * std::cbrt(0.25)) + " bin",
            "neigh_modify every 1 delay 0 check yes", "run 20"});
  auto x = per_atom(lmp, "x", 0);
  auto v = per_atom(lmp, "v", 1);
  auto u = per_atom(lmp, "u");
  auto rho = per_atom(lmp, "rho");
  ASSERT_EQ(x.size(), x_ref.size());
  for (const auto &[id, value] : x_ref) {
    EXPECT_EQ(x[id], value) << "atom " << id;
    EXPECT_EQ(v[id], v_ref[id]) << "atom " << id;
    EXPECT_EQ(u[id], u_ref[id]) << "atom " << id;
    EXPECT_EQ(rho[id], rho_ref[id]) << "atom " << id;
  }
  std::remove(restart.c_str());
}

INSTANTIATE_TEST_SUITE_P(PairSPHAstro, PairOption,
                         ::testing::Values("", "density continuity", "symmetrise kernel",
                                           "pressure geometric", "formulation pressure-energy",
                                           "density continuity symmetrise kernel pressure "
                                           "geometric"));

TEST(PairOptions, SettingsComeBackFromARestartFile)
{
  // each option refuses fix sph/astro/h iterate at init (pressure-energy: thermal entropy):
  // after read_restart without a new pair_style that error shows that the setting was restored
  const std::string restart = "test_pair_options_settings.restart";
  for (const std::string option : {"density continuity", "symmetrise kernel", "pressure geometric",
                                   "formulation pressure-energy", ""}) {
    const bool pe = option == "formulation pressure-energy";
    {
      auto lmp = open_lammps();
      gas(lmp, "box", 2, GAS + " " + option, "sph/astro");
      commands(lmp, {"run 2", "write_restart " + restart});
    }
    auto lmp = open_lammps();
    commands(lmp,
             {"read_restart " + restart,
              pe ? "fix gas all sph/astro thermal entropy" : "fix gas all sph/astro",
              "fix hvar all sph/astro/h iterate"});
    const std::string message = error_of(lmp, "run 0");
    const std::string expected = pe ? "needs fix sph/astro thermal energy"
                                    : "needs fixed h or fix sph/astro/h dhdt";
    if (option.empty())
      EXPECT_EQ(message, "");
    else
      EXPECT_NE(message.find("pair_style sph/astro " + option + " " + expected), std::string::npos)
          << option << ": " << message;
  }
  std::remove(restart.c_str());
}

TEST(DensityContinuity, DataFileRoundTrip)
{
  // write_data adds the section SPH_ASTRO_CONTINUITY; read back with its fix defined first
  const std::string data = "test_pair_options.data";
  std::map<int, double> h_ref;
  {
    auto lmp = open_lammps();
    gas(lmp, "box", 2, GAS + " density continuity", "sph/astro");
    commands(lmp, {"run 5", "write_data " + data});
    h_ref = per_atom(lmp, "h");
  }
  auto lmp = open_lammps();
  commands(lmp,
           {"units lj", "atom_style atomic", "atom_modify map array", "sph/astro/state",
            "fix SPH_ASTRO_CONTINUITY all property/atom d_rhoest d_drhodt ghost yes",
            "read_data " + data +
                " fix SPH_ASTRO_STATE NULL SPH_ASTRO_STATE fix SPH_ASTRO_CONTINUITY NULL "
                "SPH_ASTRO_CONTINUITY",
            "pair_style " + GAS + " density continuity", "pair_coeff * *", "fix gas all sph/astro",
            "run 0"});
  const auto h = per_atom(lmp, "h");
  const auto rho = per_atom(lmp, "rho");
  ASSERT_EQ(h.size(), h_ref.size());
  for (const auto &[id, value] : h_ref) {
    EXPECT_EQ(h.at(id), value);
    EXPECT_GT(rho.at(id), 0.5);
  }
  std::remove(data.c_str());
}

// ---------------------------------------------------------------- pressure-energy

TEST(PressureEnergy, UniformEnergyGivesTheDensityEnergyEquations)
{
  // with u_j = u_i the smoothed pressure is (gamma-1) u rho_i and every pair term reduces to
  // the density-energy one: (gamma-1)^2 u^2 / P_i = P_i / rho_i^2 (fixed h, varying from
  // particle to particle); with fix sph/astro/h iterate C_i = (gamma-1) u h_i (drho^m_i/dh_i)
  // / (d rho^m_i Omega_i) = (gamma-1) u (1 - 1/Omega_i), so e_i (e_j - C_i) / P_i = P_i /
  // (Omega_i rho_i^2): the grad-h equations
  const char *names[] = {"fx", "fy", "fz", "rho", "du/dt", "h"};
  for (const bool iterate : {false, true}) {
    std::map<int, double> out[2][6];
    int k = 0;
    for (const std::string formulation : {"density-energy", "pressure-energy"}) {
      auto lmp = open_lammps();
      gas(lmp, "box", 3, GAS + " formulation " + formulation, "sph/astro");
      if (iterate)
        commands(lmp, {"fix hvar all sph/astro/h iterate"});
      else
        vary_h(lmp);
      commands(lmp, {"set group all d_u 1.3", "velocity all create 0.3 4928459", "run 0"});
      for (int d = 0; d < 3; d++) out[k][d] = per_atom(lmp, "f", d);
      out[k][3] = per_atom(lmp, "rho");
      out[k][4] = per_atom(lmp, "dudt");
      out[k][5] = per_atom(lmp, "h");
      k++;
    }
    for (int q = 0; q < 6; q++) {
      double scale = 0.0, worst = 0.0;
      for (const auto &[id, value] : out[0][q]) {
        scale = std::max(scale, std::fabs(value));
        worst = std::max(worst, std::fabs(out[1][q].at(id) - value));
      }
      printf("uniform u, %s h: %s largest |difference| / largest value %.2e\n",
             iterate ? "iterated" : "fixed", names[q], worst / scale);
      ASSERT_GT(scale, 0.0);
      EXPECT_LE(worst, 1e-12 * scale) << names[q];
    }
  }
}

TEST(PressureEnergy, GradHConservesMomentumAndEnergyToSecondOrder)
{
  // expanding ball with u varying by +-20 %, fix sph/astro/h iterate: forces pairwise
  // antisymmetric, and the energy equation matches the force pair by pair (for any C), so the
  // energy error is the leapfrog's, ~ dt^2
  auto run = [](double dt) {
    auto lmp = open_lammps();
    gas(lmp, "ball", 6, GAS + " formulation pressure-energy", "sph/astro dt fixed");
    const int nsteps = static_cast<int>(std::lround(0.4 / dt));
    commands(lmp,
             {"fix hvar all sph/astro/h iterate tol 1e-10", "timestep " + num(dt),
              "thermo " + std::to_string(nsteps), "run 0"});
    expect_forces_sum_to_zero(lmp);
    commands(lmp, {"run " + std::to_string(nsteps)});
    return std::fabs(global_vector(lmp, "sum", 12)[DEREL]);
  };
  const double e1 = run(0.02), e2 = run(0.01), e3 = run(0.005);
  printf("pressure-energy, iterate: energy error dt 0.02 %.3e, 0.01 %.3e, 0.005 %.3e (ratios "
         "%.2f %.2f)\n",
         e1, e2, e3, e1 / e2, e2 / e3);
  ASSERT_GT(e3, 0.0);
  EXPECT_LT(e1, 1e-2);
  EXPECT_NEAR(e1 / e2, 4.0, 1.0);
  EXPECT_NEAR(e2 / e3, 4.0, 1.0);
}

TEST(PressureEnergy, AdiabaticFlowKeepsItsEntropyOnlyWithDensityEnergy)
{
  // no viscosity, uniform u at the start, a jittered ball expanding into vacuum: the
  // density-energy equations keep A = P / rho^gamma of each particle to the time-integration
  // error (du/dt is exactly P/rho^2 drho/dt, also with grad-h terms); pressure-energy does not
  // where u varies between neighbours (rho_i = P_i/((gamma-1) u_i) then moves with the
  // neighbours' u, which its P dV term holds fixed)
  const double gamma = 5.0 / 3.0;
  for (const std::string form : {"density-energy", "pressure-energy"})
    for (const bool iterate : {false, true}) {
      auto lmp = open_lammps();
      gas(lmp, "ball", 6, "sph/astro eos ideal $(5.0/3.0) viscosity none formulation " + form,
          "sph/astro dt fixed");
      commands(
          lmp,
          {"set group all d_u 1.0", "timestep 0.001", "compute p all sph/astro/atom pressure"});
      if (iterate) commands(lmp, {"fix hvar all sph/astro/h iterate tol 1e-10"});
      auto entropies = [&]() {
        auto *p = static_cast<double *>(
            lammps_extract_compute(lmp.get(), "p", LMP_STYLE_ATOM, LMP_TYPE_VECTOR));
        const auto rho = per_atom(lmp, "rho");
        std::map<int, double> a;
        for (int i = 0; i < lmp->atom->nlocal; i++)
          a[lmp->atom->tag[i]] = p[i] / std::pow(rho.at(lmp->atom->tag[i]), gamma);
        return a;
      };
      commands(lmp, {"run 0"});
      const auto a0 = entropies();
      commands(lmp, {"run 200"});
      const auto a1 = entropies();
      double drift = 0.0;
      for (const auto &[id, a] : a0) drift = std::max(drift, std::fabs(a1.at(id) / a - 1.0));
      printf("%s, %s h, no viscosity, t = 0.2: largest |A/A0 - 1| %.2e\n", form.c_str(),
             iterate ? "iterated" : "fixed", drift);
      if (form == "density-energy")
        EXPECT_LT(drift, 1e-5);
      else {
        EXPECT_GT(drift, 1e-3);    // the property documented in doc/Howto_sph_astro_options.rst
        EXPECT_LT(drift, 5e-2);
      }
    }
}

// a periodic fcc box, left half masses 1/4 and u = 1, right half masses 1/16 and u = 4 on the
// same lattice: density 4:1 and equal pressure (the contact of shock3d, in pressure balance)
static const double CONTACT_H = 1.5 * std::cbrt(0.25);
static std::unique_ptr<LAMMPS> contact(const std::string &formulation)
{
  auto lmp = open_lammps();
  const double h = CONTACT_H;
  commands(lmp,
           {"units lj",
            "atom_style atomic",
            "atom_modify map array sort 0 0.0",
            "boundary p p p",
            "lattice fcc 4.0",
            "region box block 0 8 0 3 0 3",
            "create_box 2 box",
            "create_atoms 1 box",
            "region right block 4 8 INF INF INF INF",
            "set region right type 2",
            "mass 1 0.25",
            "mass 2 0.0625",
            "pair_style " + GAS + " formulation " + formulation,
            "pair_coeff * *",
            "fix gas all sph/astro courant 0.3",
            "set group all d_h " + num(h),
            "set type 1 d_u 1.0",
            "set type 2 d_u 4.0",
            "neighbor " + num(0.3 * h) + " bin",
            "neigh_modify every 1 delay 0 check yes",
            "compute sum all sph/astro/global",
            "compute p all sph/astro/atom pressure",
            "thermo_style custom step c_sum[12]",
            "run 0"});
  return lmp;
}

static double largest_force(const std::unique_ptr<LAMMPS> &lmp)
{
  double worst = 0.0;
  for (int i = 0; i < lmp->atom->nlocal; i++)
    for (int d = 0; d < 3; d++) worst = std::max(worst, std::fabs(lmp->atom->f[i][d]));
  return worst;
}

TEST(PressureEnergy, ContactInPressureBalanceFeelsNoForce)
{
  // m_j u_j is the same for every particle, so the smoothed pressure is uniform and each
  // particle's pressure force is a multiple of sum_j grad W_ij = 0 on the perfect lattice; the
  // density summation instead smooths rho across the contact, and rho u gives the two layers
  // next to it a pressure blip that pushes them apart
  const double gm1 = 2.0 / 3.0;
  double blip[2], force[2];
  int k = 0;
  for (const std::string formulation : {"density-energy", "pressure-energy"}) {
    auto lmp = contact(formulation);
    auto *p = static_cast<double *>(
        lammps_extract_compute(lmp.get(), "p", LMP_STYLE_ATOM, LMP_TYPE_VECTOR));
    ASSERT_NE(p, nullptr);
    const auto rho = per_atom(lmp, "rho");
    const auto u = per_atom(lmp, "u");
    double pmin = INFINITY, pmax = 0.0, p_left = 0.0;
    for (int i = 0; i < lmp->atom->nlocal; i++) {
      pmin = std::min(pmin, p[i]);
      pmax = std::max(pmax, p[i]);
      if (lmp->atom->type[i] == 1) p_left = p[i];
      // P = (gamma-1) rho u in both formulations
      const int id = lmp->atom->tag[i];
      EXPECT_NEAR(p[i], gm1 * rho.at(id) * u.at(id), 1e-13 * p[i]);
    }
    blip[k] = (pmax - pmin) / p_left;
    // the scale of a pressure force on a left particle: m P / (rho h), m = 1/4, rho ~ 1
    force[k] = largest_force(lmp) / (0.25 * p_left / CONTACT_H);
    if (formulation == "pressure-energy") {
      // rho jumps by 4 from one layer to the next (the left and right lattice sums are equal)
      double rho_left = 0.0, rho_right = 0.0;
      for (int i = 0; i < lmp->atom->nlocal; i++)
        (lmp->atom->type[i] == 1 ? rho_left : rho_right) = rho.at(lmp->atom->tag[i]);
      for (const auto &[id, r] : rho)
        EXPECT_NEAR(r, u.at(id) == 1.0 ? rho_left : rho_right, 1e-12 * r) << "atom " << id;
      EXPECT_NEAR(rho_left / rho_right, 4.0, 1e-12);
      // and the contact stays in place: no particle moves beyond round-off in 50 steps
      commands(lmp, {"run 50"});
      double vmax = 0.0;
      for (int i = 0; i < lmp->atom->nlocal; i++)
        for (int d = 0; d < 3; d++) vmax = std::max(vmax, std::fabs(lmp->atom->v[i][d]));
      printf("pressure-energy contact after 50 steps: largest |v| %.2e (c_s %.3f)\n", vmax,
             std::sqrt(gm1 * 5.0 / 3.0));
      EXPECT_LT(vmax, 1e-10);
    }
    k++;
  }
  printf("contact 4:1 in pressure balance: (P_max - P_min) / P %.3e / %.3e, largest force "
         "(P/h units) %.3e / %.3e (density-energy / pressure-energy)\n",
         blip[0], blip[1], force[0], force[1]);
  EXPECT_GT(blip[0], 0.1);
  EXPECT_LT(blip[1], 1e-12);
  EXPECT_GT(force[0], 0.1);
  EXPECT_LT(force[1], 1e-12);
}

// ---------------------------------------------------------------- per-atom output

TEST(DensityContinuity, NeighbourCountsMatchTheSummation)
{
  // without a summation pass the counts of compute sph/astro/atom come from a pass of their own
  for (const std::string sym : {"hmean", "kernel"}) {
    std::map<int, double> counts[2];
    int k = 0;
    for (const std::string density : {"summation", "continuity"}) {
      auto lmp = open_lammps();
      gas(lmp, "box", 3, GAS + " symmetrise " + sym + " density " + density, "sph/astro");
      vary_h(lmp);
      // the first run sums rho in both cases; the second one of continuity counts by itself
      commands(lmp, {"compute n all sph/astro/atom nneigh", "run 0", "run 0"});
      auto *n = static_cast<double *>(
          lammps_extract_compute(lmp.get(), "n", LMP_STYLE_ATOM, LMP_TYPE_VECTOR));
      ASSERT_NE(n, nullptr);
      for (int i = 0; i < lmp->atom->nlocal; i++) counts[k][lmp->atom->tag[i]] = n[i];
      k++;
    }
    ASSERT_FALSE(counts[0].empty());
    double total = 0.0;
    for (const auto &[id, n] : counts[0]) {
      EXPECT_EQ(counts[1].at(id), n) << "atom " << id;
      total += n;
    }
    printf("symmetrise %s: mean neighbour count %.2f\n", sym.c_str(), total / counts[0].size());
  }
}

// ---------------------------------------------------------------- bad input

class BadOptionInput : public BadInputTest {
 protected:
  void setup_with(const std::string &options, const std::string &fix = "sph/astro")
  {
    commands(lmp,
             {"pair_style " + GAS + " " + options, "pair_coeff * *", "fix gas all " + fix,
              "set group all d_h 0.75", "set group all d_u 1.0"});
  }
};

TEST_F(BadOptionInput, KeywordValuesNameTheStyleTheValueAndTheChoices)
{
  expect_error("pair_style sph/astro density sum",
               "pair_style sph/astro: unknown density 'sum'; allowed: summation, continuity");
  expect_error("pair_style sph/astro symmetrise average",
               "pair_style sph/astro: unknown symmetrise 'average'; allowed: hmean, kernel");
  expect_error("pair_style sph/astro pressure mean",
               "pair_style sph/astro: unknown pressure 'mean'; allowed: standard, geometric");
  expect_error("pair_style sph/astro density", "Illegal pair_style sph/astro density");
  expect_error("pair_style sph/astro symmetrise", "Illegal pair_style sph/astro symmetrise");
  expect_error("pair_style sph/astro pressure", "Illegal pair_style sph/astro pressure");
  expect_error("pair_style sph/astro symmetrize kernel",
               "unknown keyword 'symmetrize'; allowed: kernel, eos, viscosity, balsara, "
               "reconstruct, conductivity, conduction, epsilon, density, symmetrise, pressure, "
               "formulation");
  expect_error("pair_style sph/astro prune yes", "unknown keyword 'prune'");
  expect_error("pair_style sph/astro formulation entropy-energy",
               "pair_style sph/astro: unknown formulation 'entropy-energy'; allowed: "
               "density-energy, pressure-energy");
  expect_error("pair_style sph/astro formulation", "Illegal pair_style sph/astro formulation");
  expect_error("pair_style sph/astro reconstruct yes gate 100",
               "reconstruct gate 100 must be an integer in 0-64");
  expect_error("pair_style sph/astro reconstruct yes trigger -1",
               "reconstruct trigger -1 must be >= 0");
}

TEST_F(BadOptionInput, OptionsNeedFixedOrDhdtSmoothingLengths)
{
  setup_with("density continuity");
  commands(lmp, {"fix hvar all sph/astro/h iterate"});
  expect_error("run 0",
               "pair_style sph/astro density continuity needs fixed h or fix sph/astro/h dhdt: "
               "with fix sph/astro/h iterate h follows from the summed density");
  commands(lmp, {"pair_style " + GAS + " symmetrise kernel"});
  expect_error("run 0",
               "pair_style sph/astro symmetrise kernel needs fixed h or fix "
               "sph/astro/h dhdt");
  commands(lmp, {"pair_style " + GAS + " pressure geometric"});
  expect_error("run 0",
               "pair_style sph/astro pressure geometric needs fixed h or fix "
               "sph/astro/h dhdt");
  commands(lmp, {"unfix hvar", "run 0"});    // fine with fixed h
}

TEST_F(BadOptionInput, GeometricPressureNeedsTheEnergyEquation)
{
  setup_with("pressure geometric", "sph/astro thermal entropy");
  expect_error("run 0",
               "pair_style sph/astro pressure geometric needs fix sph/astro thermal "
               "energy");
}

TEST_F(BadOptionInput, PressureEnergyNamesWhatItNeeds)
{
  const std::string pe = "pair_style sph/astro formulation pressure-energy needs ";
  setup_with("formulation pressure-energy");
  for (const auto &[options, needs] : std::vector<std::pair<std::string, std::string>>{
           {"eos isothermal 1.0", "eos ideal"},
           {"density continuity", "density summation"},
           {"symmetrise kernel", "symmetrise hmean"},
           {"pressure geometric", "pressure standard"}}) {
    commands(lmp, {"pair_style sph/astro " + options + " formulation pressure-energy"});
    if (options == "eos isothermal 1.0") commands(lmp, {"pair_coeff * *"});
    expect_error("run 0", pe + needs);
  }
  commands(lmp,
           {"pair_style " + GAS + " formulation pressure-energy", "unfix gas",
            "fix gas all sph/astro thermal entropy"});
  expect_error("run 0", pe + "fix sph/astro thermal energy");
  commands(lmp, {"unfix gas", "fix gas all sph/astro", "run 0"});    // fine
  // u = 0 has no pressure-energy density: the error names the atom
  commands(lmp, {"set atom 3 d_u 0.0"});
  expect_error("run 0",
               "formulation pressure-energy: atom 3 has specific internal energy u = 0; this "
               "formulation needs u > 0");
}
