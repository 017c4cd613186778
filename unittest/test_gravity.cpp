/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// LAMMPS-driven tests of self-gravity: pair sph/astro/gravity, kspace pppm/sph/astro/gravity and
// msm/sph/astro/gravity against compute sph/astro/gravity/direct (direct summation for open
// boundaries, Ewald summation for periodic boxes), momentum conservation, the hybrid/overlay
// combination with pair sph/astro, restart continuity and the errors for bad input.

#include "lammps_fixture.h"

#include "pair_sph_astro.h"
#include "sph_astro_gravity_kernel.h"
#include "sph_astro_kernel.h"

#include "compute.h"
#include "fix.h"
#include "force.h"
#include "kspace.h"
#include "pair.h"
#include "update.h"
#include "variable.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>

using namespace sph_astro_test;
using LAMMPS_NS::LAMMPS;

namespace {
// N random atoms of mass 1 in a ball of radius 5 (open, boundary m) or a periodic box of side
// 10; per-atom softening lengths d_h in [0.3, 0.6] from the SPH state; pair cutoff CUT
void cloud(const std::unique_ptr<LAMMPS> &lmp, bool periodic, int n, const std::string &pair,
           const std::string &kspace, const std::string &kernel = "m4")
{
  commands(lmp,
           {"units lj", "atom_style atomic", "atom_modify map array sort 0 0.0",
            std::string("boundary ") + (periodic ? "p p p" : "m m m")});
  if (periodic)
    commands(lmp,
             {"region box block 0 10 0 10 0 10", "create_box 1 box",
              "create_atoms 1 random " + std::to_string(n) + " 4711 NULL"});
  else
    commands(lmp,
             {"region box block -6 6 -6 6 -6 6", "create_box 1 box",
              "region ball sphere 0 0 0 5 units box",
              "create_atoms 1 random " + std::to_string(n) + " 4711 ball"});
  commands(lmp,
           {"mass 1 1.0", "sph/astro/state", "variable hrand atom 0.3+0.3*random(0,1,99)",
            "set group all d_h v_hrand", "pair_style " + pair + " kernel " + kernel,
            "pair_coeff * *"});
  if (!kspace.empty()) commands(lmp, {"kspace_style " + kspace});
  commands(lmp,
           {"compute ref all sph/astro/gravity/direct", "thermo_style custom step pe c_ref",
            "thermo_modify norm no"});
}

// relative RMS difference of the forces from the reference compute's (atoms with IDs up to
// max_id)
double force_error(const std::unique_ptr<LAMMPS> &lmp, int max_id = 0)
{
  auto *ref = lmp->modify->get_compute_by_id("ref");
  ref->compute_peratom();
  double d2 = 0.0, f2 = 0.0;
  for (int i = 0; i < lmp->atom->nlocal; i++)
    for (int d = 0; d < 3 && (max_id == 0 || lmp->atom->tag[i] <= max_id); d++) {
      const double diff = lmp->atom->f[i][d] - ref->array_atom[i][d];
      d2 += diff * diff;
      f2 += ref->array_atom[i][d] * ref->array_atom[i][d];
    }
  return std::sqrt(d2 / f2);
}

double potential_energy(const std::unique_ptr<LAMMPS> &lmp)
{
  double e = lmp->force->pair->eng_vdwl;
  if (lmp->force->kspace) e += lmp->force->kspace->energy;
  return e;
}

double reference_energy(const std::unique_ptr<LAMMPS> &lmp)
{
  return lmp->modify->get_compute_by_id("ref")->compute_scalar();
}

const char *all_kernels[] = {"m4", "m6", "wendland/c2", "wendland/c4"};
}    // namespace

// direct summation (no kspace, cutoff beyond the system) equals the reference for every kernel
class GravityDirect : public ::testing::TestWithParam<const char *> {};

TEST_P(GravityDirect, PairEqualsDirectSum)
{
  auto lmp = open_lammps();
  cloud(lmp, false, 300, "sph/astro/gravity 20", "", GetParam());
  commands(lmp, {"run 0"});
  const double err = force_error(lmp);
  printf("%s: pair vs direct sum: relative RMS force difference %.2e\n", GetParam(), err);
  EXPECT_LT(err, 1e-12);
  EXPECT_NEAR(potential_energy(lmp), reference_energy(lmp),
              1e-12 * std::fabs(reference_energy(lmp)));
  // the softening matters here (h up to 0.6, mean spacing ~1.2): it differs from Newtonian
  ASSERT_LT(reference_energy(lmp), 0.0);
}

INSTANTIATE_TEST_SUITE_P(AllKernels, GravityDirect, ::testing::ValuesIn(all_kernels));

TEST(GravityDirect, SofteningChangesTheForces)
{
  // the same cloud with h 10x smaller: the forces must differ (the test can fail)
  auto lmp = open_lammps();
  cloud(lmp, false, 300, "sph/astro/gravity 20", "");
  commands(lmp, {"run 0"});
  std::vector<double> f0;
  for (int i = 0; i < lmp->atom->nlocal; i++) f0.push_back(lmp->atom->f[i][0]);
  commands(lmp, {"variable hsmall atom 0.1*v_hrand", "set group all d_h v_hsmall", "run 0"});
  double diff = 0.0, norm = 0.0;
  for (int i = 0; i < lmp->atom->nlocal; i++) {
    diff += std::fabs(lmp->atom->f[i][0] - f0[i]);
    norm += std::fabs(f0[i]);
  }
  EXPECT_GT(diff / norm, 1e-3);
  EXPECT_LT(force_error(lmp), 1e-12);
}

// long range + short range against the reference within the set accuracy
struct KSpaceCase {
  const char *name;
  bool periodic;
  const char *kspace;
  double accuracy, bound;    // bound on the relative RMS force error
};

class GravityKSpace : public ::testing::TestWithParam<KSpaceCase> {};

TEST_P(GravityKSpace, MatchesReferenceWithinAccuracy)
{
  const auto c = GetParam();
  auto lmp = open_lammps();
  cloud(lmp, c.periodic, 400, "sph/astro/gravity 3.0",
        std::string(c.kspace) + " " + num(c.accuracy));
  commands(lmp, {"run 0"});
  const double err = force_error(lmp);
  const double e = potential_energy(lmp), eref = reference_energy(lmp);
  printf("%s accuracy %.0e: relative RMS force error %.3e, energy %.10g vs %.10g\n", c.name,
         c.accuracy, err, e, eref);
  EXPECT_LT(err, c.bound);
  EXPECT_GT(err, 1e-3 * c.accuracy);    // a long-range solver, not the exact sum
  EXPECT_NEAR(e, eref, 10 * c.bound * std::fabs(eref));
}

INSTANTIATE_TEST_SUITE_P(
    Solvers, GravityKSpace,
    ::testing::Values(KSpaceCase{"msm_open", false, "msm/sph/astro/gravity", 1e-4, 3e-4},
                      KSpaceCase{"msm_open", false, "msm/sph/astro/gravity", 1e-6, 3e-6},
                      KSpaceCase{"pppm_periodic", true, "pppm/sph/astro/gravity", 1e-4, 3e-4},
                      KSpaceCase{"pppm_periodic", true, "pppm/sph/astro/gravity", 1e-6, 3e-6}),
    [](const ::testing::TestParamInfo<KSpaceCase> &info) {
      return std::string(info.param.name) + "_" + std::to_string(info.index);
    });

// a shrink-wrapped box that grows within a run: LAMMPS keeps MSM's number of grid points, so
// its spacing would grow with the box and its error as (h/a)^(p-1); msm/sph/astro/gravity
// doubles the points along an axis whenever the spacing exceeds that of the run's start. The
// cloud expands freely (G tiny) in one run, its box (boundary m) from 12 to 20.5: the forces
// of its last step stay within the accuracy's bound (3.1e-3 with the grid of the start kept)
TEST(GravityKSpaceGrowingBox, MSMKeepsItsGridSpacing)
{
  auto lmp = open_lammps();
  cloud(lmp, false, 400, "sph/astro/gravity 3.0 G 1e-6", "msm/sph/astro/gravity 1e-4");
  commands(lmp, {"run 0"});
  const double before = force_error(lmp);
  const double box = lmp->domain->prd[0];
  commands(lmp,
           {"variable vx atom 0.06*x", "variable vy atom 0.06*y", "variable vz atom 0.06*z",
            "velocity all set v_vx v_vy v_vz", "fix nve all nve", "timestep 1.0",
            "neigh_modify every 1 delay 0 check yes", "run 20"});
  const double after = force_error(lmp);
  std::printf("relative RMS force error %.3e before, %.3e after the box grew from %.3g to %.3g\n",
              before, after, box, lmp->domain->prd[0]);
  EXPECT_GT(lmp->domain->prd[0], 1.7 * box);
  EXPECT_LT(before, 3e-4);
  EXPECT_LT(after, 3e-4);
}

// a particle far from the rest when the run starts: LAMMPS wraps the box around it at the run's
// setup, after MSM chose its grid and cutoff at init for the box as it was (12 long), and MSM
// kept its number of points: the spacing along x grew with the box, and the other 400 atoms'
// relative RMS force error was 1.6e-3 with the atom at x = 15 (box 21: grid refined to the
// spacing of init) and 0.25 at x = 100 (box 106: grid and cutoff chosen for it). The atom at
// 100, 25 times the others' RMS distance from the centre of mass, is named at init
TEST(GravityKSpaceFarParticle, AtTheRunStartKeepsTheAccuracy)
{
  const std::string log = "test_gravity_far_atom.log";
  for (const char *x : {"15", "100"}) {
    auto lmp = open_lammps();
    cloud(lmp, false, 400, "sph/astro/gravity 3.0", "msm/sph/astro/gravity 1e-4");
    commands(lmp,
             {"create_atoms 1 single 0 0 0 units box",
              std::string("set atom 401 x ") + x + " d_h 0.5", "log " + log, "run 0", "log none"});
    ASSERT_EQ(lmp->atom->natoms, 401);
    const double err = force_error(lmp, 400);
    std::printf("atom 401 at x = %s: the others' relative RMS force error %.3e\n", x, err);
    EXPECT_LT(err, 3e-4) << "x = " << x;
    std::ifstream in(log);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text.find("kspace_style msm/sph/astro/gravity: atom 401 lies 99.8") !=
                  std::string::npos,
              std::string(x) == "100")
        << text;
  }
  std::remove(log.c_str());
}

// a box so long that MSM would need more than its 10 levels (512 points along an axis) for the
// accuracy: LAMMPS' MSM stopped with "Too many MSM grid levels" (and, as a library, freed its
// levels twice when deleted: the heap was corrupted); the atom and the remedies are named. A
// grid of more than 512 points given with kspace_modify mesh is refused likewise
TEST(GravityKSpaceFarParticle, BeyondMSMsLevelsIsNamed)
{
  {
    auto lmp = open_lammps();
    cloud(lmp, false, 4000, "sph/astro/gravity 3.0", "msm/sph/astro/gravity 1e-4");
    commands(lmp, {"create_atoms 1 single 0 0 0 units box", "set atom 4001 x 10000 d_h 0.5"});
    const std::string message = error_of(lmp, "run 0");
    EXPECT_NE(message.find("asks for 1024 grid points along x for the accuracy, more than the "
                           "512 LAMMPS' MSM takes"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("atom 4001 lies 99"), std::string::npos) << message;
  }
  auto lmp = open_lammps();
  cloud(lmp, false, 40, "sph/astro/gravity 3.0", "msm/sph/astro/gravity 1e-4");
  commands(lmp, {"kspace_modify mesh 2048 8 8"});
  const std::string message = error_of(lmp, "run 0");
  EXPECT_NE(message.find("kspace_modify mesh 2048 8 8: kspace_style msm/sph/astro/gravity takes "
                         "at most 512 grid points along an axis"),
            std::string::npos)
      << message;
}

// a box created 2000 long around a ball of radius 5 (boundary s): MSM chose its grid and cutoff
// for that box (cutoff 1350) and kept the number of points when LAMMPS wrapped the box around
// the atoms at the run's setup; its direct-sum stencil, 2 cutoff / spacing wide, then asked for
// a negative number of bytes (1.4 of 81 for a box 120 long: 4.8 GB)
TEST(GravityKSpaceFarParticle, OversizedBoxIsWrappedBeforeMSMChoosesItsGrid)
{
  auto lmp = open_lammps();
  commands(lmp,
           {"units lj", "atom_style atomic", "atom_modify map array sort 0 0.0", "boundary s s s",
            "region box block -1000 1000 -1000 1000 -1000 1000", "create_box 1 box",
            "region ball sphere 0 0 0 5 units box", "create_atoms 1 random 400 4711 ball",
            "mass 1 1.0", "sph/astro/state", "variable hrand atom 0.3+0.3*random(0,1,99)",
            "set group all d_h v_hrand", "pair_style sph/astro/gravity 3.0", "pair_coeff * *",
            "kspace_style msm/sph/astro/gravity 1e-4", "compute ref all sph/astro/gravity/direct"});
  ASSERT_EQ(error_of(lmp, "run 0"), "");
  const double err = force_error(lmp);
  int dim = 0;
  const double cutoff = *static_cast<double *>(lmp->force->pair->extract("cut_coul", dim));
  std::printf("box created 2000 long: relative RMS force error %.3e, MSM cutoff %.4g\n", err,
              cutoff);
  EXPECT_LT(err, 3e-4);
  EXPECT_LT(cutoff, 12.0);
}

// one particle escaping from a cloud (G tiny: the cloud stays where it is) at 200 length units
// per time unit: MSM keeps the grid spacing of the run's start, so the points along x double
// with the box, 8 -> 1024 within 4 steps, where LAMMPS' MSM stopped with "Too many MSM grid
// levels" (and its levels, freed twice, corrupted the heap when LAMMPS was deleted); moving in
// y and z as well the grid grew to 64 64 64, 7 s per step. The growth is bounded, at the 512
// points along an axis of MSM's 10 levels and at 128 times the points of the run's start
// (kspace_modify mesh/growth): the run stops there, naming the atom, its distance from the
// centre of mass and the remedies
TEST(GravityKSpaceFarParticle, EscapingParticleBoundsTheGridGrowth)
{
  for (const bool lower_bound : {false, true}) {
    auto lmp = open_lammps();
    cloud(lmp, false, 400, "sph/astro/gravity 3.0 G 1e-6", "msm/sph/astro/gravity 1e-4");
    commands(lmp,
             {"create_atoms 1 single 0 0 0 units box", "set atom 401 x 5.5 vx 200 d_h 0.5",
              "fix nve all nve", "timestep 1.0", "neigh_modify every 1 delay 0 check yes"});
    if (lower_bound) commands(lmp, {"kspace_modify mesh/growth 4"});
    const std::string message = error_of(lmp, "run 20");
    // 8 8 8 points at the start (spacing 1.5): more than 512 along x for a box longer than 768
    // (step 4), 4 times the points for one longer than 48 (step 1)
    EXPECT_NE(message.find(std::string("kspace_style msm/sph/astro/gravity: on step ") +
                           (lower_bound ? "1 " : "4 ")),
              std::string::npos)
        << message;
    EXPECT_NE(message.find(lower_bound
                               ? "more than 4 times the 512 points of the run's start"
                               : "more than the 512 points along an axis LAMMPS' MSM takes"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("atom 401 lies"), std::string::npos) << message;
    // (a bound to raise only below MSM's levels)
    EXPECT_EQ(message.find("raise the bound (kspace_modify mesh/growth)") != std::string::npos,
              lower_bound)
        << message;
    std::printf("%s\n", message.c_str());
  }
  // the points of the start grow in x, y and z: the default bound
  {
    auto lmp = open_lammps();
    cloud(lmp, false, 400, "sph/astro/gravity 3.0 G 1e-6", "msm/sph/astro/gravity 1e-4");
    commands(lmp,
             {"create_atoms 1 single 0 0 0 units box",
              "set atom 401 x 5.5 y 5.5 z 5.5 vx 20 vy 20 vz 20 d_h 0.5", "fix nve all nve",
              "timestep 1.0", "neigh_modify every 1 delay 0 check yes"});
    const std::string message = error_of(lmp, "run 20");
    EXPECT_NE(message.find("more than 128 times the 512 points of the run's start (kspace_modify "
                           "mesh/growth 128)"),
              std::string::npos)
        << message;
    std::printf("%s\n", message.c_str());
  }
  auto lmp = open_lammps();
  cloud(lmp, false, 40, "sph/astro/gravity 3.0", "msm/sph/astro/gravity 1e-4");
  for (const char *bad : {"0.5", "-1", "many"}) {
    const std::string message = error_of(lmp, std::string("kspace_modify mesh/growth ") + bad);
    EXPECT_NE(message.find("mesh/growth"), std::string::npos) << bad << ": " << message;
  }
}

TEST(GravityPair, MomentumIsConserved)
{
  // pairwise antisymmetric forces: total force zero, momentum constant over a run
  auto lmp = open_lammps();
  cloud(lmp, false, 300, "sph/astro/gravity 20", "");
  commands(lmp,
           {"fix nve all nve", "timestep 0.01", "velocity all create 0.1 12345 mom yes rot yes",
            "run 0"});
  expect_forces_sum_to_zero(lmp);
  commands(lmp, {"run 200"});
  double p[3] = {0, 0, 0}, pabs = 0;
  for (int i = 0; i < lmp->atom->nlocal; i++)
    for (int d = 0; d < 3; d++) {
      p[d] += lmp->atom->v[i][d];
      pabs += std::fabs(lmp->atom->v[i][d]);
    }
  ASSERT_GT(pabs, 0.0);
  for (double pd : p) EXPECT_LT(std::fabs(pd), 1e-12 * pabs);
}

TEST(GravityPair, EnergyIsConservedWithFixedSoftening)
{
  // fixed h (no SPH state change): the softened potential is a true potential, so
  // leapfrog conserves E = K + U to O(dt^2)
  auto energy_drift = [](double dt) {
    auto lmp = open_lammps();
    cloud(lmp, false, 200, "sph/astro/gravity 20", "");
    commands(lmp,
             {"fix nve all nve", "timestep " + num(dt), "thermo_style custom step etotal",
              "thermo_modify norm no", "run 0"});
    const double e0 = lmp->force->pair->eng_vdwl;
    const int n = static_cast<int>(std::lround(0.4 / dt));
    commands(
        lmp,
        {"variable et equal etotal", "thermo " + std::to_string(n), "run " + std::to_string(n)});
    const double e1 = lmp->input->variable->compute_equal("v_et");
    return std::fabs((e1 - e0) / e0);
  };
  const double e1 = energy_drift(0.02), e2 = energy_drift(0.01);
  printf("gravity energy error: dt 0.02 %.3e, dt 0.01 %.3e\n", e1, e2);
  EXPECT_LT(e1, 1e-3);
  EXPECT_NEAR(e1 / e2, 4.0, 1.5);
}

TEST(GravityPair, HybridOverlayWithSPH)
{
  // gas ball with SPH and self-gravity: fix sph/astro finds the SPH sub-style, the gravity
  // sub-style takes the SPH kernel, and compute sph/astro/global's potential energy (value 10)
  // is the gravitational energy of the reference
  auto lmp = open_lammps();
  const double h = 1.2 * std::cbrt(0.25);
  commands(lmp,
           {"units lj",
            "atom_style atomic",
            "atom_modify map array sort 0 0.0",
            "boundary s s s",
            "lattice fcc 4.0",
            "region box block -4 4 -4 4 -4 4",
            "create_box 1 box",
            "region ball sphere 0 0 0 3 units box",
            "create_atoms 1 region ball",
            "mass 1 0.25",
            "pair_style hybrid/overlay sph/astro kernel wendland/c4 eos ideal 1.6666667 "
            "viscosity classic 1.0 2.0 sph/astro/gravity 30",
            "pair_coeff * * sph/astro",
            "pair_coeff * * sph/astro/gravity",
            "fix gas all sph/astro courant 0.3",
            "set group all d_h " + num(h),
            "set group all d_u 0.05",
            "neighbor " + num(0.3 * h) + " bin",
            "compute sum all sph/astro/global",
            "thermo_style custom step c_sum[10]",
            "compute ref all sph/astro/gravity/direct",
            "run 0"});
  const auto sum = global_vector(lmp, "sum", 12);
  const double eref = reference_energy(lmp);
  ASSERT_LT(eref, 0.0);
  EXPECT_NEAR(sum[9], eref, 1e-11 * std::fabs(eref));
  // the gas falls inwards: gravity acts through the hybrid style during a run
  commands(lmp, {"run 20"});
  const auto after = global_vector(lmp, "sum", 12);
  EXPECT_LT(after[9], sum[9]);
  // a different kernel for the gravity sub-style is refused
  commands(lmp,
           {"pair_style hybrid/overlay sph/astro kernel wendland/c4 eos ideal 1.6 "
            "sph/astro/gravity 30 kernel m4",
            "pair_coeff * * sph/astro", "pair_coeff * * sph/astro/gravity"});
  const auto err = error_of(lmp, "run 0");
  EXPECT_NE(err.find("kernel m4 differs from the kernel wendland/c4"), std::string::npos) << err;
}

// a cold gas ball of radius 2.5 lattice units (SPH + gravity, variable h by iteration with grad-h
// terms, lattice displaced at random) under fix sph/astro FIX; gravity: the pair sub-style's
// arguments after its name
// positions and velocities bit for bit those of a reference run (by atom ID)
static void expect_same_x_v(const std::unique_ptr<LAMMPS> &lmp, const std::map<int, double> &x_ref,
                            const std::map<int, double> &v_ref)
{
  auto x = per_atom(lmp, "x", 0);
  auto v = per_atom(lmp, "v", 1);
  ASSERT_EQ(x.size(), x_ref.size());
  for (const auto &[id, value] : x_ref) {
    EXPECT_EQ(x[id], value) << "atom " << id;
    EXPECT_EQ(v[id], v_ref.at(id)) << "atom " << id;
  }
}

static void falling_ball(const std::unique_ptr<LAMMPS> &lmp, const std::string &gravity,
                         const std::string &fix, const std::string &boundary = "s s s")
{
  const double h = 1.2 * std::cbrt(0.25);
  commands(lmp,
           {"units lj",
            "atom_style atomic",
            "atom_modify map array sort 0 0.0",
            "boundary " + boundary,
            "lattice fcc 4.0",
            "region box block -4 4 -4 4 -4 4",
            "create_box 1 box",
            "region ball sphere 0 0 0 2.5 units box",
            "create_atoms 1 region ball",
            "displace_atoms all random 0.05 0.05 0.05 4711 units box",
            "mass 1 0.25",
            "pair_style hybrid/overlay sph/astro kernel m4 eos ideal 1.6666667 viscosity "
            "classic 1.0 2.0 sph/astro/gravity " +
                gravity,
            "pair_coeff * * sph/astro",
            "pair_coeff * * sph/astro/gravity",
            "fix gas all sph/astro " + fix,
            "fix hvar all sph/astro/h iterate hfact 1.2 tol 1e-10 margin 2.5",
            "set group all d_h " + num(h),
            "set group all d_u 0.05",
            "neighbor " + num(0.3 * h) + " bin",
            "neigh_modify every 1 delay 0 check yes",
            "compute sum all sph/astro/global"});
}

// the ball falling in for time T with fixed dt: relative total-energy error (K + U + W)
static double collapse_energy_error(double dt, const std::string &zeta, double *hratio = nullptr)
{
  auto lmp = open_lammps();
  const double T = 0.4;
  const int nsteps = static_cast<int>(std::lround(T / dt));
  falling_ball(lmp, "30 zeta " + zeta, "dt fixed");
  commands(lmp,
           {"thermo_style custom step c_sum[12] c_sum[13]", "thermo " + std::to_string(nsteps),
            "timestep " + num(dt), "run 0"});
  const double hmin0 = global_vector(lmp, "sum", 13)[12];
  commands(lmp, {"run " + std::to_string(nsteps)});
  const auto end = global_vector(lmp, "sum", 18);
  if (hratio) *hratio = hmin0 / end[12];
  EXPECT_EQ(end[17], 0.0) << "particles held at the h cap";
  return std::fabs(end[11]);
}

TEST(GravityPair, AdaptiveSofteningConservesEnergyToSecondOrder)
{
  // Price & Monaghan 2007: with h following rho the zeta terms make the energy error a pure
  // time-integration error (falls as dt^2); without them an O(1) error remains that does not
  // fall with dt
  double hratio = 0.0;
  const double z1 = collapse_energy_error(0.02, "yes", &hratio);
  const double z2 = collapse_energy_error(0.01, "yes");
  const double z3 = collapse_energy_error(0.005, "yes");
  const double n2 = collapse_energy_error(0.01, "no");
  const double n3 = collapse_energy_error(0.005, "no");
  printf("collapse, smallest h shrank by %.2f: energy error with zeta: dt 0.02 %.3e, 0.01 %.3e, "
         "0.005 %.3e; without zeta: dt 0.01 %.3e, 0.005 %.3e\n",
         hratio, z1, z2, z3, n2, n3);
  EXPECT_GT(hratio, 1.3);    // h really varies
  EXPECT_NEAR(z1 / z2, 4.0, 1.0);
  EXPECT_NEAR(z2 / z3, 4.0, 1.0);
  EXPECT_GT(n3, 10.0 * z3);
  EXPECT_GT(n3, 0.5 * n2);    // without zeta the error does not converge away
}

// zeta_i = -h_i/(3 rho_i) S_i, S_i = sum_{j != i, r_ij < R h_i} m_j dphi(r_ij, h_i)/dh_i (Price &
// Monaghan 2007, eq. 26) of the owned atoms (one rank) against all pairs; evaluated: the atoms
// whose S_i is of this step (else each must hold h_i^2 S_i of its last evaluation, d_step_dphidh,
// over its h^2 of now).
// Returns how many atoms were checked against all pairs
static int expect_zeta_is_pair_sum(const std::unique_ptr<LAMMPS> &lmp,
                                   const std::vector<char> &evaluated = {})
{
  int ncol = 0;
  const auto *zeta = static_cast<const double *>(
      lmp->force->pair_match("^sph/astro/gravity$", 0, 0)->extract_peratom("zeta", ncol));
  EXPECT_NE(zeta, nullptr);
  if (!zeta) return 0;
  auto *sph = static_cast<LAMMPS_NS::PairSPHAstro *>(lmp->force->pair_match("^sph/astro$", 0, 0));
  int flag, cols;
  const double *h = lmp->atom->dvector[lmp->atom->find_custom("h", flag, cols)];
  const double *rho = lmp->atom->dvector[lmp->atom->find_custom("rho", flag, cols)];
  const int kept = lmp->atom->find_custom("step_dphidh", flag, cols);
  const double cap = sph->h_cap();
  double **x = lmp->atom->x;
  const int n = lmp->atom->nlocal;
  EXPECT_EQ(n, lmp->atom->natoms);    // one rank: every atom is owned
  const double R = SPHAstro::kernel_radius(SPHAstro::KernelType::CUBIC);
  int inside = 0, checked = 0;
  for (int i = 0; i < n; i++) {
    double sum = 0.0;
    if (evaluated.empty() || evaluated[i]) {
      for (int j = 0; j < n; j++) {
        const double dx = x[i][0] - x[j][0], dy = x[i][1] - x[j][1], dz = x[i][2] - x[j][2];
        const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
        if (j == i || !(r < R * h[i])) continue;
        sum += 0.25 * SPHAstro::softened_dphidh(SPHAstro::KernelType::CUBIC, r, h[i]);
        inside++;
      }
      checked++;
    } else {
      EXPECT_GE(kept, 0);
      if (kept < 0) return 0;
      sum = lmp->atom->dvector[kept][i] / (h[i] * h[i]);
    }
    const double expected = h[i] >= cap ? 0.0 : -h[i] / (3.0 * rho[i]) * sum;
    EXPECT_NEAR(zeta[i], expected, 1e-13 * std::fabs(expected)) << "atom " << lmp->atom->tag[i];
  }
  EXPECT_GT(inside, 20 * checked);    // each atom has its kernel neighbours
  return checked;
}

// pair sph/astro sums S_i in its h iteration for direct summation and for the short-range
// part of a kspace split alike
class GravityZeta : public ::testing::TestWithParam<const char *> {};

TEST_P(GravityZeta, IsTheSumOverTheKernelNeighbours)
{
  const bool msm = std::string(GetParam()) == "msm";
  auto lmp = open_lammps();
  falling_ball(lmp, msm ? "1.5" : "30", "dt fixed");
  if (msm) commands(lmp, {"kspace_style msm/sph/astro/gravity 1e-5"});
  commands(lmp, {"timestep 0.01", "run 5"});
  EXPECT_EQ(expect_zeta_is_pair_sum(lmp), lmp->atom->nlocal);
}

INSTANTIATE_TEST_SUITE_P(Summed, GravityZeta, ::testing::Values("direct", "msm"));

// individual timesteps (a ball with a hot core), between synchronisation points: the atoms of
// the step's evaluation have the zeta of their kernel neighbours now; the others that of
// h^2 S_i when they were last evaluated, with their h and rho of now
TEST(GravityZetaIndividualSteps, InactiveAtomsKeepTheSumOfTheirLastEvaluation)
{
  auto lmp = open_lammps();
  falling_ball(lmp, "30", "courant 0.3 steps individual tend 0.4");
  commands(lmp, {"region core sphere 0 0 0 1.0 units box", "set region core d_u 3.0", "run 0"});
  // steps until one evaluates fewer than half the atoms: those whose new step begins now (the
  // latest begin of all)
  const int n = lmp->atom->nlocal;
  std::vector<char> evaluated(n);
  int active = n;
  for (int step = 0; step < 200 && !(active < n / 2); step++) {
    commands(lmp, {"run 1 pre no post no"});
    int flag, cols;
    const double *begin = lmp->atom->dvector[lmp->atom->find_custom("step_begin", flag, cols)];
    const double now = *std::max_element(begin, begin + n);
    for (int i = 0; i < n; i++) evaluated[i] = begin[i] == now;
    active = static_cast<int>(std::count(evaluated.begin(), evaluated.end(), 1));
  }
  std::printf("step %lld: %d of %d atoms evaluated\n",
              static_cast<long long>(lmp->update->ntimestep), active, n);
  ASSERT_GT(active, 0);
  ASSERT_LT(active, n / 2);
  EXPECT_EQ(expect_zeta_is_pair_sum(lmp, evaluated), active);
}

// individual timesteps with adaptive softening: a restart in the middle of the hierarchy
// continues bit for bit (the sleeping atoms' sums of zeta travel in d_step_dphidh; a hot core
// and limiter 3 make a deep hierarchy)
TEST(GravityZetaIndividualSteps, RestartMidHierarchyContinuesBitForBit)
{
  const std::string restart = "test_gravity_individual.restart";
  const std::string fix = "courant 0.3 steps individual tend 0.4 limiter 3";
  std::map<int, double> x_ref, v_ref;
  {
    auto lmp = open_lammps();
    falling_ball(lmp, "30", fix);
    commands(lmp, {"region core sphere 0 0 0 1.0 units box", "set region core d_u 30.0"});
    auto *gas = lmp->modify->get_fix_by_id("gas");
    commands(lmp, {"run 1"});
    EXPECT_LT(gas->compute_vector(4), 0.5 * lmp->atom->natoms);    // the restart: mid-hierarchy
    commands(lmp, {"write_restart " + restart, "run 1"});
    EXPECT_LT(gas->compute_vector(4), lmp->atom->natoms);    // the next step: some asleep
    commands(lmp, {"run 40"});
    EXPECT_GE(gas->compute_vector(5), 2.0);
    x_ref = per_atom(lmp, "x", 0);
    v_ref = per_atom(lmp, "v", 1);
  }
  auto lmp = open_lammps();
  commands(lmp,
           {"read_restart " + restart, "pair_coeff * * sph/astro",
            "pair_coeff * * sph/astro/gravity", "fix gas all sph/astro " + fix,
            "fix hvar all sph/astro/h iterate hfact 1.2 tol 1e-10 margin 2.5",
            "neighbor " + num(0.3 * 1.2 * std::cbrt(0.25)) + " bin",
            "neigh_modify every 1 delay 0 check yes", "run 1", "run 40"});
  expect_same_x_v(lmp, x_ref, v_ref);
  std::remove(restart.c_str());
}

// individual timesteps (a ball with a hot core): the gravity pair sums forces only for pairs
// with an active atom, and with the energy tallied (direct summation) only the potential of
// the others; per-atom energies need every pair. Three runs: nothing tallied between the
// thermo rows, the energy at every step, the energy and per-atom energies at every step. The
// active atoms' forces, and so the runs, are the same bit for bit, and the energy of the second
// run is that of the third at every step
class GravityIndividualSteps : public ::testing::TestWithParam<const char *> {};

TEST_P(GravityIndividualSteps, PairsOfInactiveAtomsDoNotChangeTheRun)
{
  const bool msm = std::string(GetParam()) == "msm";
  enum { QUIET, ENERGY, PERATOM };
  std::map<int, double> x[3], v[3];
  std::vector<double> pe[3];
  double bins = 0.0, updates = 0.0, steps = 0.0, natoms = 0.0;
  for (int mode : {QUIET, ENERGY, PERATOM}) {
    auto lmp = open_lammps();
    falling_ball(lmp, msm ? "1.5" : "30", "courant 0.3 steps individual tend 0.4");
    if (msm) commands(lmp, {"kspace_style msm/sph/astro/gravity 1e-5"});
    // a hot core: its particles step short, the cold ones long
    commands(lmp, {"region core sphere 0 0 0 1.0 units box", "set region core d_u 3.0"});
    if (mode == ENERGY)
      commands(lmp, {"compute e all pe", "variable e equal c_e", "fix rec all vector 1 v_e v_e"});
    if (mode == PERATOM)
      commands(lmp,
               {"compute e all pe", "variable e equal c_e", "compute ea all pe/atom",
                "compute esum all reduce sum c_ea", "variable ea equal c_esum",
                "fix rec all vector 1 v_e v_ea"});
    commands(lmp, {"thermo_style custom step c_sum[12] f_gas[5]", "thermo 1000", "run 100000"});
    x[mode] = per_atom(lmp, "x", 0);
    v[mode] = per_atom(lmp, "v", 1);
    if (mode != QUIET) {
      auto *rec = lmp->modify->get_fix_by_id("rec");
      for (int r = 0; r < rec->size_array_rows; r++) pe[mode].push_back(rec->compute_array(r, 0));
    }
    bins = lmp->modify->get_fix_by_id("gas")->compute_vector(5);
    updates = lmp->modify->get_fix_by_id("gas")->compute_vector(6);
    steps = static_cast<double>(lmp->update->ntimestep);
    natoms = static_cast<double>(lmp->atom->natoms);
  }
  // several bins, so that most steps evaluate a part of the atoms
  EXPECT_GE(bins, 2.0);
  EXPECT_LT(updates, 0.75 * steps * natoms) << updates << " updates in " << steps << " steps";
  for (int mode : {ENERGY, PERATOM}) {
    ASSERT_EQ(x[QUIET].size(), x[mode].size());
    for (const auto &[id, value] : x[QUIET]) {
      EXPECT_EQ(x[mode][id], value) << "atom " << id << ", run " << mode;
      EXPECT_EQ(v[mode][id], v[QUIET][id]) << "atom " << id << ", run " << mode;
    }
  }
  ASSERT_EQ(pe[ENERGY].size(), pe[PERATOM].size());
  ASSERT_GT(pe[ENERGY].size(), 10U);
  for (std::size_t r = 0; r < pe[ENERGY].size(); r++)
    EXPECT_NEAR(pe[ENERGY][r], pe[PERATOM][r], 1e-12 * std::fabs(pe[PERATOM][r])) << "step " << r;
}

INSTANTIATE_TEST_SUITE_P(GravityPair, GravityIndividualSteps, ::testing::Values("direct", "msm"));

// fix sph/astro's energy at the synchronisation points (vector 9) on the collapsing ball: the
// infall shortens every particle's step, the top bin empties, and the steps at which every
// particle ends its step lie on finer bins' grids as well. At each of them (run by run: the
// thermo prints the energy at every step) the fix's value is compute sph/astro/global's
TEST(GravityPair, IndividualStepsMeasureTheEnergyWhereverEveryParticleEndsItsStep)
{
  auto lmp = open_lammps();
  falling_ball(lmp, "30", "courant 0.3 steps individual tend 0.4");
  commands(lmp, {"thermo_style custom step c_sum[12] f_gas[9]", "run 1"});    // (E0 at step 0)
  const double n = static_cast<double>(lmp->atom->natoms);
  auto *gas = lmp->modify->get_fix_by_id("gas");
  auto now = [&]() {
    return lmp->update->atime + (lmp->update->ntimestep - lmp->update->atimestep) * lmp->update->dt;
  };
  int points = 0, steps = 1;
  while (steps < 5000 && now() < 0.4 * (1.0 - 1e-12)) {
    commands(lmp, {"run 1 pre no post no"});
    steps++;
    if (gas->compute_vector(4) != n) continue;    // not every particle active
    const auto sum = global_vector(lmp, "sum", 12);
    EXPECT_NEAR(gas->compute_vector(8), sum[11], 1e-12) << "step " << steps;
    points++;
  }
  std::printf("%d synchronisation points in %d steps\n", points, steps);
  EXPECT_GT(points, 10);
}

// fix sph/astro longrange sync (a ball with a hot core, MSM): the long range is computed only
// at the steps where every particle ends its step, and integrated on the intervals between them
namespace {
// each atom's long-range acceleration d2_step_accel_long, by atom ID
std::map<int, std::array<double, 3>> accel_long(const std::unique_ptr<LAMMPS> &lmp)
{
  int flag, cols;
  const int index = lmp->atom->find_custom("step_accel_long", flag, cols);
  std::map<int, std::array<double, 3>> out;
  if (index < 0) return out;
  double **a = lmp->atom->darray[index];
  for (int i = 0; i < lmp->atom->nlocal; i++)
    out[static_cast<int>(lmp->atom->tag[i])] = {a[i][0], a[i][1], a[i][2]};
  return out;
}

// solver msm (open box) or pppm (periodic box of 8)
void hot_ball(const std::unique_ptr<LAMMPS> &lmp, const std::string &fix,
              const std::string &solver = "msm")
{
  const bool msm = solver == "msm";
  falling_ball(lmp, msm ? "1.5" : "3.0", fix, msm ? "s s s" : "p p p");
  commands(lmp,
           {"kspace_style " + solver + "/sph/astro/gravity 1e-5",
            "region core sphere 0 0 0 1.0 units box", "set region core d_u 3.0"});
}
}    // namespace

// the solver's forces change at the synchronisation points only, and there are fewer of them
// than steps; its energy, asked for at every step here (thermo pe), is that of the current
// positions at every step
TEST(GravityLongRangeSync, ForcesOnlyWhereEveryParticleEndsItsStep)
{
  auto lmp = open_lammps();
  hot_ball(lmp, "courant 0.3 steps individual tend 0.4 longrange sync");
  commands(lmp, {"thermo_style custom step pe c_sum[12] f_gas[9]", "run 1"});
  const double n = static_cast<double>(lmp->atom->natoms);
  auto *gas = lmp->modify->get_fix_by_id("gas");
  auto before = accel_long(lmp);
  ASSERT_FALSE(before.empty());
  double energy = lmp->force->kspace->energy;
  int points = 0, between = 0;
  for (int step = 0; step < 400 && !(points >= 4 && between >= 20); step++) {
    commands(lmp, {"run 1 pre no post no"});
    const auto now = accel_long(lmp);
    const bool all_active = gas->compute_vector(4) == n;
    int changed = 0;
    for (const auto &[id, a] : now) changed += a != before.at(id);
    if (all_active) {
      EXPECT_GT(changed, 0) << "step " << lmp->update->ntimestep;
      points++;
    } else {
      EXPECT_EQ(changed, 0) << "step " << lmp->update->ntimestep;
      between++;
    }
    EXPECT_NE(lmp->force->kspace->energy, energy) << "step " << lmp->update->ntimestep;
    before = now;
    energy = lmp->force->kspace->energy;
  }
  std::printf("%d synchronisation points, %d steps between\n", points, between);
  EXPECT_GE(points, 4);
  EXPECT_GE(between, 20);
}

// with every particle on one bin (dtmax below every particle's own step) each step is a
// synchronisation point, and the long-range kicks over the interval are those of every step:
// the same run as longrange every to round-off (this includes the long-range term in the
// predicted velocities)
class GravityLongRangeSyncSolver : public ::testing::TestWithParam<const char *> {};

TEST_P(GravityLongRangeSyncSolver, OneBinIsTheRunOfEveryStep)
{
  std::map<int, double> x[2], v[2];
  for (int k : {0, 1}) {
    auto lmp = open_lammps();
    hot_ball(lmp,
             std::string("courant 0.3 steps individual tend 0.1 dtmax 0.002 longrange ") +
                 (k ? "sync" : "every"),
             GetParam());
    commands(lmp, {"thermo_style custom step c_sum[12] f_gas[6]", "run 100000"});
    EXPECT_EQ(lmp->modify->get_fix_by_id("gas")->compute_vector(5), 1.0);    // one bin
    EXPECT_GE(lmp->update->ntimestep, 50);
    x[k] = per_atom(lmp, "x", 0);
    v[k] = per_atom(lmp, "v", 1);
  }
  double dx = 0.0, dv = 0.0, vmax = 0.0;
  for (const auto &[id, value] : x[0]) {
    dx = std::max(dx, std::fabs(x[1][id] - value));
    dv = std::max(dv, std::fabs(v[1][id] - v[0][id]));
    vmax = std::max(vmax, std::fabs(v[0][id]));
  }
  std::printf("largest differences: x %.3e, v %.3e (largest |v| %.3e)\n", dx, dv, vmax);
  EXPECT_LT(dx, 1e-12);
  EXPECT_LT(dv, 1e-10 * vmax);
  EXPECT_GT(vmax, 1e-2);
}

// a restart between two synchronisation points continues bit for bit: the long-range
// accelerations come back with the restart file, the interval from the particles' steps. MSM
// runs in a shrink-wrapped box, whose padding comes back with fix sph/astro's record (without
// it the continued run's box is narrower, MSM's grid finer, x 3e-9 apart after 30 steps)
TEST_P(GravityLongRangeSyncSolver, RestartBetweenSynchronisationPointsContinuesBitForBit)
{
  const std::string restart = "test_gravity_long_range.restart";
  const std::string fix = "courant 0.3 steps individual tend 0.4 longrange sync";
  std::map<int, double> x_ref, v_ref;
  LAMMPS_NS::bigint steps = 0;
  {
    auto lmp = open_lammps();
    hot_ball(lmp, fix, GetParam());
    auto *gas = lmp->modify->get_fix_by_id("gas");
    commands(lmp, {"run 1"});
    for (int step = 0; step < 50 && gas->compute_vector(4) == lmp->atom->natoms; step++)
      commands(lmp, {"run 1"});
    ASSERT_LT(gas->compute_vector(4), lmp->atom->natoms);    // the restart: between two points
    commands(lmp, {"write_restart " + restart, "run 60"});
    EXPECT_GE(gas->compute_vector(5), 2.0);
    steps = lmp->update->ntimestep;
    x_ref = per_atom(lmp, "x", 0);
    v_ref = per_atom(lmp, "v", 1);
  }
  auto lmp = open_lammps();
  commands(lmp,
           {"read_restart " + restart, "pair_coeff * * sph/astro",
            "pair_coeff * * sph/astro/gravity",
            std::string("kspace_style ") + GetParam() + "/sph/astro/gravity 1e-5",
            "fix gas all sph/astro " + fix,
            "fix hvar all sph/astro/h iterate hfact 1.2 tol 1e-10 margin 2.5",
            "neighbor " + num(0.3 * 1.2 * std::cbrt(0.25)) + " bin",
            "neigh_modify every 1 delay 0 check yes", "run 60"});
  EXPECT_EQ(lmp->update->ntimestep, steps);
  expect_same_x_v(lmp, x_ref, v_ref);
  std::remove(restart.c_str());
}

INSTANTIATE_TEST_SUITE_P(GravityLongRangeSync, GravityLongRangeSyncSolver,
                         ::testing::Values("msm", "pppm"));

TEST(GravityLongRangeSync, NeedsAGravitySolver)
{
  auto lmp = open_lammps();
  falling_ball(lmp, "30", "steps individual longrange sync");
  const auto err = error_of(lmp, "run 0");
  EXPECT_NE(err.find("fix sph/astro: longrange sync needs kspace_style msm/sph/astro/gravity, "
                     "pppm/sph/astro/gravity or tree/sph/astro/gravity in a periodic box "
                     "(kspace_style is none)"),
            std::string::npos)
      << err;
  // the tree in an open box needs none
  commands(lmp, {"kspace_style tree/sph/astro/gravity relative 0.002"});
  const auto tree = error_of(lmp, "run 0");
  EXPECT_NE(tree.find("(kspace_style is tree/sph/astro/gravity, open box); the tree in an open "
                      "box computes the active particles only"),
            std::string::npos)
      << tree;
}

TEST(GravityPair, RestartContinuesBitForBit)
{
  const std::string restart = "test_gravity.restart";
  std::map<int, double> x_ref, v_ref;
  const std::vector<std::string> run_setup = {"fix nve all nve", "timestep 0.01",
                                              "neigh_modify every 1 delay 0 check yes"};
  {
    auto lmp = open_lammps();
    cloud(lmp, false, 200, "sph/astro/gravity 3.0", "msm/sph/astro/gravity 1e-5");
    commands(lmp, {"velocity all create 0.1 777"});
    commands(lmp, run_setup);
    commands(lmp, {"run 20", "write_restart " + restart, "run 20"});
    x_ref = per_atom(lmp, "x", 0);
    v_ref = per_atom(lmp, "v", 1);
  }
  auto lmp = open_lammps();
  commands(
      lmp,
      {"read_restart " + restart, "sph/astro/state", "kspace_style msm/sph/astro/gravity 1e-5"});
  commands(lmp, run_setup);
  commands(lmp, {"run 20"});
  expect_same_x_v(lmp, x_ref, v_ref);
  std::remove(restart.c_str());
}

// read_restart of pair_style hybrid/overlay: LAMMPS restores the sub-styles and their settings
// but keeps no pair_coeff of hybrid styles in restart files, and a run stopped with "All pair
// coeffs are not set". read_restart warns, naming the sub-styles' pair_coeff; a gravity kspace
// style stops the run with an error saying so (before LAMMPS' check); with the pair_coeff
// given again the run goes on
TEST(GravityRestart, HybridPairCoeffsAreNamedAfterReadRestart)
{
  const std::string restart = "test_gravity_hybrid.restart", log = "test_gravity_hybrid.log";
  {
    auto lmp = open_lammps();
    falling_ball(lmp, "1.5", "courant 0.3");
    commands(lmp, {"run 1", "write_restart " + restart});
  }
  {
    auto lmp = open_lammps();
    commands(lmp, {"log " + log, "read_restart " + restart, "log none"});
    std::ifstream in(log);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const char *style : {"sph/astro", "sph/astro/gravity"})
      EXPECT_NE(text.find(std::string("pair_style hybrid/overlay: sub-style ") + style +
                          " restored from the restart file without pair_coeff"),
                std::string::npos)
          << text;
    EXPECT_NE(text.find("pair_coeff * * sph/astro/gravity"), std::string::npos) << text;
    commands(lmp, {"kspace_style msm/sph/astro/gravity 1e-5", "fix gas all sph/astro"});
    const std::string message = error_of(lmp, "run 0");
    EXPECT_NE(message.find("kspace_style msm/sph/astro/gravity: pair_style hybrid/overlay has no "
                           "pair_coeff for type 1"),
              std::string::npos)
        << message;
  }
  auto lmp = open_lammps();
  commands(lmp,
           {"read_restart " + restart, "pair_coeff * * sph/astro",
            "pair_coeff * * sph/astro/gravity", "kspace_style msm/sph/astro/gravity 1e-5",
            "fix gas all sph/astro"});
  EXPECT_EQ(error_of(lmp, "run 0"), "");
  std::remove(restart.c_str());
  std::remove(log.c_str());
}

// ----------------------------------------------------------------- bad input

TEST(GravityErrors, MissingGInUnitsReal)
{
  auto lmp = open_lammps();
  commands(lmp, {"units real", "region box block 0 1 0 1 0 1", "create_box 1 box"});
  const auto err = error_of(lmp, "pair_style sph/astro/gravity 5.0");
  EXPECT_NE(err.find("pair_style sph/astro/gravity: no default G for units real"),
            std::string::npos)
      << err;
  EXPECT_EQ(error_of(lmp, "pair_style sph/astro/gravity 5.0 G 6.6743e-11"), "");
}

TEST(GravityErrors, BadValues)
{
  auto lmp = open_lammps();
  commands(lmp, {"units lj", "region box block 0 1 0 1 0 1", "create_box 1 box"});
  auto err = error_of(lmp, "pair_style sph/astro/gravity -1.0");
  EXPECT_NE(err.find("cutoff -1.0 must be > 0"), std::string::npos) << err;
  err = error_of(lmp, "pair_style sph/astro/gravity 5.0 G -2");
  EXPECT_NE(err.find("G = -2 must be > 0"), std::string::npos) << err;
  err = error_of(lmp, "pair_style sph/astro/gravity 5.0 kernel lucy");
  EXPECT_NE(err.find("unknown kernel 'lucy'"), std::string::npos) << err;
  err = error_of(lmp, "pair_style sph/astro/gravity 5.0 kernel gaussian");
  EXPECT_NE(err.find("unknown kernel 'gaussian'"), std::string::npos) << err;
  err = error_of(lmp, "pair_style sph/astro/gravity 5.0 h 0");
  EXPECT_NE(err.find("softening length h = 0 must be > 0"), std::string::npos) << err;
  err = error_of(lmp, "pair_style sph/astro/gravity 5.0 soften 1");
  EXPECT_NE(err.find("unknown keyword 'soften'"), std::string::npos) << err;
}

TEST(GravityErrors, IncompatibleBoundaries)
{
  {
    auto lmp = open_lammps();
    cloud(lmp, false, 50, "sph/astro/gravity 3.0", "pppm/sph/astro/gravity 1e-4");
    const auto err = error_of(lmp, "run 0");
    EXPECT_NE(err.find("kspace_style pppm/sph/astro/gravity: boundary m m m is not periodic"),
              std::string::npos)
        << err;
  }
  {
    auto lmp = open_lammps();
    cloud(lmp, true, 50, "sph/astro/gravity 3.0", "msm/sph/astro/gravity 1e-4");
    const auto err = error_of(lmp, "run 0");
    EXPECT_NE(err.find("kspace_style msm/sph/astro/gravity: boundary p p p is periodic"),
              std::string::npos)
        << err;
  }
  {
    auto lmp = open_lammps();
    cloud(lmp, true, 50, "sph/astro/gravity 3.0", "");
    const auto err = error_of(lmp, "run 0");
    EXPECT_NE(err.find("without kspace needs non-periodic boundaries"), std::string::npos) << err;
  }
}

TEST(GravityErrors, KSpaceWithoutGravityPair)
{
  auto lmp = open_lammps();
  commands(lmp,
           {"units lj", "atom_style atomic", "boundary p p p", "region box block 0 10 0 10 0 10",
            "create_box 1 box", "create_atoms 1 random 50 4711 NULL", "mass 1 1.0",
            "pair_style lj/cut 2.5", "pair_coeff * * 1 1",
            "kspace_style pppm/sph/astro/gravity 1e-4"});
  const auto err = error_of(lmp, "run 0");
  EXPECT_NE(err.find("kspace_style pppm/sph/astro/gravity needs pair_style sph/astro/gravity"),
            std::string::npos)
      << err;
}

TEST(GravityErrors, NonGravityKSpace)
{
  for (const char *kspace : {"pppm 1e-4", "ewald 1e-4"}) {
    auto lmp = open_lammps();
    cloud(lmp, true, 50, "sph/astro/gravity 3.0", kspace);
    const auto err = error_of(lmp, "run 0");
    EXPECT_NE(err.find("pair_style sph/astro/gravity: kspace_style"), std::string::npos) << err;
    EXPECT_NE(err.find("is not a gravity solver"), std::string::npos) << err;
  }
}

// an absurd accuracy: MSM adjusts its cutoff to 485 for a grid spacing of 1.5, and its direct
// sums asked for a negative number of bytes ("Failed to allocate -67781918720 bytes"); the
// error names the accuracy, the cutoff and the memory. 1e-10 runs (cutoff 37.6)
TEST(GravityErrors, MSMAccuracyBeyondMemory)
{
  {
    auto lmp = open_lammps();
    cloud(lmp, false, 400, "sph/astro/gravity 3.0", "msm/sph/astro/gravity 1e-20");
    const auto err = error_of(lmp, "run 0");
    EXPECT_NE(err.find("kspace_style msm/sph/astro/gravity: its cutoff 485.561 spans 324 grid "
                       "spacings"),
              std::string::npos)
        << err;
    EXPECT_NE(err.find("the accuracy 1e-20 asks for that cutoff"), std::string::npos) << err;
  }
  auto lmp = open_lammps();
  cloud(lmp, false, 400, "sph/astro/gravity 3.0", "msm/sph/astro/gravity 1e-10");
  EXPECT_EQ(error_of(lmp, "run 0"), "");
}

TEST(GravityErrors, CutoffShorterThanSoftening)
{
  auto lmp = open_lammps();
  // (PPPM: MSM may itself enlarge a short cutoff to fit its grid)
  cloud(lmp, true, 50, "sph/astro/gravity 1.0", "pppm/sph/astro/gravity 1e-4");
  const auto err = error_of(lmp, "run 0");
  EXPECT_NE(err.find("pair_style sph/astro/gravity: cutoff 1 is shorter than the softening "
                     "support"),
            std::string::npos)
      << err;
}

TEST(GravityErrors, AtomWithoutSofteningLength)
{
  auto lmp = open_lammps();
  commands(lmp,
           {"units lj", "atom_style atomic", "atom_modify map array", "boundary f f f",
            "region box block 0 10 0 10 0 10", "create_box 1 box",
            "create_atoms 1 random 20 4711 NULL", "mass 1 1.0", "pair_style sph/astro/gravity 30",
            "pair_coeff * *"});
  auto err = error_of(lmp, "run 0");
  EXPECT_NE(err.find("has no softening length"), std::string::npos) << err;
  commands(lmp, {"pair_style sph/astro/gravity 30 h 0.5", "pair_coeff * *"});
  EXPECT_EQ(error_of(lmp, "run 0"), "");
}
