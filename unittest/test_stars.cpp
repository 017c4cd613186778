/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Stars and gas in one LAMMPS run: point masses (atoms of a type that is not SPH gas of pair
// sph/astro, moved by fix nve) feel and exert the package's self-gravity with the softening
// length of their type (pair_style sph/astro/gravity ... softening TYPES H), beside a gas ball
// moved by fix sph/astro. Total linear momentum with global steps (direct summation and the
// tree with every node opened: round-off; the tree's default criterion: its force error), the
// point masses' trajectories with individual steps against global steps, the kernel-softened
// force of a close pair against the closed form of the M4 kernel, the restart record and the
// errors for bad input.

#include "lammps_fixture.h"
#include "styles_fixture.h"

#include "force.h"
#include "pair.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace sph_astro_test;
using LAMMPS_NS::LAMMPS;

namespace {

// a gas ball of radius 1 and mass 1 with rho ~ 1/r (the Evrard sphere's start, n fcc cells
// across, 456 particles for n 6; u 0.05) and two point masses of mass 0.1 (type 2) inside it
// on crossing paths; gravity: "direct" or a kspace_style of the tree; fix: fix sph/astro's
// options; stars: the keywords of the point masses' softening
void ball_with_stars(const std::unique_ptr<LAMMPS> &lmp, const std::string &gravity,
                     const std::string &fix, const std::string &stars = "softening 2 0.05",
                     int n = 6)
{
  const double a = 2.0 / n;
  commands(lmp,
           {"units lj",
            "atom_style atomic",
            "atom_modify map array sort 0 0.0",
            "boundary m m m",
            "lattice fcc " + num(4.0 / (a * a * a)) + " origin 0.25 0.25 0.25",
            "region box block -1.05 1.05 -1.05 1.05 -1.05 1.05 units box",
            "create_box 2 box",
            "region ball sphere 0 0 0 1.0 units box",
            "create_atoms 1 region ball",
            "mass * 1.0",
            "reset_atoms id sort yes",
            "variable r atom sqrt(x*x+y*y+z*z)",
            "variable dx atom x*(sqrt(v_r)-1.0)",
            "variable dy atom y*(sqrt(v_r)-1.0)",
            "variable dz atom z*(sqrt(v_r)-1.0)",
            "displace_atoms all move v_dx v_dy v_dz units box",
            "create_atoms 2 single 0.3 0.05 0.0 units box",
            "create_atoms 2 single -0.25 -0.1 0.02 units box",
            "group gas type 1",
            "group stars type 2"});
  const double m = 1.0 / (lmp->atom->natoms - 2);
  const double rfloor = 0.5 * std::pow(a / std::sqrt(2.0), 1.5);
  commands(
      lmp,
      {"mass 1 " + num(m), "mass 2 0.1",
       "variable rf atom (v_r>" + num(rfloor) + ")*v_r+(v_r<=" + num(rfloor) + ")*" + num(rfloor),
       "variable hinit atom 1.2*(" + num(m) + "*2.0*PI*v_rf)^(1.0/3.0)",
       "pair_style hybrid/overlay sph/astro kernel m4 eos ideal $(5.0/3.0) viscosity "
       "classic 1.0 2.0 sph/astro/gravity 1000.0 " +
           stars,
       "pair_coeff 1 1 sph/astro", "pair_coeff * * sph/astro/gravity"});
  if (gravity != "direct") commands(lmp, {"kspace_style " + gravity});
  commands(lmp,
           {"fix gas gas sph/astro " + fix, "fix hvar gas sph/astro/h iterate hfact 1.2",
            "fix nve stars nve", "set group gas d_h v_hinit", "set group gas d_u 0.05",
            "velocity stars set 0.0 0.3 0.1 units box", "neighbor 0.03 bin",
            "neigh_modify every 1 delay 0 check yes", "compute sum all sph/astro/global",
            "thermo_style custom step c_sum[2] c_sum[3] c_sum[4] c_sum[12]"});
}

// total momentum (compute sph/astro/global: the state at the current time also for particles
// inside their individual steps)
std::vector<double> momentum(const std::unique_ptr<LAMMPS> &lmp)
{
  const auto sum = global_vector(lmp, "sum", 12);
  return {sum[PX], sum[PY], sum[PZ]};
}

// the largest change of a component of the total momentum over a run of nsteps, relative to
// the momentum scale sum_i m_i |v_i| at its end
double momentum_drift(const std::unique_ptr<LAMMPS> &lmp, int nsteps)
{
  commands(lmp, {"thermo " + std::to_string(nsteps), "run 0"});
  const auto start = momentum(lmp);
  commands(lmp, {"run " + std::to_string(nsteps)});
  const auto end = momentum(lmp);
  const double scale = momentum_scale(lmp);
  double worst = 0.0;
  for (int d = 0; d < 3; d++) worst = std::max(worst, std::fabs(end[d] - start[d]) / scale);
  return worst;
}

// positions of the two point masses (the last two atom IDs)
std::vector<double> stars_at(const std::unique_ptr<LAMMPS> &lmp)
{
  const auto x = per_atom(lmp, "x", 0), y = per_atom(lmp, "x", 1), z = per_atom(lmp, "x", 2);
  const int last = static_cast<int>(lmp->atom->natoms);
  std::vector<double> out;
  for (int id : {last - 1, last}) out.insert(out.end(), {x.at(id), y.at(id), z.at(id)});
  return out;
}

// dphi/dr of the M4 kernel's softened potential per h^-2 (Price & Monaghan 2007, MNRAS 374,
// 1347, appendix A), written out here as the reference of the force
double m4_force(double q)
{
  if (q < 1.0) return 4.0 / 3.0 * q - 1.2 * q * q * q + 0.5 * q * q * q * q;
  if (q < 2.0)
    return 8.0 / 3.0 * q - 3.0 * q * q + 1.2 * q * q * q - q * q * q * q / 6.0 -
        1.0 / (15.0 * q * q);
  return 1.0 / (q * q);
}

}    // namespace

// global steps: the point masses (fix nve) and the gas (fix sph/astro) take the same leapfrog
// steps and every pair force acts on both atoms: momentum to round-off with direct summation;
// the tree with every node opened sums each target's force on its own, to round-off too; with
// its default criterion the forces are not antisymmetric and momentum drifts by the tree's
// force error (measured 3.1e-6 of sum m |v| over 150 steps, against 1.1e-16 and 1.7e-16 for
// direct summation and the tree opened fully; bound 2x)
TEST(Stars, MomentumWithGlobalSteps)
{
  for (const std::string gravity : {"direct", "tree/sph/astro/gravity geometric 1e-6",
                                    "tree/sph/astro/gravity relative 0.002"}) {
    auto lmp = open_lammps();
    ball_with_stars(lmp, gravity, "courant 0.3 dtmax 0.005");
    const double drift = momentum_drift(lmp, 150);
    printf("%s: momentum drift %.3e of sum m |v| in 150 steps\n", gravity.c_str(), drift);
    if (gravity.find("relative") == std::string::npos)
      EXPECT_LT(drift, 1e-13) << gravity;
    else {
      EXPECT_LT(drift, 6e-6) << gravity;
      EXPECT_GT(drift, 1e-13) << gravity;    // (not round-off: the bound above is a reading)
    }
  }
}

// individual steps: the point masses are outside fix sph/astro's group, always active for the
// gravity styles (full forces at every LAMMPS step, as fix nve integrates them at every step),
// and the gas feels them. Their trajectories follow those of global steps within the
// difference the integration itself makes: the deviation from the global-step run is compared
// with that of a global-step run with dtmax halved (measured at t 0.6, where the gas takes two
// time bins: 2.55e-5 against 6.87e-5 with direct summation and with the tree; bound: 1x, the
// individual steps move the stars by less than a halved dtmax does)
TEST(Stars, IndividualStepsFollowGlobalSteps)
{
  const double tend = 0.6;
  auto run = [&](const std::string &gravity, const std::string &steps, double dtmax) {
    auto lmp = open_lammps();
    ball_with_stars(lmp, gravity,
                    "courant 0.3 dtmax " + num(dtmax) + " tend " + num(tend) + " steps " + steps);
    commands(lmp, {"thermo 1000", "run 100000"});
    EXPECT_NEAR(lmp->update->atime +
                    (lmp->update->ntimestep - lmp->update->atimestep) * lmp->update->dt,
                tend, 1e-12);
    return stars_at(lmp);
  };
  auto distance = [](const std::vector<double> &a, const std::vector<double> &b) {
    double worst = 0.0;
    for (int s = 0; s < 2; s++) {
      double d2 = 0.0;
      for (int d = 0; d < 3; d++) d2 += std::pow(a[3 * s + d] - b[3 * s + d], 2);
      worst = std::max(worst, std::sqrt(d2));
    }
    return worst;
  };
  for (const std::string gravity : {"direct", "tree/sph/astro/gravity relative 0.002"}) {
    const auto global = run(gravity, "global", 0.005);
    const auto global_half = run(gravity, "global", 0.0025);
    const auto individual = run(gravity, "individual", 0.005);
    const double d_steps = distance(individual, global), d_dt = distance(global_half, global);
    printf("%s: point masses at t %.2f: individual - global %.3e, global dtmax/2 - global %.3e\n",
           gravity.c_str(), tend, d_steps, d_dt);
    EXPECT_GT(d_dt, 0.0);
    EXPECT_LT(d_steps, d_dt) << gravity;
  }
}

// two point masses (types 2 and 3, softening 0.4 and 0.2) closer than the kernel support: the
// force is G m_i m_j [phi'(r, h_2) + phi'(r, h_3)] / 2 with the M4 closed form; a type without
// softening takes the pair style's fixed h; direct summation, the tree with every node opened
// and the restart record give the same
TEST(Stars, SofteningPerTypeEntersTheForce)
{
  const double r = 0.3, m2 = 0.7, m3 = 0.2, G = 1.3;
  auto force = [&](const std::string &kspace, const std::string &softening, bool restart) {
    const bool msm = kspace.rfind("msm", 0) == 0;    // (its split: the pair's cutoff)
    {
      auto lmp = open_lammps();
      commands(lmp,
               {"units lj", "atom_style atomic", "atom_modify map array", "boundary m m m",
                "region box block -2 2 -2 2 -2 2", "create_box 3 box",
                "create_atoms 2 single 0 0 0 units box",
                "create_atoms 3 single " + num(r) + " 0 0 units box",
                "create_atoms 1 single 1.5 1.5 1.5 units box", "mass 1 1e-20", "mass 2 " + num(m2),
                "mass 3 " + num(m3),
                "pair_style sph/astro/gravity " + std::string(msm ? "1.0" : "100.0") + " G " +
                    num(G) + " " + softening,
                "pair_coeff * *"});
      if (!kspace.empty()) commands(lmp, {"kspace_style " + kspace});
      if (!restart) {
        commands(lmp, {"run 0"});
        return per_atom(lmp, "f", 0).at(1);
      }
      commands(lmp, {"write_restart test_stars.restart"});
    }
    // (the settings, the softening of each type among them, from the restart file; one LAMMPS
    // instance at a time: deleting one unloads the plugin)
    auto lmp = open_lammps();
    commands(lmp, {"read_restart test_stars.restart", "run 0"});
    std::remove("test_stars.restart");
    return per_atom(lmp, "f", 0).at(1);
  };
  // M4 dphi/dr = fforce(r/h)/h^2, the mean of the two softening lengths' values
  auto expected = [&](double h2, double h3) {
    return G * m2 * m3 * 0.5 * (m4_force(r / h2) / (h2 * h2) + m4_force(r / h3) / (h3 * h3));
  };
  const double newton = G * m2 * m3 / (r * r);
  const double f_types = force("", "h 0.01 softening 2 0.4 softening 3 0.2", false);
  EXPECT_NEAR(f_types, expected(0.4, 0.2), 1e-13 * newton);
  EXPECT_LT(f_types, 0.9 * newton);    // softened: well below Newton's force
  // a range, and the fixed h for the type left out
  EXPECT_NEAR(force("", "h 0.2 softening 1*2 0.4", false), expected(0.4, 0.2), 1e-13 * newton);
  // the tree with every node opened, and the settings after read_restart
  EXPECT_NEAR(force("tree/sph/astro/gravity geometric 1e-6",
                    "h 0.01 softening 2 0.4 softening 3 0.2", false),
              expected(0.4, 0.2), 1e-12 * newton);
  EXPECT_NEAR(force("", "h 0.01 softening 2 0.4 softening 3 0.2", true), expected(0.4, 0.2),
              1e-13 * newton);
  // the short range of MSM (neighbour-list pairs; cutoff 1.0 covers the supports 2 h): the
  // softened pair plus MSM's long range, within MSM's accuracy
  const double f_msm =
      force("msm/sph/astro/gravity 1e-6", "h 0.01 softening 2 0.4 softening 3 0.2", false);
  printf("MSM: relative force difference from the closed form %.3e\n",
         std::fabs(f_msm - expected(0.4, 0.2)) / newton);
  EXPECT_NEAR(f_msm, expected(0.4, 0.2), 1e-6 * newton);    // (measured 3e-11)
  // a later softening of a type replaces an earlier one
  EXPECT_NEAR(force("", "h 0.01 softening 2*3 0.05 softening 2 0.4 softening 3 0.2", false),
              expected(0.4, 0.2), 1e-13 * newton);
  // beyond both supports: Newton's force
  EXPECT_NEAR(force("", "h 0.01 softening 2*3 0.1", false), newton, 1e-13 * newton);
}

// the gas's softening is its h: softening for a gas type is refused, as are a type out of range
// and a length that is not positive
TEST(Stars, SofteningErrorsNameTheCommandAndTheValue)
{
  auto lmp = open_lammps();
  commands(lmp,
           {"units lj", "atom_style atomic", "atom_modify map array", "boundary m m m",
            "region box block -2 2 -2 2 -2 2", "create_box 2 box",
            "create_atoms 1 single 0 0 0 units box", "create_atoms 2 single 1 0 0 units box",
            "mass * 1.0"});
  auto expect_error = [&](const std::string &line, const std::string &fragment) {
    const std::string message = error_of(lmp, line);
    EXPECT_NE(message.find(fragment), std::string::npos)
        << line << "\nmessage: " << message << "\nexpected: " << fragment;
  };
  expect_error("pair_style sph/astro/gravity 10.0 softening 2 -0.1",
               "pair_style sph/astro/gravity: softening 2 -0.1: the length must be finite and > 0");
  expect_error("pair_style sph/astro/gravity 10.0 softening 3 0.1",
               "pair_style sph/astro/gravity: softening 3 0.1: atom type 3 is out of range 1-2");
  expect_error("pair_style sph/astro/gravity 10.0 softening 2", "softening");
  commands(lmp,
           {"pair_style hybrid/overlay sph/astro sph/astro/gravity 10.0 softening 1*2 0.1",
            "pair_coeff 1 1 sph/astro", "pair_coeff * * sph/astro/gravity", "fix gas all sph/astro",
            "set type 1 d_h 0.5", "group gas type 1"});
  expect_error("run 0", "softening for type 1: type 1 is SPH gas of pair sph/astro");
  // fix sph/astro moves the gas only: a point mass in its group is refused
  commands(lmp,
           {"pair_style hybrid/overlay sph/astro sph/astro/gravity 10.0 softening 2 0.1",
            "pair_coeff 1 1 sph/astro", "pair_coeff * * sph/astro/gravity"});
  expect_error("run 0", "fix sph/astro: group all holds 1 atoms of types that are not SPH gas");
  // (and with the gas's group it runs: the error above came from the group)
  commands(lmp,
           {"unfix gas", "fix gas gas sph/astro", "group stars type 2", "fix stars stars nve"});
  EXPECT_EQ(error_of(lmp, "run 0"), "");
}
