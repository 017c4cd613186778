/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// LAMMPS-driven tests of kspace_style tree/sph/astro/gravity: the force accuracy with the
// defaults on the Evrard sphere and a Plummer sphere against direct summation (and that a
// looser criterion misses it), the limit of opening every node against pair
// sph/astro/gravity's direct summation with the adaptive-softening terms and, in a periodic
// box (TreePM), against the pair's short range with PPPM; energy, virial and per-atom energy,
// individual timesteps (active particles only), restart bit for bit with the relative
// criterion's accelerations, and the errors for bad input.

#include "lammps_fixture.h"

#include "tree_sph_astro_gravity.h"

#include "compute.h"
#include "force.h"
#include "kspace.h"
#include "pair.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

using namespace sph_astro_test;
using LAMMPS_NS::LAMMPS;

namespace {

// the Evrard sphere's start (examples/evrard): fcc lattice of n cells across cut to the unit
// sphere, stretched to rho ~ 1/r; softening length hfact (m/rho)^(1/3) in d_h
void evrard(const std::unique_ptr<LAMMPS> &lmp, int n)
{
  const double a = 2.0 / n;
  commands(lmp,
           {"units lj", "atom_style atomic", "atom_modify map array sort 0 0.0", "boundary m m m",
            "lattice fcc " + num(4.0 / (a * a * a)) + " origin 0.25 0.25 0.25",
            "region box block -1.05 1.05 -1.05 1.05 -1.05 1.05 units box", "create_box 1 box",
            "region ball sphere 0 0 0 1.0 units box", "create_atoms 1 region ball"});
  const double m = 1.0 / lmp->atom->natoms;
  const double rfloor = 0.5 * std::pow(a / std::sqrt(2.0), 1.5);
  commands(
      lmp,
      {"mass 1 " + num(m), "reset_atoms id sort yes", "variable r atom sqrt(x*x+y*y+z*z)",
       "variable dx atom x*(sqrt(v_r)-1.0)", "variable dy atom y*(sqrt(v_r)-1.0)",
       "variable dz atom z*(sqrt(v_r)-1.0)", "displace_atoms all move v_dx v_dy v_dz units box",
       "variable rf atom (v_r>" + num(rfloor) + ")*v_r+(v_r<=" + num(rfloor) + ")*" + num(rfloor),
       "variable hinit atom 1.2*(" + num(m) + "*2.0*PI*v_rf)^(1.0/3.0)", "sph/astro/state",
       "set group all d_h v_hinit", "pair_style sph/astro/gravity 1000.0", "pair_coeff * *",
       "neighbor 0.01 bin"});
}

// a Plummer sphere (a = M = 1) of n particles cut at 10 a, softening length 0.01
void plummer(const std::unique_ptr<LAMMPS> &lmp, int n)
{
  commands(lmp,
           {"units lj", "atom_style atomic", "atom_modify map array sort 0 0.0", "boundary m m m",
            "region box block -10 10 -10 10 -10 10", "create_box 1 box"});
  std::mt19937_64 rng(4711);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> x;
  while (static_cast<int>(x.size()) < 3 * n) {
    const double r = 1.0 / std::sqrt(std::pow(u(rng), -2.0 / 3.0) - 1.0);
    if (r >= 10.0) continue;
    const double c = 2.0 * u(rng) - 1.0, p = 2.0 * M_PI * u(rng), s = std::sqrt(1.0 - c * c);
    x.insert(x.end(), {r * s * std::cos(p), r * s * std::sin(p), r * c});
  }
  std::vector<int> type(n, 1);
  lammps_create_atoms(lmp.get(), n, nullptr, type.data(), x.data(), nullptr, nullptr, 0);
  commands(lmp,
           {"mass 1 " + num(1.0 / n), "pair_style sph/astro/gravity 1000.0 h 0.01",
            "pair_coeff * *", "neighbor 0.01 bin"});
}

// per-particle relative force errors |F - F_ref| / |F_ref| against compute
// sph/astro/gravity/direct (computed once, "ref"): their RMS and 99th percentile
std::pair<double, double> force_errors(const std::unique_ptr<LAMMPS> &lmp)
{
  auto *ref = lmp->modify->get_compute_by_id("ref");
  ref->compute_peratom();
  std::vector<double> rel;
  for (int i = 0; i < lmp->atom->nlocal; i++) {
    double d2 = 0.0, f2 = 0.0;
    for (int d = 0; d < 3; d++) {
      const double diff = lmp->atom->f[i][d] - ref->array_atom[i][d];
      d2 += diff * diff;
      f2 += ref->array_atom[i][d] * ref->array_atom[i][d];
    }
    rel.push_back(std::sqrt(d2 / f2));
  }
  double s2 = 0.0;
  for (double e : rel) s2 += e * e;
  std::sort(rel.begin(), rel.end());
  return {std::sqrt(s2 / rel.size()), rel[static_cast<size_t>(0.99 * rel.size())]};
}

// forces of a kspace setting (two evaluations: the relative criterion needs the first's
// accelerations)
std::pair<double, double> tree_errors(void (*scene)(const std::unique_ptr<LAMMPS> &, int), int n,
                                      const std::string &kspace)
{
  auto lmp = open_lammps();
  scene(lmp, n);
  commands(lmp,
           {"kspace_style " + kspace, "compute ref all sph/astro/gravity/direct",
            "thermo_style custom step pe", "run 0", "run 0"});
  return force_errors(lmp);
}

}    // namespace

// the bars of the defaults: RMS <= 1e-3, 99th percentile <= 1e-2 (measured, relative 0.002:
// Evrard n 16 3.1e-4 / 7.5e-4, Plummer 10 000 4.7e-4 / 1.3e-3; relative 0.05: 2.3e-3 / 5.6e-3
// and 4.9e-3 / 1.7e-2; geometric 0.9: 2.5e-3 / 6.2e-3 and 7.1e-3 / 2.4e-2)
TEST(TreeGravity, DefaultCriterionMeetsTheForceBars)
{
  for (auto [scene, n] : {std::make_pair(&evrard, 16), std::make_pair(&plummer, 10000)}) {
    const auto [rms, p99] = tree_errors(scene, n, "tree/sph/astro/gravity relative 0.002");
    EXPECT_LT(rms, 1e-3);
    EXPECT_LT(p99, 1e-2);
    // ... and a looser criterion does not meet them
    const auto [rms_loose, p99_loose] =
        tree_errors(scene, n, "tree/sph/astro/gravity relative 0.05");
    EXPECT_GT(rms_loose, 1e-3);
    const auto [rms_wide, p99_wide] = tree_errors(scene, n, "tree/sph/astro/gravity geometric 0.9");
    EXPECT_GT(rms_wide, 1e-3);
  }
}

// opening every node is pair sph/astro/gravity's direct summation, with the adaptive-softening
// (zeta) terms of a gas whose h follows its density
TEST(TreeGravity, OpeningEveryNodeIsDirectSummation)
{
  std::map<int, double> f_direct[3], f_tree[3];
  double e_direct = 0.0, e_tree = 0.0;
  for (const bool tree : {false, true}) {
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
              "region ball sphere 0 0 0 2.5 units box",
              "create_atoms 1 region ball",
              "displace_atoms all random 0.05 0.05 0.05 4711 units box",
              "mass 1 0.25",
              "pair_style hybrid/overlay sph/astro kernel m4 eos ideal 1.6666667 viscosity "
              "classic 1.0 2.0 sph/astro/gravity 30",
              "pair_coeff * * sph/astro",
              "pair_coeff * * sph/astro/gravity",
              "fix gas all sph/astro",
              "fix hvar all sph/astro/h iterate hfact 1.2",
              "set group all d_h " + num(h),
              "set group all d_u 0.05",
              "neighbor " + num(0.3 * h) + " bin",
              "thermo_style custom step pe"});
    if (tree) commands(lmp, {"kspace_style tree/sph/astro/gravity geometric 1e-6"});
    commands(lmp, {"run 0"});
    // (the forces include pair sph/astro's pressure force, the same in both runs)
    for (int d = 0; d < 3; d++) (tree ? f_tree : f_direct)[d] = per_atom(lmp, "f", d);
    (tree ? e_tree : e_direct) =
        lmp->force->pair->eng_vdwl + (lmp->force->kspace ? lmp->force->kspace->energy : 0.0);
    if (tree) {
      int dim;
      EXPECT_NE(lmp->force->pair_match("sph/astro/gravity", 1, 0)->extract_peratom("zeta", dim),
                nullptr);
    }
  }
  double fmax = 0.0;
  for (const auto &[id, f] : f_direct[0]) fmax = std::max(fmax, std::fabs(f));
  for (int d = 0; d < 3; d++)
    for (const auto &[id, f] : f_direct[d]) EXPECT_NEAR(f_tree[d][id], f, 1e-12 * fmax);
  EXPECT_NEAR(e_tree, e_direct, 1e-12 * std::fabs(e_direct));
}

// energy, virial and per-atom energies of the tree against direct summation
TEST(TreeGravity, EnergyVirialAndPerAtomEnergy)
{
  double e[2], p[2], peatom[2];
  for (const bool tree : {false, true}) {
    auto lmp = open_lammps();
    plummer(lmp, 3000);
    if (tree) commands(lmp, {"kspace_style tree/sph/astro/gravity geometric 0.3"});
    commands(lmp,
             {"compute pea all pe/atom", "compute pesum all reduce sum c_pea",
              "thermo_style custom step pe press c_pesum", "run 0"});
    e[tree] = lmp->force->pair->eng_vdwl + (tree ? lmp->force->kspace->energy : 0.0);
    auto *press = lmp->modify->get_compute_by_id("thermo_press");
    press->compute_scalar();
    p[tree] = press->scalar;
    auto *sum = lmp->modify->get_compute_by_id("pesum");
    peatom[tree] = sum->compute_scalar();
  }
  EXPECT_NEAR(e[1], e[0], 1e-4 * std::fabs(e[0]));
  EXPECT_NEAR(p[1], p[0], 1e-3 * std::fabs(p[0]));
  EXPECT_NEAR(peatom[1], e[1], 1e-12 * std::fabs(e[1]));
}

// individual timesteps: only the active particles are targets (the energy steps aside); with
// every node opened the run is that of direct summation to round-off, with the default
// criterion within the tree's error
TEST(TreeGravity, IndividualStepsEvaluateTheActiveParticles)
{
  std::map<int, double> x[3];
  double energy_error[3];
  const char *kspace[3] = {"", "tree/sph/astro/gravity geometric 1e-6",
                           "tree/sph/astro/gravity relative 0.002"};
  for (int run = 0; run < 3; run++) {
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
              "region ball sphere 0 0 0 2.5 units box",
              "create_atoms 1 region ball",
              "displace_atoms all random 0.05 0.05 0.05 4711 units box",
              "mass 1 0.25",
              "variable r atom sqrt(x*x+y*y+z*z)",
              "pair_style hybrid/overlay sph/astro kernel m4 eos ideal 1.6666667 viscosity "
              "classic 1.0 2.0 sph/astro/gravity 30",
              "pair_coeff * * sph/astro",
              "pair_coeff * * sph/astro/gravity",
              "fix gas all sph/astro steps individual",
              "fix hvar all sph/astro/h iterate hfact 1.2",
              "set group all d_h " + num(h),
              "variable u0 atom 0.02+0.2*v_r",
              "set group all d_u v_u0",
              "neighbor " + num(0.3 * h) + " bin",
              "compute sum all sph/astro/global",
              "thermo_style custom step c_sum[12]",
              "thermo 1000"});
    if (run > 0) commands(lmp, {std::string("kspace_style ") + kspace[run]});
    commands(lmp, {"run 40"});
    x[run] = per_atom(lmp, "x", 0);
    energy_error[run] = global_vector(lmp, "sum", 12)[11];
    if (run > 0) {
      // (static_cast: the plugin's classes have no type information in this program)
      ASSERT_STREQ(lmp->force->kspace_style, "tree/sph/astro/gravity");
      auto *tree = static_cast<LAMMPS_NS::TreeSPHAstroGravity *>(lmp->force->kspace);
      // targets per evaluation: the active particles, fewer than all (thermo every 1000)
      EXPECT_GT(tree->targets_per_evaluation(), 0.0);
      EXPECT_LT(tree->targets_per_evaluation(), 0.9 * lmp->atom->natoms);    // (measured 0.73)
    }
  }
  double exact = 0.0, approx = 0.0;
  for (const auto &[id, v] : x[0]) {
    exact = std::max(exact, std::fabs(x[1][id] - v));
    approx = std::max(approx, std::fabs(x[2][id] - v));
  }
  EXPECT_LT(exact, 1e-12);
  EXPECT_LT(approx, 1e-3);    // (measured 1.7e-4 in a ball of radius 2.5)
  EXPECT_NEAR(energy_error[1], energy_error[0], 1e-12);
  EXPECT_NEAR(energy_error[2], energy_error[0], 1e-4);
}

// write_restart and read_restart at a re-neighbouring: the continued run is the uninterrupted
// one bit for bit (the tree's structure and the relative criterion's accelerations come back)
TEST(TreeGravity, RestartContinuesBitForBit)
{
  const std::string restart = "test_tree_gravity.restart";
  const std::vector<std::string> run_setup = {"fix nve all nve", "timestep 0.002",
                                              "neigh_modify every 1 delay 0 check no"};
  std::map<int, double> x_ref, v_ref;
  {
    auto lmp = open_lammps();
    plummer(lmp, 2000);
    commands(
        lmp,
        {"kspace_style tree/sph/astro/gravity relative 0.002", "velocity all create 0.01 777"});
    commands(lmp, run_setup);
    commands(lmp, {"run 10", "write_restart " + restart, "run 10"});
    x_ref = per_atom(lmp, "x", 0);
    v_ref = per_atom(lmp, "v", 1);
  }
  auto lmp = open_lammps();
  commands(lmp, {"read_restart " + restart, "kspace_style tree/sph/astro/gravity relative 0.002"});
  commands(lmp, run_setup);
  commands(lmp, {"run 10"});
  auto x = per_atom(lmp, "x", 0), v = per_atom(lmp, "v", 1);
  ASSERT_EQ(x.size(), x_ref.size());
  for (const auto &[id, value] : x_ref) {
    EXPECT_EQ(x[id], value) << "atom " << id;
    EXPECT_EQ(v[id], v_ref.at(id)) << "atom " << id;
  }
  std::remove(restart.c_str());
}

// periodic boxes (TreePM): with every node opened the tree's short range is pair
// sph/astro/gravity's with the same PPPM (grid and g_ewald from the same accuracy and cutoff);
// with the default criterion the forces meet the Ewald reference within PPPM's and the tree's
// errors
TEST(TreeGravity, PeriodicTreePMIsThePairsShortRangeWithPPPM)
{
  std::map<int, double> f[3][3];
  double energy[3], pressure[3];
  const char *kspace[3] = {"pppm/sph/astro/gravity 1e-5",
                           "tree/sph/astro/gravity geometric 1e-6 pm 1e-5",
                           "tree/sph/astro/gravity relative 0.002 pm 1e-5"};
  std::pair<double, double> errors[3];
  for (int run = 0; run < 3; run++) {
    auto lmp = open_lammps();
    // a clustered periodic box: a Plummer sphere of scale 1 in a box of side 10
    commands(lmp,
             {"units lj", "atom_style atomic", "atom_modify map array sort 0 0.0", "boundary p p p",
              "region box block -5 5 -5 5 -5 5", "create_box 1 box"});
    std::mt19937_64 rng(4711);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<double> x;
    while (x.size() < 3 * 2000) {
      const double r = 1.0 / std::sqrt(std::pow(u(rng), -2.0 / 3.0) - 1.0);
      if (r >= 4.5) continue;
      const double c = 2.0 * u(rng) - 1.0, p = 2.0 * M_PI * u(rng), s = std::sqrt(1.0 - c * c);
      x.insert(x.end(), {r * s * std::cos(p), r * s * std::sin(p), r * c});
    }
    std::vector<int> type(2000, 1);
    lammps_create_atoms(lmp.get(), 2000, nullptr, type.data(), x.data(), nullptr, nullptr, 0);
    commands(lmp,
             {"mass 1 0.0005", "pair_style sph/astro/gravity 2.0 h 0.05", "pair_coeff * *",
              "neighbor 0.1 bin", "neigh_modify one 5000 page 50000",
              std::string("kspace_style ") + kspace[run],
              "compute ref all sph/astro/gravity/direct", "thermo_style custom step pe press",
              "run 0", "run 0"});
    for (int d = 0; d < 3; d++) f[run][d] = per_atom(lmp, "f", d);
    energy[run] = lmp->force->pair->eng_vdwl + lmp->force->kspace->energy;
    auto *press = lmp->modify->get_compute_by_id("thermo_press");
    press->compute_scalar();
    pressure[run] = press->scalar;
    errors[run] = force_errors(lmp);
  }
  double fmax = 0.0;
  for (const auto &[id, v] : f[0][0]) fmax = std::max(fmax, std::fabs(v));
  for (int d = 0; d < 3; d++)
    for (const auto &[id, v] : f[0][d]) EXPECT_NEAR(f[1][d][id], v, 1e-12 * fmax);
  EXPECT_NEAR(energy[1], energy[0], 1e-12 * std::fabs(energy[0]));
  EXPECT_NEAR(pressure[1], pressure[0], 1e-10 * std::fabs(pressure[0]));
  // the default criterion: within the tree's error of the PPPM run, both near the reference
  EXPECT_LT(errors[0].first, 1e-3);
  EXPECT_LT(errors[2].first, 2e-3);
  EXPECT_NEAR(energy[2], energy[0], 1e-4 * std::fabs(energy[0]));
}

// ----------------------------------------------------------------- bad input

TEST(TreeGravityErrors, BadSettings)
{
  auto lmp = open_lammps();
  commands(lmp, {"units lj", "boundary m m m", "region box block 0 1 0 1 0 1", "create_box 1 box"});
  const std::string style = "kspace_style tree/sph/astro/gravity ";
  auto err = error_of(lmp, style + "relative 0");
  EXPECT_NE(err.find("relative criterion alpha = 0 must be in (0, 1)"), std::string::npos) << err;
  err = error_of(lmp, style + "geometric 1.5");
  EXPECT_NE(err.find("opening angle theta = 1.5 must be in (0, 1]"), std::string::npos) << err;
  err = error_of(lmp, style + "barnes 0.5");
  EXPECT_NE(err.find("unknown opening criterion 'barnes'; allowed: relative ALPHA"),
            std::string::npos)
      << err;
  err = error_of(lmp, style + "geometric 0.5 theta 0.4");
  EXPECT_NE(err.find("keyword theta belongs to the relative criterion"), std::string::npos) << err;
  err = error_of(lmp, style + "relative 0.002 leaf 0");
  EXPECT_NE(err.find("leaf = 0 must be in 1..1024"), std::string::npos) << err;
  err = error_of(lmp, style + "relative 0.002 group 10000");
  EXPECT_NE(err.find("group = 10000 must be in 1..4096"), std::string::npos) << err;
  err = error_of(lmp, style + "relative 0.002 pm 0");
  EXPECT_NE(err.find("pm accuracy = 0 must be in (0, 1)"), std::string::npos) << err;
  err = error_of(lmp, style + "relative 0.002 quadrupole yes");
  EXPECT_NE(err.find("unknown keyword 'quadrupole'"), std::string::npos) << err;
  err = error_of(lmp, style + "relative");
  EXPECT_NE(err.find("Illegal kspace_style tree/sph/astro/gravity command: missing argument"),
            std::string::npos)
      << err;
}

TEST(TreeGravityErrors, NeedsOpenBoundariesAndTheGravityPair)
{
  {
    auto lmp = open_lammps();
    commands(lmp,
             {"units lj", "boundary p p p", "region box block 0 10 0 10 0 10", "create_box 1 box",
              "create_atoms 1 random 50 4711 NULL", "mass 1 1.0",
              "pair_style sph/astro/gravity 3.0 h 0.5", "pair_coeff * *",
              "kspace_style tree/sph/astro/gravity relative 0.002"});
    commands(lmp, {"change_box all boundary p p m"});
    const auto err = error_of(lmp, "run 0");
    EXPECT_NE(err.find("kspace_style tree/sph/astro/gravity: boundary p p m is periodic along "
                       "some axes only"),
              std::string::npos)
        << err;
  }
  {
    auto lmp = open_lammps();
    commands(lmp,
             {"units lj", "boundary m m m", "region box block 0 10 0 10 0 10", "create_box 1 box",
              "create_atoms 1 random 50 4711 NULL", "mass 1 1.0", "pair_style lj/cut 2.5",
              "pair_coeff * * 1 1", "kspace_style tree/sph/astro/gravity relative 0.002"});
    const auto err = error_of(lmp, "run 0");
    EXPECT_NE(err.find("kspace_style tree/sph/astro/gravity needs pair_style sph/astro/gravity"),
              std::string::npos)
        << err;
  }
  {
    auto lmp = open_lammps();
    commands(lmp,
             {"units lj", "boundary m m m", "region box block 0 10 0 10 0 10", "create_box 1 box",
              "create_atoms 1 random 50 4711 NULL", "mass 1 1.0",
              "pair_style sph/astro/gravity 3.0", "pair_coeff * *",
              "kspace_style tree/sph/astro/gravity relative 0.002"});
    const auto err = error_of(lmp, "run 0");
    EXPECT_NE(err.find("has no softening length"), std::string::npos) << err;
  }
}
