/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// LAMMPS-driven tests of what a user who gets a setting wrong is told: a timestep fixed above
// the stability limit, minimize, an empty system, the order of pair_style and set, a restart
// continued with another gamma, the accuracy and dimension of the gravity kspace styles, a
// particle that alone sets the timestep, a kernel support longer than the box; and runs that
// must not depend on LAMMPS' neighbor style.

#include "styles_fixture.h"

#include "atom.h"
#include "compute.h"
#include "modify.h"
#include "neighbor.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>

using namespace sph_astro_test;
using LAMMPS_NS::LAMMPS;

namespace {

// a small fcc box with the SPH styles and a state
class Setting : public BadInputTest {
 protected:
  void sph(const std::string &fix = "sph/astro")
  {
    commands(lmp,
             {"pair_style " + std::string(PAIR), "pair_coeff * *", "fix gas all " + fix,
              "set group all d_h 0.9", "set group all d_u 1.0"});
  }
};

}    // namespace

// dt fixed far above the Courant limit: the sentinel names the factor, the limiting atom and
// the remedy at the first step (sentinel stop makes it an error), not only the negative u that
// follows
TEST_F(Setting, FixedTimestepAboveTheStableStepIsReported)
{
  sph("sph/astro dt fixed sentinel stop");
  commands(lmp, {"velocity all create 0.5 4711", "timestep 0.5"});
  const std::string message = error_of(lmp, "run 10");
  EXPECT_NE(message.find("dt fixed: the timestep 0.5 at step 0 is"), std::string::npos) << message;
  EXPECT_NE(message.find("times the longest stable step"), std::string::npos) << message;
  EXPECT_NE(message.find("limited by atom"), std::string::npos) << message;
  // a stable fixed step runs
  commands(lmp, {"timestep 0.001"});
  EXPECT_EQ(error_of(lmp, "run 10"), "");
}

TEST_F(Setting, MinimizeIsRefused)
{
  sph();
  expect_error("minimize 1e-4 1e-4 10 10", "fix sph/astro: minimize is not supported");
}

TEST_F(Setting, SystemWithoutParticles)
{
  sph();
  commands(lmp, {"delete_atoms group all"});
  expect_error("run 1", "pair_style sph/astro: the system holds no particles");
}

// the state exists from pair_style on, so set may come before the fix
TEST_F(Setting, StateCanBeSetAfterPairStyle)
{
  commands(lmp,
           {"pair_style " + std::string(PAIR), "pair_coeff * *", "set group all d_h 0.9",
            "set group all d_u 1.0", "fix gas all sph/astro"});
  EXPECT_EQ(error_of(lmp, "run 1"), "");
}

// thermal entropy continued with another gamma: A is derived anew from u, so the thermal energy
// continues through the next (tiny) step, where u = A rho^(gamma-1)/(gamma-1) of the old A
// would change it by tens of per cent; with the file's gamma A is kept
TEST(EntropyRestart, AnotherGammaKeepsTheThermalEnergy)
{
  const std::string restart = "test_reliability_entropy.restart";
  double etherm_ref;
  {
    auto lmp = open_lammps();
    gas(lmp, "box", 3, PAIR, "sph/astro courant 0.3 thermal entropy");
    commands(lmp, {"velocity all create 0.5 4928459", "run 10", "write_restart " + restart});
    etherm_ref = global_vector(lmp, "sum", 12)[ETHERM];
  }
  ASSERT_GT(etherm_ref, 0.0);
  for (const char *gamma : {"1.4", ""}) {
    auto lmp = open_lammps();
    commands(lmp, {"read_restart " + restart});
    if (*gamma) commands(lmp, {"pair_style sph/astro eos ideal " + std::string(gamma)});
    commands(lmp,
             {"pair_coeff * *", "fix gas all sph/astro dt fixed thermal entropy", "timestep 1e-6",
              "neighbor " + num(0.3 * 1.2 * std::cbrt(0.25)) + " bin",
              "compute sum all sph/astro/global", "thermo_style custom step c_sum[9]", "run 1"});
    const double etherm = global_vector(lmp, "sum", 12)[ETHERM];
    EXPECT_NEAR(etherm / etherm_ref, 1.0, 1e-5) << "gamma " << (*gamma ? gamma : "of the file");
  }
  std::remove(restart.c_str());
}

TEST_F(Setting, GravityAccuracyMustBePositive)
{
  commands(lmp,
           {"pair_style hybrid/overlay " + std::string(PAIR) + " sph/astro/gravity 2.5",
            "pair_coeff * * sph/astro", "pair_coeff * * sph/astro/gravity"});
  expect_error("kspace_style pppm/sph/astro/gravity -1e-4",
               "pppm/sph/astro/gravity: accuracy -1e-4 must be > 0");
  expect_error("kspace_style msm/sph/astro/gravity 0", "msm/sph/astro/gravity: accuracy 0 must");
}

TEST(GravityKSpace, MSMIn2dNamesTheAlternative)
{
  auto lmp = open_lammps();
  commands(lmp,
           {"units lj", "dimension 2", "atom_style atomic", "atom_modify map array",
            "lattice sq 1.0", "region box block 0 6 0 6 -0.5 0.5", "create_box 1 box",
            "create_atoms 1 box", "mass 1 1",
            "pair_style hybrid/overlay " + std::string(PAIR) + " sph/astro/gravity 2.5",
            "pair_coeff * * sph/astro", "pair_coeff * * sph/astro/gravity",
            "kspace_style msm/sph/astro/gravity 1e-4", "fix gas all sph/astro",
            "set group all d_h 1.2", "set group all d_u 1.0"});
  const std::string message = error_of(lmp, "run 0");
  EXPECT_NE(message.find("MSM works in 3d only; in 2d use pair_style sph/astro/gravity"),
            std::string::npos)
      << message;
}

// a restart of a variable-h run continued without fix sph/astro/h: the pair style warns that h
// stays fixed (in the log); with the fix defined again it does not
TEST(VariableHRestart, ContinuedWithoutTheHFixIsWarned)
{
  const std::string restart = "test_reliability_h.restart", log = "test_reliability_h.log";
  {
    auto lmp = open_lammps();
    gas(lmp, "box", 3, PAIR, "sph/astro courant 0.3");
    commands(lmp, {"fix hvar all sph/astro/h iterate", "run 5", "write_restart " + restart});
  }
  for (bool with_fix : {false, true}) {
    auto lmp = open_lammps();
    commands(lmp, {"log " + log, "read_restart " + restart, "fix gas all sph/astro courant 0.3"});
    if (with_fix) commands(lmp, {"fix hvar all sph/astro/h iterate"});
    commands(lmp, {"neighbor " + num(0.3 * 1.2 * std::cbrt(0.25)) + " bin", "run 1", "log none"});
    std::ifstream in(log);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text.find("comes from a run with fix sph/astro/h; this run has none") !=
                  std::string::npos,
              !with_fix)
        << (with_fix ? "with" : "without") << " fix sph/astro/h";
  }
  std::remove(restart.c_str());
  std::remove(log.c_str());
}

// fix deform remap v (dt fixed: fix deform strains the box per step): the ghosts across a
// periodic boundary carry the box's velocity, so an expansion v_x = 2 x has div v = 2 at every
// particle (-3.75 at the boundary with unshifted ghost velocities), and a uniform shear
// v_x = 0.125 y (xy erate 0.125: d(xy)/dt = 0.125 ly) has div v = 0 and the same viscous
// heating at the boundary as inside (26 times more there with unshifted ghost velocities)
TEST(DeformRemapV, GhostsCarryTheFlowAcrossTheBoundary)
{
  for (const bool shear : {false, true}) {
    auto lmp = open_lammps();
    commands(lmp,
             {"units lj", "atom_style atomic", "atom_modify map array", "lattice fcc 4.0",
              "region box prism 0 4 0 4 0 4 0 0 0", "create_box 1 box", "create_atoms 1 box",
              "mass 1 0.25", "pair_style " + std::string(PAIR), "pair_coeff * *",
              "fix gas all sph/astro dt fixed", "timestep 0.0001", "set group all d_h 0.9",
              "set group all d_u 1.0", "neighbor 0.3 bin"});
    if (shear)
      commands(lmp,
               {"variable vx atom 0.125*y", "velocity all set v_vx 0 0",
                "fix box all deform 1 xy erate 0.125 remap v"});
    else
      commands(lmp,
               {"variable vx atom 2.0*x", "velocity all set v_vx 0 0",
                "fix box all deform 1 x erate 2.0 remap v"});
    // (run 0 would see no rate: fix deform sets it from the run's length)
    commands(lmp, {"compute sph all sph/astro/atom divv dudt", "run 1"});
    auto *compute = lmp->modify->get_compute_by_id("sph");
    compute->compute_peratom();
    double divv_min = INFINITY, divv_max = -INFINITY, dudt_min = INFINITY, dudt_max = 0.0;
    for (int i = 0; i < lmp->atom->nlocal; i++) {
      divv_min = std::min(divv_min, compute->array_atom[i][0]);
      divv_max = std::max(divv_max, compute->array_atom[i][0]);
      dudt_min = std::min(dudt_min, compute->array_atom[i][1]);
      dudt_max = std::max(dudt_max, compute->array_atom[i][1]);
    }
    const char *what = shear ? "shear" : "expansion";
    // LAMMPS strains the box at the end of a step, so the images of the step's force evaluation
    // lag the particles by one step's strain (2e-4 here): a spread of that order remains
    const double SPREAD = 2e-3;
    // every particle alike (a lattice: its div v differs from 2 by the lattice's kernel sums)
    if (shear) {
      EXPECT_LT(std::max(std::fabs(divv_min), std::fabs(divv_max)), SPREAD) << what;
      EXPECT_GT(dudt_min, 0.0) << what;    // viscous heating, the same everywhere
      EXPECT_LT(dudt_max - dudt_min, SPREAD * dudt_max) << what;
    } else {
      EXPECT_NEAR(divv_min, 2.0, 1e-2) << what;
      EXPECT_LT(divv_max - divv_min, SPREAD * divv_max) << what;
    }
    printf("%s: div v %.8g .. %.8g, du/dt %.6g .. %.6g\n", what, divv_min, divv_max, dudt_min,
           dudt_max);
  }
}

// one particle far faster than the rest sets the timestep alone: the sentinel names it at the
// start of the run (sentinel stop: as an error); an ordinary speed passes
TEST_F(Setting, ParticleThatAloneSetsTheTimestepIsNamed)
{
  sph("sph/astro sentinel stop");
  commands(lmp, {"set atom 5 vx 1e30"});
  const std::string message = error_of(lmp, "run 1");
  EXPECT_NE(message.find("atom 5 moves at |v| = 1e+30"), std::string::npos) << message;
  EXPECT_NE(message.find("times the typical signal speed"), std::string::npos) << message;
  commands(lmp, {"set atom 5 vx 10"});
  EXPECT_EQ(error_of(lmp, "run 1"), "");
}

// a finite velocity whose square overflows (kinetic energy, signal speeds) stops the run at once
TEST_F(Setting, VelocityWhoseSquareOverflowsIsNamed)
{
  sph();
  commands(lmp, {"set atom 7 vy 1e200"});
  expect_error("run 1",
               "fix sph/astro: atom 7 has velocity (0, 1e+200, 0) at the start of the run");
}

// a kernel support longer than the periodic box: the particle meets its own images (the lists
// and the cost grow as the ratio cubed); the sentinel names the atom, h and the box length
TEST_F(Setting, KernelSupportLongerThanTheBoxIsNamed)
{
  sph("sph/astro sentinel stop");
  EXPECT_EQ(error_of(lmp, "run 1"), "");    // support 1.8 in a box of 2
  commands(lmp, {"set atom 3 d_h 1.5"});
  const std::string message = error_of(lmp, "run 1");
  EXPECT_NE(message.find("atom 3 has h = 1.5: its kernel support 3 is 1.5 times the periodic box "
                         "length 2 in x"),
            std::string::npos)
      << message;
}

// the package searches its neighbours itself: LAMMPS' neighbor multi (with comm multi and a
// density contrast of 1e8) gives the run of neighbor bin, to round-off
TEST(NeighbourStyle, MultiGivesTheRunOfBin)
{
  std::map<int, double> x[2];
  for (int multi : {0, 1}) {
    auto lmp = open_lammps();
    commands(lmp,
             {"units lj", "atom_style atomic", "atom_modify map array",
              "region box block 0 6 0 6 0 6", "create_box 1 box", "lattice sc 1.0",
              "create_atoms 1 box", "lattice sc 1.0e8",
              "region clump block 2.1 2.109 2.1 2.109 2.1 2.109 units box",
              "create_atoms 1 region clump", "mass 1 1.0", "pair_style " + std::string(PAIR),
              "pair_coeff * *", "fix gas all sph/astro", "fix hvar all sph/astro/h iterate",
              "set group all d_h 1.0", "set group all d_u 1.0"});
    if (multi)
      commands(lmp,
               {"neighbor 0.001 multi", "comm_modify mode multi",
                "neigh_modify collection/interval 2 0.1 20"});
    else
      commands(lmp, {"neighbor 0.001 bin"});
    commands(lmp, {"run 20"});
    ASSERT_EQ(lmp->atom->natoms, 280);
    x[multi] = per_atom(lmp, "x");
  }
  for (auto &[id, value] : x[0]) EXPECT_NEAR(x[1][id], value, 1e-12) << "atom " << id;
}

// fix sph/astro/h dhdt: particles held at the h cap (here hmax in an expansion) are counted in
// the fix's vector and reported by the sentinel (sentinel stop: as an error)
TEST_F(Setting, ParticlesAtTheDhdtCapAreCountedAndReported)
{
  for (bool stop : {false, true}) {
    if (stop) {    // a fresh instance (the old one first: LAMMPS plugins are global)
      lmp.reset();
      SetUp();
    }
    sph(stop ? "sph/astro sentinel stop" : "sph/astro");
    commands(lmp,
             {"fix hvar all sph/astro/h dhdt hmax 0.92", "variable vx atom 2.0*(x-1.0)",
              "variable vy atom 2.0*(y-1.0)", "variable vz atom 2.0*(z-1.0)",
              "velocity all set v_vx v_vy v_vz", "thermo_style custom step f_hvar[4]"});
    if (stop) {
      const std::string message = error_of(lmp, "run 4");
      EXPECT_NE(message.find("particles were held at the h cap of fix sph/astro/h dhdt (first: "
                             "atom"),
                std::string::npos)
          << message;
    } else {
      commands(lmp, {"run 4"});    // (measured: 4 of 32 held at the cap at steps 1-9)
      const double capped = *static_cast<double *>(
          lammps_extract_fix(lmp.get(), "hvar", LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR, 3, 0));
      EXPECT_GT(capped, 0.05 * 32) << "capped particles after the expansion";
    }
  }
}

// cold gas at rest: no particle's criteria limit its step, so with individual steps the top step
// is dtmax; a dtmax of 1e308 takes the simulation time past the largest double at the second
// step. The run stops there, naming dtmax and its value, instead of running on at time inf (a
// value beyond the largest double is refused by LAMMPS' number parser)
TEST_F(Setting, DtmaxThatOverflowsTheTimeIsNamed)
{
  sph("sph/astro steps individual dtmax 1e308");
  commands(lmp, {"set group all d_u 0.0", "velocity all set 0 0 0"});
  const std::string message = error_of(lmp, "run 5");
  EXPECT_NE(message.find("fix sph/astro: the simulation time 1e+308 plus the next timestep "
                         "1e+308 is not finite at step 1"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("dtmax = 1e+308"), std::string::npos) << message;
  EXPECT_LT(lmp->update->ntimestep, 2);
}

// fix sph/astro/h margin M: the ghost cutoff of a run's start serves h up to M x the largest h.
// Within a run fix sph/astro/h widens it at most to what half the shortest periodic box length
// serves (a kernel wider than that meets its particle's own images); at the start a margin
// beyond the default 1.5 is bounded likewise, with a warning naming the keyword and value.
// Without the bound margin 5 in this box of side 2 (h 0.9) made 34 429 ghosts for 32
// particles, margin 20 1.7 million (500 MB), margin 100 hung in the set-up with gigabytes
TEST_F(Setting, GhostCutoffOfALargeMarginIsBoundedByThePeriodicBox)
{
  const std::string log = "test_reliability_margin.log";
  for (const char *margin : {"5", "100", "1.5"}) {
    if (std::string(margin) != "5") {    // a fresh instance (the old one first: plugins are global)
      lmp.reset();
      SetUp();
    }
    sph();
    commands(lmp,
             {std::string("fix hvar all sph/astro/h iterate margin ") + margin, "log " + log,
              "run 1", "log none"});
    // half the box serves h up to (2 / 2 - skin 0.3) / R 2 = 0.35, below the default's room
    // 1.5 x 0.9: ghost cutoff R 1.35 + skin = 3.0, as with the default margin
    ASSERT_NEAR(lmp->neighbor->cutneighmax, 3.0, 1e-12) << "margin " << margin;
    EXPECT_LT(lmp->atom->nghost, 4000) << "margin " << margin;
    std::ifstream in(log);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text.find(std::string("fix sph/astro/h margin ") + margin +
                        ": the ghost cutoff for h up to") != std::string::npos,
              std::string(margin) != "1.5")
        << text;
  }
  std::remove(log.c_str());
}

// dimension 2: pair sph/astro uses the 2d kernel on distances that include z, so an atom off the
// plane z = 0 (set, a force in z) changed the densities silently (0.87 instead of 1.0 beside an
// atom set to z = 0.45) and drifted in z; fix sph/astro names the atom, its z and v_z, at the
// start of the run or after the step where it left the plane
TEST(TwoDimensions, AtomOffThePlaneIsNamed)
{
  for (const std::string bad : {"", "set atom 5 z 0.45", "fix push all addforce 0 0 1.0"}) {
    auto lmp = open_lammps();
    commands(lmp,
             {"units lj", "dimension 2", "atom_style atomic", "atom_modify map array",
              "lattice sq 1.0", "region box block 0 10 0 10 -0.5 0.5", "create_box 1 box",
              "create_atoms 1 box", "mass 1 1", "pair_style " + std::string(PAIR), "pair_coeff * *",
              "fix gas all sph/astro dt fixed", "set group all d_h 1.2", "set group all d_u 1.0",
              "timestep 0.001"});
    if (!bad.empty()) commands(lmp, {bad});
    const std::string message = error_of(lmp, "run 3");
    if (bad.empty())
      EXPECT_EQ(message, "");
    else if (bad.find("set") == 0)
      EXPECT_NE(message.find("fix sph/astro: dimension 2, but atom 5 has z = 0.45 (v_z = 0) at "
                             "the start of the run"),
                std::string::npos)
          << message;
    else
      EXPECT_NE(message.find("after the step (step 1)"), std::string::npos) << message;
    if (!bad.empty()) EXPECT_NE(message.find("set group all z 0.0"), std::string::npos) << message;
  }
}

// a box periodic in none: a support longer than the box diagonal reaches no further atom; margin
// 1e10 asked for a ghost cutoff of 1.8e10, which on 2 MPI ranks overflowed LAMMPS' count of
// ghost-exchange swaps, so that the ranks waited on each other for ever. The cap is bounded by
// the diagonal, at the start and within a run, with the warning naming the margin
TEST(GhostCutoff, LargeMarginInAnOpenBoxIsBoundedByTheDiagonal)
{
  const std::string log = "test_reliability_margin_open.log";
  auto lmp = open_lammps();
  commands(lmp,
           {"units lj", "atom_style atomic", "atom_modify map array", "boundary s s s",
            "lattice fcc 4.0", "region box block -2 2 -2 2 -2 2", "create_box 1 box",
            "create_atoms 1 box", "mass 1 0.25", "pair_style " + std::string(PAIR),
            "pair_coeff * *", "fix gas all sph/astro",
            "fix hvar all sph/astro/h iterate margin 1e10", "set group all d_h 0.9",
            "set group all d_u 1.0", "log " + log, "run 2", "log none"});
  const double *prd = lmp->domain->prd;
  const double diagonal = std::sqrt(prd[0] * prd[0] + prd[1] * prd[1] + prd[2] * prd[2]);
  EXPECT_LE(lmp->neighbor->cutneighmax, diagonal + lmp->neighbor->skin + 1e-9);
  std::ifstream in(log);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("fix sph/astro/h margin 10000000000: the ghost cutoff for h up to"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("beyond what the box diagonal"), std::string::npos) << text;
  std::remove(log.c_str());
}

// h that outgrows a cap the box does not let widen (hfact 3 in a periodic box of side 2): the
// setup says the particles are held there (it promised a widening that never came)
TEST_F(Setting, HeldAtTheBoxBoundIsSaid)
{
  const std::string log = "test_reliability_box_cap.log";
  sph();
  commands(lmp,
           {"fix hvar all sph/astro/h iterate hfact 3.0", "set group all d_h 0.5", "log " + log,
            "run 1", "log none"});
  std::ifstream in(log);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("32 particles need h beyond the cap 0.75 at the setup of step 0; they are "
                      "held there: the cap is not widened past what half the periodic box length "
                      "serves (h up to 0.35)"),
            std::string::npos)
      << text;
  std::remove(log.c_str());
}

// a viscosity far beyond its range (alpha = beta = 1e300) drives the Courant step to 3e-303:
// the sentinel names the run's first timestep, the particle time scale it falls below and what
// limits it, at the first step; the usual settings pass
TEST_F(Setting, TimestepFarBelowTheParticlesTimeScalesIsNamedAtTheFirstStep)
{
  commands(lmp,
           {"pair_style sph/astro kernel m4 eos ideal $(5.0/3.0) viscosity classic 1e300 "
            "1e300",
            "pair_coeff * *", "fix gas all sph/astro sentinel stop", "set group all d_h 0.9",
            "set group all d_u 1.0"});
  const std::string message = error_of(lmp, "run 1");
  EXPECT_NE(message.find("the run's first timestep"), std::string::npos) << message;
  EXPECT_NE(message.find("times the shortest time in which a particle crosses its h"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("limited by atom"), std::string::npos) << message;
  commands(lmp, {"pair_style " + std::string(PAIR), "pair_coeff * *"});
  EXPECT_EQ(error_of(lmp, "run 1"), "");
}

// 200 particles within 1e-9 of a point: the h iteration of nearly all of them fails in the
// setup's density pass; the sentinel says so at step 0 (it looked only at the steps' passes,
// which converge once h has grown, so only fix sph/astro/h's counter showed it)
TEST(HIteration, FailuresOfTheSetupPassAreReportedAtStepZero)
{
  auto lmp = open_lammps();
  commands(lmp,
           {"units lj", "atom_style atomic", "atom_modify map array", "boundary f f f",
            "region box block -1 1 -1 1 -1 1", "create_box 1 box",
            "region dot sphere 0 0 0 1e-9 units box", "create_atoms 1 random 200 4711 dot",
            "mass 1 0.005", "pair_style " + std::string(PAIR), "pair_coeff * *",
            "fix gas all sph/astro sentinel stop", "fix hvar all sph/astro/h iterate",
            "set group all d_h 0.1", "set group all d_u 1.0", "neighbor 0.05 bin"});
  const std::string message = error_of(lmp, "run 3");
  EXPECT_NE(message.find("at step 0 the h iteration of"), std::string::npos) << message;
  EXPECT_NE(message.find("particles did not converge (first: atom"), std::string::npos) << message;
}
