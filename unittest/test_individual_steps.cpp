/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// LAMMPS-driven tests of individual timesteps (fix sph/astro steps individual): one bin is the
// global leapfrog, a hot spot spreads the particles over bins and evaluates fewer of them,
// the limiter, restarts and continued runs mid-hierarchy, output, and the errors.

#include "styles_fixture.h"

#include "fix.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>

using namespace sph_astro_test;

namespace {

// a periodic box of gas with a hot spot of radius 1 (lattice units) at the centre, u = hot
void hot_spot(const std::unique_ptr<LAMMPS_NS::LAMMPS> &lmp, int n, const std::string &fix,
              double hot = 200.0)
{
  gas(lmp, "box", n, PAIR, fix, 0.01, 0.02);
  const std::string c = num(0.5 * n);
  commands(lmp,
           {"velocity all set 0 0 0", "region hot sphere " + c + " " + c + " " + c + " 1.0",
            "set region hot d_u " + num(hot), "fix hvar all sph/astro/h iterate hfact 1.2"});
}

double fix_value(const std::unique_ptr<LAMMPS_NS::LAMMPS> &lmp, const char *id, int n)
{
  return lmp->modify->get_fix_by_id(id)->compute_vector(n);
}

}    // namespace

// with every particle in the top bin (dtmax below every criterion) the scheme is the global
// kick-drift-kick leapfrog with that step
TEST(IndividualSteps, OneBinIsTheGlobalLeapfrog)
{
  std::map<int, double> x_ref, v_ref, u_ref, h_ref;
  {
    auto lmp = open_lammps();
    gas(lmp, "box", 3, PAIR, "sph/astro dt fixed");
    commands(lmp, {"fix hvar all sph/astro/h iterate", "timestep 0.002", "run 30"});
    x_ref = per_atom(lmp, "x", 0);
    v_ref = per_atom(lmp, "v", 1);
    u_ref = per_atom(lmp, "u");
    h_ref = per_atom(lmp, "h");
  }
  auto lmp = open_lammps();
  gas(lmp, "box", 3, PAIR, "sph/astro steps individual dtmax 0.002");
  commands(lmp, {"fix hvar all sph/astro/h iterate", "run 30"});
  EXPECT_DOUBLE_EQ(lmp->update->dt, 0.002);
  EXPECT_EQ(fix_value(lmp, "gas", 4), lmp->atom->natoms);    // all active
  EXPECT_EQ(fix_value(lmp, "gas", 5), 1.0);                  // one bin
  auto x = per_atom(lmp, "x", 0);
  auto v = per_atom(lmp, "v", 1);
  auto u = per_atom(lmp, "u");
  auto h = per_atom(lmp, "h");
  ASSERT_EQ(x.size(), x_ref.size());
  // (the same steps; a = f/m is kept, so the kicks round differently)
  for (const auto &[id, value] : x_ref) {
    EXPECT_NEAR(x[id], value, 1e-12) << id;
    EXPECT_NEAR(v[id], v_ref[id], 1e-12) << id;
    EXPECT_NEAR(u[id], u_ref[id], 1e-12) << id;
    EXPECT_NEAR(h[id], h_ref[id], 1e-12) << id;
  }
}

// a hot spot in cold gas: its particles step short, the rest long; far fewer particle-updates
// than steps x particles; the energy error stays small, momentum is kept to round-off. vsig:
// the default viscosity (each particle's own signal speed: the limiter wakes the cold gas the
// blast reaches) or pairs (a cold particle next to hot gas takes its sound speed at its next
// evaluation)
class HotSpot : public ::testing::TestWithParam<std::string> {};

TEST_P(HotSpot, SpreadsParticlesOverBins)
{
  auto lmp = open_lammps();
  hot_spot(lmp, 5, "sph/astro courant 0.3 steps individual tend 0.05" + GetParam());
  commands(lmp,
           {"compute bins all sph/astro/atom bin", "thermo_style custom step c_sum[12] f_gas[5]",
            "run 100000"});
  const double n = static_cast<double>(lmp->atom->natoms);
  const double steps = static_cast<double>(lmp->update->ntimestep);
  EXPECT_NEAR(lmp->update->atime +
                  (lmp->update->ntimestep - lmp->update->atimestep) * lmp->update->dt,
              0.05, 1e-12);
  EXPECT_GE(fix_value(lmp, "gas", 5), 3.0);
  const double updates = fix_value(lmp, "gas", 6);
  EXPECT_LT(updates, 0.5 * steps * n) << updates << " updates, " << steps << " steps";
  EXPECT_GT(updates, n);
  std::printf("%.0f updates in %.0f steps, %.0f woken by the limiter\n", updates, steps,
              fix_value(lmp, "gas", 7));
  if (GetParam().empty()) EXPECT_GT(fix_value(lmp, "gas", 7), 0.0);
  const auto sum = global_vector(lmp, "sum", 12);
  EXPECT_LT(std::fabs(sum[DEREL]), 2e-2);
  // momentum: the default kicks pair conserves it to round-off (kicks particle: the next test)
  const double scale = momentum_scale(lmp);
  for (int k : {PX, PY, PZ}) EXPECT_LT(std::fabs(sum[k]), 1e-13 * scale) << k;
  // the bins: hot particles in the shortest ones
  auto *bins = static_cast<double *>(
      lammps_extract_compute(lmp.get(), "bins", LMP_STYLE_ATOM, LMP_TYPE_VECTOR));
  ASSERT_NE(bins, nullptr);
  double lo = 1e9, hi = -1.0;
  for (int i = 0; i < lmp->atom->nlocal; i++) {
    lo = std::min(lo, bins[i]);
    hi = std::max(hi, bins[i]);
  }
  EXPECT_GE(hi - lo, 2.0);
}

INSTANTIATE_TEST_SUITE_P(IndividualSteps, HotSpot, ::testing::Values("", " vsig pairs"),
                         [](const auto &info) {
                           return info.param.empty() ? "vsig_viscosity" : "vsig_pairs";
                         });

// kicks pair: each pair kicks both its particles with the same impulse, so the total momentum
// is conserved to round-off (the initial momentum is 0); kicks particle does not
TEST(IndividualSteps, PairKicksConserveMomentumToRoundOff)
{
  double drift[2];
  for (int pair = 0; pair < 2; pair++) {
    auto lmp = open_lammps();
    hot_spot(lmp, 5,
             std::string("sph/astro courant 0.3 steps individual tend 0.05 kicks ") +
                 (pair ? "pair" : "particle"));
    commands(lmp, {"run 100000"});
    EXPECT_GE(fix_value(lmp, "gas", 5), 3.0);    // several bins
    const auto sum = global_vector(lmp, "sum", 12);
    const double scale = momentum_scale(lmp);
    drift[pair] = std::max({std::fabs(sum[PX]), std::fabs(sum[PY]), std::fabs(sum[PZ])}) / scale;
    std::printf("kicks %s: largest momentum component %g of sum m|v| %g, energy error %g\n",
                pair ? "pair" : "particle", drift[pair] * scale, scale, sum[DEREL]);
    EXPECT_LT(std::fabs(sum[DEREL]), 2e-2);
  }
  EXPECT_LT(drift[1], 1e-13);
  EXPECT_GT(drift[0], 1e3 * drift[1]);
}

// inside its step a particle follows x_b + v_b tau + a tau^2 / 2 (the drift takes the
// velocity predicted at the middle of each LAMMPS step), so that active particles see their
// sleeping neighbours where they are at that time; the step ends where kick-drift-kick puts
// it, x_b + (v_b + a dt / 2) dt. Checked at every LAMMPS step inside each observed step:
// x = x_b + (x_e - x_b) tau / dt + a tau (tau - dt) / 2, a = f/m (an inactive particle's f is
// that of its last evaluation)
TEST(IndividualSteps, SleepingParticlesDriftOnTheirParabola)
{
  auto lmp = open_lammps();
  hot_spot(lmp, 5, "sph/astro courant 0.3 steps individual tend 0.03 kicks particle");
  commands(lmp, {"thermo 1000", "run 0"});
  struct Record {
    double t, begin, x[3], a[3];
  };
  std::map<int, std::vector<Record>> history;
  const double mass = lmp->atom->mass[1];
  for (int step = 0; step < 400; step++) {
    auto *u = lmp->update;
    const double t = u->atime + (u->ntimestep - u->atimestep) * u->dt;
    if (t >= 0.03 - 1e-12) break;
    commands(lmp, {"run 1 post no"});
    const double now = u->atime + (u->ntimestep - u->atimestep) * u->dt;
    std::map<int, double> x[3], f[3];
    for (int d = 0; d < 3; d++) {
      x[d] = per_atom(lmp, "x", d);
      f[d] = per_atom(lmp, "f", d);
    }
    const auto begin = per_atom(lmp, "step_begin");
    for (const auto &[id, b] : begin) {
      Record r{now, b, {x[0][id], x[1][id], x[2][id]}, {}};
      for (int d = 0; d < 3; d++) r.a[d] = f[d][id] / mass;
      history[id].push_back(r);
    }
  }
  // a step: the records from the one where begin changed to the next change
  int checked = 0;
  double worst = 0.0, curvature = 0.0;
  for (const auto &[id, rec] : history) {
    for (std::size_t s = 1; s < rec.size(); s++) {
      if (rec[s].begin == rec[s - 1].begin) continue;
      std::size_t e = s + 1;
      while (e < rec.size() && rec[e].begin == rec[s].begin) e++;
      if (e >= rec.size()) break;    // the step did not end in the run
      const Record &rb = rec[s], &re = rec[e];
      const double dt = re.t - rb.t;
      for (std::size_t k = s + 1; k < e; k++) {
        const double tau = rec[k].t - rb.t;
        for (int d = 0; d < 3; d++) {
          const double bend = 0.5 * rec[k].a[d] * tau * (tau - dt);
          const double expected = rb.x[d] + (re.x[d] - rb.x[d]) * tau / dt + bend;
          worst = std::max(worst, std::fabs(rec[k].x[d] - expected));
          curvature = std::max(curvature, std::fabs(bend));
        }
        checked++;
      }
      s = e - 1;
    }
  }
  std::printf("%d positions inside steps: largest deviation %g from the parabola, largest "
              "bend %g\n",
              checked, worst, curvature);
  EXPECT_GT(checked, 100);
  EXPECT_GT(curvature, 1e-8);    // the parabola differs from the chord
  EXPECT_LT(worst, 1e-3 * curvature);
}

// kicks pair: a sleeping particle's prediction (its velocity in the force evaluations of its
// active neighbours) takes the forces its pairs got at their evaluations since its own. Kept
// at the forces of its own evaluation, the prediction lags behind the pushes a blast gives it,
// and each pair's heating -F_ij . v_ij no longer matches the kinetic energy its kicks give.
// Hot spots (u = 2000 in cold gas) with a limiter of 2 levels (factor 4): measured energy
// errors 5e-6 (n 6, t 0.1) and -4.0e-4 (n 8, t 0.2); with the prediction of the particle's
// own evaluation 2.0e-3 and 3.1e-3
TEST(IndividualSteps, SleepingParticlesPredictWithTheirPairsNewForces)
{
  for (const auto &[n, tend] : {std::pair<int, double>{6, 0.1}, {8, 0.2}}) {
    auto lmp = open_lammps();
    hot_spot(lmp, n, "sph/astro courant 0.3 steps individual limiter 2 tend " + num(tend), 2000.0);
    commands(lmp, {"thermo 1000", "run 100000"});
    const auto sum = global_vector(lmp, "sum", 12);
    std::printf("n %d: energy error %g, %g particles woken\n", n, sum[DEREL],
                fix_value(lmp, "gas", 7));
    EXPECT_GE(fix_value(lmp, "gas", 5), 3.0);      // occupied bins
    EXPECT_GT(fix_value(lmp, "gas", 7), 100.0);    // woken
    EXPECT_LT(std::fabs(sum[DEREL]), 6e-4) << "n " << n;
  }
}

// fix sph/astro's energy at the synchronisation points (vector 9 and 10), the steps at which
// every particle ends its step: there compute sph/astro/global's sums hold no prediction, so
// its energy error is the fix's. Run by run (one step each: the thermo prints the energy at
// every step) the two agree at each such step, and the fix's value stays between them; in one
// run whose thermo prints only at its ends the fix has the potential energy tallied at those
// steps itself and finds the same largest error.
TEST(IndividualSteps, EnergyIsMeasuredAtEverySynchronisationPoint)
{
  const std::string fix = "sph/astro courant 0.3 steps individual limiter 2 dtmax 0.005 tend 0.05";
  double largest = 0.0;
  int points = 0, steps = 0;
  {
    auto lmp = open_lammps();
    hot_spot(lmp, 5, fix, 2000.0);
    const double n = static_cast<double>(lmp->atom->natoms);
    double latest = NAN;    // (until a point after the one that set E0)
    while (steps < 5000) {
      commands(lmp, {"run 1 pre no post no"});
      steps++;
      const auto sum = global_vector(lmp, "sum", 12);
      if (fix_value(lmp, "gas", 4) == n) {    // every particle active: a synchronisation point
        EXPECT_NEAR(fix_value(lmp, "gas", 8), sum[DEREL], 1e-12) << "step " << steps;
        latest = fix_value(lmp, "gas", 8);
        largest = std::max(largest, std::fabs(latest));
        points++;
      } else if (std::isnan(latest))
        EXPECT_TRUE(std::isnan(fix_value(lmp, "gas", 8))) << "step " << steps;
      else
        EXPECT_EQ(fix_value(lmp, "gas", 8), latest) << "step " << steps;
      if (lmp->update->atime +
              (lmp->update->ntimestep - lmp->update->atimestep) * lmp->update->dt >=
          0.05 * (1.0 - 1e-12))
        break;
    }
  }
  std::printf("%d synchronisation points in %d steps, largest energy error %g\n", points, steps,
              largest);
  EXPECT_GT(points, 3);
  EXPECT_LT(points, steps / 2);
  EXPECT_GT(largest, 0.0);
  auto lmp = open_lammps();
  hot_spot(lmp, 5, fix, 2000.0);
  commands(lmp, {"thermo 100000", "run 100000"});
  EXPECT_EQ(lmp->update->ntimestep, steps);
  EXPECT_NEAR(fix_value(lmp, "gas", 9), largest, 1e-12);
}

// a run in which no synchronisation point follows the one that set E0 (no tend or dtmax: the
// cold gas steps dt_max, longer than the run) has measured no energy error there: the fix's
// vector 9 and 10 are NaN, not 0, and the log says so and why, while compute sph/astro/global
// reads the energy error with the predictions. Here the blast without the limiter loses 28 % of
// its energy to the sleeping gas it runs into (the fix's outputs read 0). With the limiter
// off, and with limiter or kicks given to global steps, or longdisplacement without longrange
// sync, the fix warns, naming the keyword
TEST(IndividualSteps, EnergyErrorWithoutASynchronisationPointIsNotAReading)
{
  const std::string log = "test_individual_steps_sync.log";
  {
    auto lmp = open_lammps();
    commands(lmp, {"log " + log});
    hot_spot(lmp, 6, "sph/astro courant 0.3 steps individual limiter off", 2000.0);
    commands(lmp, {"thermo 20", "run 200"});
    EXPECT_TRUE(std::isnan(fix_value(lmp, "gas", 8)));
    EXPECT_TRUE(std::isnan(fix_value(lmp, "gas", 9)));
    const double error = global_vector(lmp, "sum", 12)[DEREL];
    std::printf("energy error (compute sph/astro/global, with the predictions) %g\n", error);
    EXPECT_LT(error, -0.05);
    commands(lmp, {"log none"});
  }
  std::ifstream in(log);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("fix sph/astro steps individual: no synchronisation point in this run after "
                      "the one that set the reference energy"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("fix sph/astro: limiter off with steps individual"), std::string::npos);
  std::remove(log.c_str());
  for (const auto &[keywords, warning] :
       {std::pair<std::string, std::string>{"limiter 2",
                                            "fix sph/astro: limiter 2 is ignored "
                                            "with steps global"},
        {"kicks particle", "fix sph/astro: kicks particle is ignored with steps global"},
        {"steps individual longdisplacement 0.05",
         "fix sph/astro: longdisplacement 0.05 is ignored without longrange sync"}}) {
    auto lmp = open_lammps();
    commands(lmp,
             {"log " + log, "units lj", "atom_style atomic", "lattice fcc 4.0",
              "region box block 0 2 0 2 0 2", "create_box 1 box", "pair_style " + std::string(PAIR),
              "fix gas all sph/astro " + keywords, "log none"});
    std::ifstream file(log);
    const std::string logged((std::istreambuf_iterator<char>(file)),
                             std::istreambuf_iterator<char>());
    EXPECT_NE(logged.find(warning), std::string::npos) << keywords << "\n" << logged;
    std::remove(log.c_str());
  }
}

// kicks pair integrates pair sph/astro's du/dt terms pair by pair, as its forces: a particle
// inside its step is heated (or cooled) by the pairs its active neighbours evaluate; with
// kicks particle its u changes only at its own kicks. Counted over the LAMMPS steps inside a
// particle's step: its step began before the previous LAMMPS step (whose start gave it its
// first half kick) and neither ends nor is shortened by the limiter in this one
TEST(IndividualSteps, PairKicksHeatSleepingParticles)
{
  for (const std::string kicks : {"particle", "pair"}) {
    auto lmp = open_lammps();
    hot_spot(lmp, 4, "sph/astro courant 0.3 steps individual tend 0.03 kicks " + kicks);
    commands(lmp, {"thermo 1000", "run 0"});
    auto now = [&] {
      auto *u = lmp->update;
      return u->atime + (u->ntimestep - u->atimestep) * u->dt;
    };
    int inside = 0, changed = 0;
    std::map<int, double> begin_older;
    auto u_before = per_atom(lmp, "u");
    auto begin_before = per_atom(lmp, "step_begin");
    auto end_before = per_atom(lmp, "step_end");
    for (int step = 0; step < 200 && now() < 0.03 - 1e-12; step++) {
      commands(lmp, {"run 1 post no"});
      const auto u_after = per_atom(lmp, "u");
      const auto begin_after = per_atom(lmp, "step_begin");
      const auto end_after = per_atom(lmp, "step_end");
      // the time line starts a new cycle at each multiple of dt_max: all begins go down, and a
      // step in the top bin then has the same begin and end as the one before
      bool wrapped = false;
      for (const auto &[id, b] : begin_after) wrapped = wrapped || b < begin_before.at(id);
      if (wrapped) begin_before.clear();
      for (const auto &[id, b] : begin_older) {
        if (wrapped || !begin_before.count(id)) break;
        if (begin_before.at(id) != b || begin_after.at(id) != b) continue;
        if (end_after.at(id) != end_before.at(id)) continue;
        inside++;
        if (u_after.at(id) != u_before.at(id)) changed++;
      }
      begin_older = begin_before;
      u_before = u_after;
      begin_before = begin_after;
      end_before = end_after;
    }
    std::printf("kicks %s: u changed inside %d of %d particle steps\n", kicks.c_str(), changed,
                inside);
    EXPECT_GT(inside, 100) << kicks;
    if (kicks == "particle")
      EXPECT_EQ(changed, 0);
    else
      EXPECT_GT(changed, inside / 10);
  }
}

// without the limiter a blast runs into sleeping gas: its energy goes wrong
TEST(IndividualSteps, WithoutTheLimiterABlastIntoSleepingGasGoesWrong)
{
  double error[2];
  for (int on = 0; on < 2; on++) {
    auto lmp = open_lammps();
    hot_spot(lmp, 5,
             std::string("sph/astro courant 0.3 steps individual tend 0.05 limiter ") +
                 (on ? "2" : "off"),
             2000.0);
    commands(lmp, {"run 100000"});
    error[on] = std::fabs(global_vector(lmp, "sum", 12)[DEREL]);
    if (!on) EXPECT_EQ(fix_value(lmp, "gas", 7), 0.0);
  }
  EXPECT_GT(error[0], 10.0 * error[1]) << error[0] << " " << error[1];
  EXPECT_LT(error[1], 2e-2);
}

// without a limiter keyword the limiter is 2 levels (factor 4) with pair kicks and 1 (factor 2)
// with particle kicks: the run is that of the explicit value bit for bit, and not that of the
// other value
TEST(IndividualSteps, TheDefaultLimiterDependsOnTheKicks)
{
  for (const std::string kicks : {"pair", "particle"}) {
    std::map<std::string, std::map<int, double>> x;
    for (const std::string limiter : {"", " limiter 1", " limiter 2"}) {
      auto lmp = open_lammps();
      hot_spot(lmp, 4, "sph/astro courant 0.3 steps individual tend 0.02 kicks " + kicks + limiter,
               2000.0);
      commands(lmp, {"run 100000"});
      EXPECT_GT(fix_value(lmp, "gas", 7), 0.0) << kicks << limiter;    // the limiter woke some
      x[limiter] = per_atom(lmp, "x", 0);
    }
    const std::string same = kicks == "pair" ? " limiter 2" : " limiter 1";
    const std::string other = kicks == "pair" ? " limiter 1" : " limiter 2";
    int differ = 0;
    for (const auto &[id, value] : x[""]) {
      EXPECT_EQ(value, x[same][id]) << kicks << " atom " << id;
      if (value != x[other][id]) differ++;
    }
    EXPECT_GT(differ, 0) << kicks;
  }
}

// a restart mid-hierarchy, and a run split in two, continue bit for bit (split in three with
// runs of pre no: to round-off)
// (kicks: particle or pair; kicks pair keeps the pair kicks it opened in d2_step_kick)
void restart_and_split_runs_continue_bit_for_bit(const std::string &kicks)
{
  const std::string restart = "test_individual_steps.restart";
  const std::string fix = "sph/astro courant 0.3 steps individual kicks " + kicks;
  std::map<int, double> x_ref, v_ref, u_ref, h_ref;
  double time_ref;
  {
    auto lmp = open_lammps();
    hot_spot(lmp, 4, fix);
    commands(lmp, {"run 41"});
    EXPECT_LT(fix_value(lmp, "gas", 4), lmp->atom->natoms);    // the restart: mid-hierarchy
    commands(lmp, {"write_restart " + restart, "run 40"});
    x_ref = per_atom(lmp, "x", 0);
    v_ref = per_atom(lmp, "v", 1);
    u_ref = per_atom(lmp, "u");
    h_ref = per_atom(lmp, "h");
    time_ref = lmp->update->atime;
    EXPECT_GE(fix_value(lmp, "gas", 5), 2.0);
    EXPECT_LT(fix_value(lmp, "gas", 4), lmp->atom->natoms);
  }
  // tol 0: bit for bit; else to that relative round-off
  auto compare = [&](const std::unique_ptr<LAMMPS_NS::LAMMPS> &lmp, double tol = 0.0) {
    auto x = per_atom(lmp, "x", 0);
    auto v = per_atom(lmp, "v", 1);
    auto u = per_atom(lmp, "u");
    auto h = per_atom(lmp, "h");
    ASSERT_EQ(x.size(), x_ref.size());
    double worst = 0.0;
    for (const auto &[id, value] : x_ref) {
      EXPECT_NEAR(x[id], value, 1e-14) << "atom " << id;    // (wrapping round-off)
      for (const auto &[got, ref] :
           {std::pair<double, double>{v[id], v_ref[id]}, {u[id], u_ref[id]}, {h[id], h_ref[id]}}) {
        if (tol == 0.0)
          EXPECT_EQ(got, ref) << "atom " << id;
        else
          worst = std::max(worst, std::fabs(got - ref) / std::max(std::fabs(ref), 1e-3));
      }
    }
    if (tol > 0.0) {
      std::printf("largest relative difference %g\n", worst);
      EXPECT_LT(worst, tol);
    }
    EXPECT_EQ(lmp->update->atime, time_ref);
  };
  {
    auto lmp = open_lammps();
    commands(lmp,
             {"read_restart " + restart, "fix gas all " + fix,
              "fix hvar all sph/astro/h iterate hfact 1.2",
              "neighbor " + num(0.3 * 1.2 * std::cbrt(0.25)) + " bin",
              "neigh_modify every 1 delay 0 check yes", "run 40"});
    compare(lmp);
  }
  {
    auto lmp = open_lammps();
    hot_spot(lmp, 4, fix);
    commands(lmp, {"run 41", "run 40"});
    compare(lmp);
  }
  {    // runs without init and setup (pre no) continue the hierarchy too, to round-off (a
    // hierarchy started anew would differ by 1e-4)
    auto lmp = open_lammps();
    hot_spot(lmp, 4, fix);
    commands(lmp, {"run 41", "run 15 pre no post no", "run 25 pre no post no"});
    compare(lmp, 1e-10);
  }
  {    // a run whose setup sorts the atoms (a new order between the runs): the opening kicks
    // of the last step of the first run go to their own atoms (to round-off: new sum orders)
    auto lmp = open_lammps();
    hot_spot(lmp, 4, fix);
    commands(lmp, {"run 41", "atom_modify sort 1 0.0", "run 40"});
    compare(lmp, 1e-10);
  }
  std::remove(restart.c_str());
}

TEST(IndividualSteps, RestartAndSplitRunsContinueBitForBit)
{
  restart_and_split_runs_continue_bit_for_bit("particle");
}

TEST(IndividualSteps, RestartAndSplitRunsContinueBitForBitWithPairKicks)
{
  restart_and_split_runs_continue_bit_for_bit("pair");
}

// newton on makes rows only for the leaves of active particles and takes each step's pairs
// from them; newton off makes the whole lists and selects the due pairs from the half list
// (sph_astro_neighbour_lists.h). Both evaluate the same pairs: the runs agree to round-off.
// a restart file whose particles' step state lies in a fix property/atom of that ID (the layout
// of other versions: its style is not fix sph/astro/owned, so LAMMPS does not restore it) cannot
// continue its hierarchy
TEST(IndividualSteps, ARestartWithoutTheStepStateIsRefused)
{
  const std::string restart = "test_individual_steps_old_state.restart";
  const std::string fix = "sph/astro courant 0.3 steps individual";
  {
    auto lmp = open_lammps();
    hot_spot(lmp, 4, "sph/astro courant 0.3");
    commands(lmp,
             {"fix SPH_ASTRO_STEPS all property/atom d_step_begin d_step_end d_step_bin "
              "d_step_woken d_step_end_then d2_step_accel 3 d2_step_accel_other 3 "
              "d2_step_kick 3 d2_step_pair_lead 3 d_step_dudt d_step_divv d_step_omega "
              "d_step_balsara d_step_nneigh d_step_kick_u d_step_lead_u d_step_dudt_other "
              "d_step_pending_next d_step_dphidh d2_step_pending 20 d2_step_recent 6",
              "fix gas all " + fix, "run 41", "write_restart " + restart});
  }
  auto lmp = open_lammps();
  commands(lmp, {"read_restart " + restart});
  EXPECT_NE(error_of(lmp, "fix gas all " + fix)
                .find("holds the hierarchy of individual steps but not the particles' step state "
                      "of fix SPH_ASTRO_STEPS (style sph/astro/owned)"),
            std::string::npos);
  std::remove(restart.c_str());
}

TEST(IndividualSteps, NewtonOffGivesTheRunOfNewtonOn)
{
  for (const std::string kicks : {"particle", "pair"}) {
    std::map<int, double> x_on, v_on, u_on;
    for (const std::string newton : {"on", "off"}) {
      auto lmp = open_lammps();
      commands(lmp, {"newton " + newton});
      hot_spot(lmp, 4, "sph/astro courant 0.3 steps individual kicks " + kicks);
      commands(lmp, {"run 81"});    // (mid-hierarchy, as in the restart test)
      EXPECT_GE(fix_value(lmp, "gas", 5), 2.0) << kicks;
      EXPECT_LT(fix_value(lmp, "gas", 4), lmp->atom->natoms) << kicks;
      auto x = per_atom(lmp, "x", 0);
      auto v = per_atom(lmp, "v", 1);
      auto u = per_atom(lmp, "u");
      if (newton == "on") {
        x_on = x;
        v_on = v;
        u_on = u;
        continue;
      }
      ASSERT_EQ(x.size(), x_on.size());
      for (const auto &[id, value] : x_on) {
        EXPECT_NEAR(x[id], value, 1e-10) << kicks << ", atom " << id;
        EXPECT_NEAR(v[id], v_on[id], 1e-10 * (1.0 + std::fabs(v_on[id]))) << kicks << ", " << id;
        EXPECT_NEAR(u[id], u_on[id], 1e-10 * u_on[id]) << kicks << ", atom " << id;
      }
    }
  }
}

// a viscosity switch integrates each particle's alpha over its own step: the hot spot's shock
// raises alpha as far as with global steps
TEST(IndividualSteps, ViscositySwitchFollowsEachParticlesStep)
{
  double largest[2], mean[2];
  for (int individual = 0; individual < 2; individual++) {
    auto lmp = open_lammps();
    hot_spot(lmp, 5,
             std::string("sph/astro courant 0.3 tend 0.1 steps ") +
                 (individual ? "individual" : "global"));
    commands(lmp,
             {"fix av all sph/astro/switch morris-monaghan 0.1 1.0 0.5",
              "set group all d_alpha 0.1", "run 100000"});
    auto *av = lmp->modify->get_fix_by_id("av");
    largest[individual] = av->compute_vector(1);
    mean[individual] = av->compute_vector(0);
    EXPECT_LT(std::fabs(global_vector(lmp, "sum", 12)[DEREL]), 2e-2);
  }
  printf("largest alpha %.4f (global %.4f), mean %.4f (global %.4f)\n", largest[1], largest[0],
         mean[1], mean[0]);
  EXPECT_GT(largest[0], 0.15);    // alpha rose from 0.1 in the shock
  EXPECT_NEAR(largest[1], largest[0], 0.15 * largest[0]);
  EXPECT_NEAR(mean[1], mean[0], 0.15 * mean[0]);
}

TEST_F(BadInputTest, IndividualStepsArguments)
{
  commands(lmp, {"pair_style " + std::string(PAIR), "pair_coeff * *"});
  expect_error("fix gas all sph/astro steps some",
               "steps 'some' is not one of: global, individual");
  expect_error("fix gas all sph/astro limiter 0", "limiter 0 must be off or a number of bins");
  expect_error("fix gas all sph/astro steps individual kicks both", "kicks 'both' is not one of");
  expect_error("fix gas all sph/astro steps individual dt fixed", "needs dt adaptive");
  expect_error("fix gas all sph/astro steps individual xsph 0.5", "xsph is not available");
  expect_error("fix gas all sph/astro steps individual longrange some",
               "longrange 'some' is not one of: every, sync");
  expect_error("fix gas all sph/astro longrange sync", "longrange sync needs steps individual");
  expect_error("fix gas all sph/astro steps individual longdisplacement 0",
               "longdisplacement = 0 must be in (0, 1]");
}

TEST(IndividualSteps, OptionsItDoesNotCarryAreRefused)
{
  {
    auto lmp = open_lammps();
    gas(lmp, "box", 2, std::string(PAIR) + " density continuity", "sph/astro steps individual");
    EXPECT_NE(error_of(lmp, "run 0").find("density continuity is not available with individual"),
              std::string::npos);
  }
  {
    auto lmp = open_lammps();
    gas(lmp, "box", 2, PAIR, "sph/astro steps individual thermal entropy");
    EXPECT_NE(error_of(lmp, "run 0").find("thermal entropy is not available"), std::string::npos);
  }
  auto lmp = open_lammps();
  gas(lmp, "box", 2, PAIR, "sph/astro");
  commands(lmp, {"compute bins all sph/astro/atom bin"});
  EXPECT_NE(error_of(lmp, "run 0").find("there are no time bins"), std::string::npos);
}

// the bins of a run with individual steps stay in fix SPH_ASTRO_STEPS when fix sph/astro is
// defined again (or unfixed and defined again) with global steps; they are no longer the
// particles' steps: compute sph/astro/atom bin is refused as without individual steps
TEST(IndividualSteps, BinsAfterSwitchingToGlobalStepsAreRefused)
{
  for (const bool unfix : {false, true}) {
    auto lmp = open_lammps();
    hot_spot(lmp, 3, "sph/astro courant 0.3 steps individual");
    commands(lmp, {"compute bins all sph/astro/atom bin", "run 5"});
    if (unfix)
      commands(lmp, {"unfix hvar", "unfix gas", "fix gas all sph/astro courant 0.3"});
    else
      commands(lmp, {"fix gas all sph/astro courant 0.3"});
    const std::string message = error_of(lmp, "run 0");
    EXPECT_NE(message.find("compute sph/astro/atom bin: there are no time bins; they belong to "
                           "fix sph/astro steps individual"),
              std::string::npos)
        << message;
  }
}
