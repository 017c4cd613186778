/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// LAMMPS-driven tests of runs that continue other runs, over the option families of the
// package: from a restart file written during a run by the restart command and between runs
// by write_restart (bit for bit, the simulation time included), from a data file (to a bound:
// a data file holds no global state of a fix), and in a second run command (to round-off: its
// setup re-neighbours where one long run does not).

#include "styles_fixture.h"

#include "fix.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>

using namespace sph_astro_test;

namespace {

using Lammps = std::unique_ptr<LAMMPS_NS::LAMMPS>;

const double H0 = 1.2 * std::cbrt(0.25);    // h of the fcc lattice of gas() (rho = 1)

// an option family: the system with its styles and state, and the commands that define the
// styles again after read_restart (pair_style and pair_coeff come back with the file, but not
// those of pair_style hybrid, nor kspace_style, the fixes and computes)
struct Family {
  const char *name;
  std::function<void(const Lammps &)> build;
  std::vector<std::string> again;
  // the data file's sections (read_data ... fix ID NULL SECTION) and the fixes that read them,
  // defined before read_data (after sph/astro/state)
  std::vector<std::string> data_fixes;
  std::string data_sections;
  // with a data file: the boundary (before read_data) and the pair and kspace styles (after),
  // and the bound of the largest relative difference from the uninterrupted run at tend
  std::string boundary;
  std::vector<std::string> pair;
  double data_bound;
};

// (gtest names a family by its name)
void PrintTo(const Family &family, std::ostream *os)
{
  *os << family.name;
}

std::string neighbour_lines()
{
  return "neighbor " + num(0.3 * H0) + " bin";
}

// a hot spot in a periodic box of 4 n^3 particles (u = hot inside a sphere of radius 1)
void hot_spot(const Lammps &lmp, int n, const std::string &pair, const std::string &fix,
              double hot = 200.0)
{
  gas(lmp, "box", n, pair, fix, 0.01, 0.02);
  const std::string c = num(0.5 * n);
  commands(lmp,
           {"velocity all set 0 0 0", "region hot sphere " + c + " " + c + " " + c + " 1.0",
            "set region hot d_u " + num(hot)});
}

// a self-gravitating ball with a hot core: msm (shrink-wrapped box) or pppm (periodic box)
void hot_ball(const Lammps &lmp, const std::string &fix, const std::string &solver)
{
  const bool msm = solver == "msm";
  commands(lmp,
           {"units lj",
            "atom_style atomic",
            "atom_modify map array sort 0 0.0",
            std::string("boundary ") + (msm ? "s s s" : "p p p"),
            "lattice fcc 4.0",
            "region box block -4 4 -4 4 -4 4",
            "create_box 1 box",
            "region ball sphere 0 0 0 2.5 units box",
            "create_atoms 1 region ball",
            "displace_atoms all random 0.05 0.05 0.05 4711 units box",
            "mass 1 0.25",
            "pair_style hybrid/overlay sph/astro kernel m4 eos ideal 1.6666667 viscosity "
            "classic 1.0 2.0 sph/astro/gravity " +
                std::string(msm ? "1.5" : "3.0"),
            "pair_coeff * * sph/astro",
            "pair_coeff * * sph/astro/gravity",
            "kspace_style " + solver + "/sph/astro/gravity 1e-5",
            "fix gas all sph/astro " + fix,
            "fix hvar all sph/astro/h iterate hfact 1.2 tol 1e-10 margin 2.5",
            "set group all d_h " + num(H0),
            "set group all d_u 0.05",
            "region core sphere 0 0 0 1.0 units box",
            "set region core d_u 3.0",
            neighbour_lines(),
            "neigh_modify every 1 delay 0 check yes",
            "compute sum all sph/astro/global",
            "thermo_style custom step c_sum[11]"});
}

// pair_style hybrid/overlay of pair sph/astro and sph/astro/gravity, with the kspace style
std::vector<std::string> gravity_pair(const std::string &solver)
{
  return {"pair_style hybrid/overlay sph/astro kernel m4 eos ideal 1.6666667 viscosity classic "
          "1.0 2.0 sph/astro/gravity " +
              std::string(solver == "msm" ? "1.5" : "3.0"),
          "pair_coeff * * sph/astro", "pair_coeff * * sph/astro/gravity",
          "kspace_style " + solver + "/sph/astro/gravity 1e-5"};
}

const std::string INDIVIDUAL = "sph/astro courant 0.3 steps individual tend 0.1";
const std::string SYNC = "courant 0.3 steps individual tend 0.3 longrange sync";
// (dtmax below every particle's criteria: LAMMPS' time is not advanced between the steps)
const std::string GLOBAL = "sph/astro courant 0.3 dtmax 0.004 tend 0.1";

std::vector<Family> families()
{
  const std::string gas_again = neighbour_lines();
  return {
      {"individual_iterate",
       [](const Lammps &lmp) {
         hot_spot(lmp, 4, PAIR, INDIVIDUAL);
         commands(lmp, {"fix hvar all sph/astro/h iterate hfact 1.2"});
       },
       {"fix gas all " + INDIVIDUAL, "fix hvar all sph/astro/h iterate hfact 1.2", gas_again},
       {},
       "",
       "p p p",
       {"pair_style " + std::string(PAIR), "pair_coeff * *"},
       1e-2},
      {"individual_particle_kicks_fixed_h",
       [](const Lammps &lmp) {
         hot_spot(lmp, 4, PAIR, INDIVIDUAL + " kicks particle");
       },
       {"fix gas all " + INDIVIDUAL + " kicks particle", gas_again},
       {},
       "",
       "p p p",
       {"pair_style " + std::string(PAIR), "pair_coeff * *"},
       5e-3},
      {"individual_switch_mm",
       [](const Lammps &lmp) {
         hot_spot(lmp, 4, PAIR, INDIVIDUAL);
         commands(lmp,
                  {"fix hvar all sph/astro/h iterate hfact 1.2",
                   "fix av all sph/astro/switch morris-monaghan 0.1 1.0 0.1"});
       },
       {"fix gas all " + INDIVIDUAL, "fix hvar all sph/astro/h iterate hfact 1.2",
        "fix av all sph/astro/switch morris-monaghan 0.1 1.0 0.1", gas_again},
       {"fix SPH_ASTRO_ALPHA all property/atom d_alpha ghost yes"},
       " fix SPH_ASTRO_ALPHA NULL SPH_ASTRO_ALPHA",
       "p p p",
       {"pair_style " + std::string(PAIR), "pair_coeff * *"},
       1e-2},
      {"global_dhdt_entropy_switch_cd",
       [](const Lammps &lmp) {
         hot_spot(lmp, 3, PAIR, GLOBAL + " thermal entropy");
         commands(lmp,
                  {"fix hvar all sph/astro/h dhdt",
                   "fix av all sph/astro/switch cullen-dehnen 0.1 1.0 0.1"});
       },
       {"fix gas all " + GLOBAL + " thermal entropy", "fix hvar all sph/astro/h dhdt",
        "fix av all sph/astro/switch cullen-dehnen 0.1 1.0 0.1", gas_again},
       {"fix SPH_ASTRO_ALPHA all property/atom d_alpha ghost yes",
        "fix SPH_ASTRO_ENTROPY all property/atom d_entropy d_entropy_est d_dentropy",
        "fix SPH_ASTRO_DIVV_PREV all property/atom d_divv_prev"},
       " fix SPH_ASTRO_ALPHA NULL SPH_ASTRO_ALPHA fix SPH_ASTRO_ENTROPY NULL SPH_ASTRO_ENTROPY"
       " fix SPH_ASTRO_DIVV_PREV NULL SPH_ASTRO_DIVV_PREV",
       "p p p",
       {"pair_style " + std::string(PAIR), "pair_coeff * *"},
       1e-4},
      {"global_continuity_conduction",
       [](const Lammps &lmp) {
         hot_spot(lmp, 3, std::string(PAIR) + " density continuity conduction 0.01", GLOBAL);
       },
       {"fix gas all " + GLOBAL, gas_again},
       {"fix SPH_ASTRO_CONTINUITY all property/atom d_rhoest d_drhodt ghost yes"},
       " fix SPH_ASTRO_CONTINUITY NULL SPH_ASTRO_CONTINUITY",
       "p p p",
       {"pair_style " + std::string(PAIR) + " density continuity conduction 0.01",
        "pair_coeff * *"},
       3e-4},
      {"individual_sync_pppm",
       [](const Lammps &lmp) {
         hot_ball(lmp, SYNC, "pppm");
       },
       {"pair_coeff * * sph/astro", "pair_coeff * * sph/astro/gravity",
        "kspace_style pppm/sph/astro/gravity 1e-5", "fix gas all sph/astro " + SYNC,
        "fix hvar all sph/astro/h iterate hfact 1.2 tol 1e-10 margin 2.5", gas_again},
       {"fix SPH_ASTRO_GRAVITY_Q all property/atom q ghost yes"},
       " fix SPH_ASTRO_GRAVITY_Q NULL Charges",
       "p p p",
       gravity_pair("pppm"),
       5e-4},
      {"individual_sync_msm",
       [](const Lammps &lmp) {
         hot_ball(lmp, SYNC, "msm");
       },
       {"pair_coeff * * sph/astro", "pair_coeff * * sph/astro/gravity",
        "kspace_style msm/sph/astro/gravity 1e-5", "fix gas all sph/astro " + SYNC,
        "fix hvar all sph/astro/h iterate hfact 1.2 tol 1e-10 margin 2.5", gas_again},
       {"fix SPH_ASTRO_GRAVITY_Q all property/atom q ghost yes"},
       " fix SPH_ASTRO_GRAVITY_Q NULL Charges",
       "s s s",
       gravity_pair("msm"),
       5e-4},
  };
}

double now(const Lammps &lmp)
{
  const auto *u = lmp->update;
  return u->atime + (u->ntimestep - u->atimestep) * u->dt;
}

// the state a continued run is compared by: x (unwrapped), v, u of every atom, the step and
// the time
struct Snapshot {
  std::map<int, double> x[3], v[3], u;
  LAMMPS_NS::bigint step = 0;
  double time = 0.0;
};

Snapshot snapshot(const Lammps &lmp)
{
  Snapshot s;
  for (int d = 0; d < 3; d++) {
    s.x[d] = per_atom(lmp, "x", d);
    s.v[d] = per_atom(lmp, "v", d);
  }
  s.u = per_atom(lmp, "u");
  s.step = lmp->update->ntimestep;
  s.time = now(lmp);
  return s;
}

// the largest difference of x, v and u, each relative to the largest |value| of its kind in the
// reference (0: bit for bit)
double difference(const Snapshot &a, const Snapshot &ref)
{
  double worst = 0.0;
  auto compare = [&](const std::map<int, double> &got, const std::map<int, double> &want) {
    double scale = 0.0, diff = 0.0;
    for (const auto &[id, value] : want) {
      scale = std::max(scale, std::fabs(value));
      const auto found = got.find(id);
      diff = std::max(diff, found == got.end() ? INFINITY : std::fabs(found->second - value));
    }
    worst = std::max(worst, scale > 0.0 ? diff / scale : diff);
  };
  for (int d = 0; d < 3; d++) {
    compare(a.x[d], ref.x[d]);
    compare(a.v[d], ref.v[d]);
  }
  compare(a.u, ref.u);
  return worst;
}

const int RESTART_STEP = 10;

class Continuation : public ::testing::TestWithParam<Family> {
 protected:
  std::string file(const std::string &what) const
  {
    return std::string("test_continuation_") + GetParam().name + what;
  }
  // a new instance with the family's system read from a restart file
  Lammps from_restart(const std::string &restart) const
  {
    auto lmp = open_lammps();
    commands(lmp, {"read_restart " + restart});
    commands(lmp, GetParam().again);
    commands(lmp,
             {"neigh_modify every 1 delay 0 check yes", "compute sum all sph/astro/global",
              "thermo_style custom step c_sum[11]"});
    return lmp;
  }
};

}    // namespace

// a restart file written by the restart command during a run continues it bit for bit, the
// simulation time included: LAMMPS' Integrate::init() sets update->atimestep to the current
// step without advancing update->atime, and the file holds the time of the last change of the
// timestep (a time line of individual steps, or a step held at dtmax, keeps the timestep for
// several steps); without fix sph/astro putting it back the continued run went on for
// (step - atimestep) dt too long before it reached tend
TEST_P(Continuation, RestartCommandDuringARun)
{
  const Family &family = GetParam();
  Snapshot ref;
  {
    auto lmp = open_lammps();
    family.build(lmp);
    commands(lmp,
             {"variable restartstep equal " + std::to_string(RESTART_STEP) +
                  "+(step>=" + std::to_string(RESTART_STEP) + ")*1000000000",
              "restart v_restartstep " + file(".restart.*"), "run 100000"});
    ref = snapshot(lmp);
  }
  ASSERT_GT(ref.step, RESTART_STEP + 2) << family.name;
  auto lmp = from_restart(file(".restart.") + std::to_string(RESTART_STEP));
  const double time_read = now(lmp);
  commands(lmp, {"run 100000"});
  const Snapshot got = snapshot(lmp);
  EXPECT_EQ(got.step, ref.step) << family.name << " (the file's time " << time_read << ")";
  EXPECT_EQ(got.time, ref.time) << family.name;
  EXPECT_EQ(difference(got, ref), 0.0) << family.name;
  std::remove((file(".restart.") + std::to_string(RESTART_STEP)).c_str());
}

// a restart file written by write_restart between two runs continues the second run bit for bit,
// the time included
TEST_P(Continuation, WriteRestartBetweenRuns)
{
  const Family &family = GetParam();
  Snapshot ref;
  {
    auto lmp = open_lammps();
    family.build(lmp);
    commands(
        lmp,
        {"run " + std::to_string(RESTART_STEP), "write_restart " + file(".restart"), "run 100000"});
    ref = snapshot(lmp);
  }
  auto lmp = from_restart(file(".restart"));
  commands(lmp, {"run 100000"});
  const Snapshot got = snapshot(lmp);
  EXPECT_EQ(got.step, ref.step) << family.name;
  EXPECT_EQ(got.time, ref.time) << family.name;
  EXPECT_EQ(difference(got, ref), 0.0) << family.name;
  std::remove(file(".restart").c_str());
}

// a data file written between two runs and read back as documented (sph/astro/state and the
// fixes of its sections before read_data, the step and time set again with reset_timestep: a data
// file holds neither) continues the second run to a bound. A data file holds the per-atom state
// to the last bit but no global state of a fix: the predictions of v and u start from v and u,
// a hierarchy of individual steps and the reference energies start anew
TEST_P(Continuation, DataFileBetweenRuns)
{
  const Family &family = GetParam();
  Snapshot ref;
  double time_written;
  {
    auto lmp = open_lammps();
    family.build(lmp);
    commands(lmp, {"run " + std::to_string(RESTART_STEP)});
    time_written = now(lmp);
    commands(lmp, {"write_data " + file(".data"), "run 100000"});
    ref = snapshot(lmp);
  }
  auto lmp = open_lammps();
  commands(lmp,
           {"units lj", "atom_style atomic", "atom_modify map array sort 0 0.0",
            "boundary " + family.boundary, "sph/astro/state"});
  commands(lmp, family.data_fixes);
  commands(lmp,
           {"read_data " + file(".data") + " fix SPH_ASTRO_STATE NULL SPH_ASTRO_STATE" +
            family.data_sections});
  commands(lmp, family.pair);
  commands(lmp, family.again);
  commands(lmp,
           {"reset_timestep " + std::to_string(RESTART_STEP) + " time " + num(time_written),
            "neigh_modify every 1 delay 0 check yes", "compute sum all sph/astro/global",
            "thermo_style custom step c_sum[11]", "run 100000"});
  const Snapshot got = snapshot(lmp);
  const double diff = difference(got, ref);
  std::printf("%s: %lld steps against %lld, time %.17g against %.17g, largest relative "
              "difference %.3g\n",
              family.name, static_cast<long long>(got.step), static_cast<long long>(ref.step),
              got.time, ref.time, diff);
  // (both at tend; a hierarchy started anew puts tend on its grid by another sum)
  EXPECT_NEAR(got.time, ref.time, 1e-14) << family.name;
  EXPECT_LT(diff, family.data_bound) << family.name;
  std::remove(file(".data").c_str());
}

// a second run command agrees with one long run to round-off, not bit for bit: the setup of a
// run re-neighbours where the long run did not (it wraps positions into a periodic box and
// makes the ghosts and the package's lists anew, in another order of summation). The time
// continues to the last bit (LAMMPS' end of a run adds up the time anew: fix sph/astro puts back
// the pair it came from)
TEST_P(Continuation, SecondRunCommand)
{
  const Family &family = GetParam();
  Snapshot ref;
  {
    auto lmp = open_lammps();
    family.build(lmp);
    commands(lmp, {"run 100000"});
    ref = snapshot(lmp);
  }
  auto lmp = open_lammps();
  family.build(lmp);
  commands(lmp, {"run " + std::to_string(RESTART_STEP), "run 100000"});
  const Snapshot got = snapshot(lmp);
  const double diff = difference(got, ref);
  std::printf("%s: %lld steps against %lld, largest relative difference %.3g\n", family.name,
              static_cast<long long>(got.step), static_cast<long long>(ref.step), diff);
  EXPECT_EQ(got.step, ref.step) << family.name;
  EXPECT_EQ(got.time, ref.time) << family.name;
  // (MSM: the setup also wraps the shrink-wrapped box anew, and the grid, which is set on the
  // box, moves with it)
  EXPECT_LT(diff, std::string(family.name).find("msm") != std::string::npos ? 1e-6 : 1e-12)
      << family.name;
}

INSTANTIATE_TEST_SUITE_P(Families, Continuation, ::testing::ValuesIn(families()),
                         [](const auto &info) {
                           return std::string(info.param.name);
                         });

// fix sph/astro defined again (or unfixed and defined again) after a run with individual steps
// that ended inside particles' steps: their v and u are those of the middle of their steps, and
// the fix that goes hands over their state at the current time (the predictions, as compute
// sph/astro/global reads them), so the run that follows starts from the energy the compute
// read, and the compute keeps its reference energy E0 (a new fix took v of the middle of the
// steps for the current ones: kinetic energy 0.1 % lower here, and the energy error read 0)
TEST(Redefinition, AfterIndividualStepsKeepsTheStateAndTheReference)
{
  for (const std::string how : {"again", "unfix", "global"}) {
    auto lmp = open_lammps();
    hot_spot(lmp, 4, PAIR, "sph/astro courant 0.3 steps individual", 2000.0);
    commands(lmp, {"fix hvar all sph/astro/h iterate hfact 1.2", "run 41"});
    ASSERT_LT(lmp->modify->get_fix_by_id("gas")->compute_vector(4), lmp->atom->natoms);
    const auto before = global_vector(lmp, "sum", 12);
    ASSERT_GT(std::fabs(before[DEREL]), 1e-6);
    if (how == "unfix") commands(lmp, {"unfix hvar", "unfix gas"});
    commands(lmp,
             {std::string("fix gas all sph/astro courant 0.3") +
              (how == "global" ? "" : " steps individual")});
    if (how == "unfix") commands(lmp, {"fix hvar all sph/astro/h iterate hfact 1.2"});
    commands(lmp, {"run 0"});
    const auto after = global_vector(lmp, "sum", 12);
    std::printf("%s: kinetic energy %.10g against %.10g, energy error %.6g against %.6g\n",
                how.c_str(), after[EKIN], before[EKIN], after[DEREL], before[DEREL]);
    EXPECT_NEAR(after[EKIN], before[EKIN], 1e-12 * before[EKIN]) << how;
    EXPECT_NEAR(after[ETHERM], before[ETHERM], 1e-12 * before[ETHERM]) << how;
    EXPECT_NEAR(after[DEREL], before[DEREL], 1e-12) << how;
  }
  // v set after the run is the user's: the fix that goes hands over nothing
  auto lmp = open_lammps();
  hot_spot(lmp, 4, PAIR, "sph/astro courant 0.3 steps individual", 2000.0);
  commands(lmp,
           {"fix hvar all sph/astro/h iterate hfact 1.2", "run 41", "velocity all set 0.25 0 0",
            "fix gas all sph/astro courant 0.3"});
  for (const auto &[id, vx] : per_atom(lmp, "v", 0)) EXPECT_EQ(vx, 0.25) << "atom " << id;
}

// v or u changed between two runs (velocity, set): the reference energy E0 of compute
// sph/astro/global's relative energy error is reset at the next evaluation, which the log
// says; the error then measures the integration from the new state (the change was read as
// an energy error: 11 % here). With the state unchanged E0 is kept, also with fix sph/astro
// defined again and after a restart
TEST(Redefinition, StateChangedBetweenRunsResetsTheReference)
{
  const std::string log = "test_continuation_reference.log";
  for (const std::string steps : {"global", "individual"}) {
    auto lmp = open_lammps();
    hot_spot(lmp, 3, PAIR, "sph/astro courant 0.3 steps " + steps, 20.0);
    commands(lmp, {"log " + log, "run 20"});
    const auto before = global_vector(lmp, "sum", 12);
    commands(lmp, {"run 0"});
    EXPECT_EQ(global_vector(lmp, "sum", 12)[DEREL], before[DEREL]) << steps;
    commands(lmp, {"velocity all set 0.5 0 0 sum yes", "run 0"});
    const auto after = global_vector(lmp, "sum", 12);
    std::printf("%s steps: energy error %g before the velocity command, %g after\n", steps.c_str(),
                before[DEREL], after[DEREL]);
    EXPECT_GT(after[EKIN], 1.05 * before[EKIN]) << steps;
    EXPECT_EQ(after[DEREL], 0.0) << steps;
    // fix sph/astro defined anew (it knows no state of a last run): the compute's record of the
    // state it read at the end of the run
    commands(lmp,
             {"run 5", "unfix gas", "fix gas all sph/astro courant 0.3 steps " + steps, "run 0"});
    const double kept = global_vector(lmp, "sum", 12)[DEREL];
    EXPECT_NE(kept, 0.0) << steps;
    commands(lmp,
             {"unfix gas", "fix gas all sph/astro courant 0.3 steps " + steps,
              "velocity all set 0 0.5 0 sum yes", "run 0"});
    EXPECT_EQ(global_vector(lmp, "sum", 12)[DEREL], 0.0) << steps;
    // a restart file: E0 comes back with it, and is reset after a change of v, made after the
    // file was read or before it was written
    const std::string restart = "test_continuation_reference.restart";
    const std::string changed = "test_continuation_reference_changed.restart";
    commands(lmp, {"run 5", "write_restart " + restart, "log none"});
    const double written = global_vector(lmp, "sum", 12)[DEREL];
    commands(lmp, {"velocity all set 0.5 0.5 0 sum yes", "write_restart " + changed});
    {
      std::ifstream in(log);
      const std::string text((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
      EXPECT_NE(text.find("compute sph/astro/global sum: the reference energy E0 is reset"),
                std::string::npos)
          << text;
    }
    std::remove(log.c_str());
    lmp.reset();    // (one instance at a time: the plugin is loaded for the process)
    for (const int velocity : {0, 1, 2}) {    // none, after reading, before writing
      auto again = open_lammps();
      commands(again,
               {"read_restart " + (velocity == 2 ? changed : restart),
                "fix gas all sph/astro courant 0.3 steps " + steps, neighbour_lines(),
                "compute sum all sph/astro/global", "thermo_style custom step c_sum[11]"});
      if (velocity == 1) commands(again, {"velocity all set 0 0 0.5 sum yes"});
      commands(again, {"run 0"});
      const double read = global_vector(again, "sum", 12)[DEREL];
      if (velocity)
        EXPECT_EQ(read, 0.0) << steps << ", velocity " << velocity;
      else
        EXPECT_NEAR(read, written, 1e-12) << steps;
    }
    std::remove(restart.c_str());
    std::remove(changed.c_str());
  }
}
