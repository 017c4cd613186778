/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// LAMMPS-driven tests of fix sph/astro/sink and compute sph/astro/sink: accretion keeps the
// total mass, momentum and angular momentum (orbital + the sinks' spin) to round-off, the same
// accretion on 1 and 2 MPI ranks, a restart that continues bit for bit, the sinks' timestep
// bound, sink creation in a cold collapsing sphere, and the errors of bad input. Run on 1 rank
// and (sink_mpi) on 2: the tests compare against a run on rank 0 alone.

#include "lammps_fixture.h"

#include "comm.h"
#include "compute.h"
#include "fix.h"
#include "force.h"
#include "modify.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

using namespace sph_astro_test;

namespace {

using Lammps = std::unique_ptr<LAMMPS_NS::LAMMPS>;

const double H0 = 1.2 * std::cbrt(0.25);    // h of the fcc lattice (rho = 1)

Lammps open_on(MPI_Comm comm)
{
  const char *args[] = {"sph_astro_test", "-log", "none", "-screen", "none", "-nocite"};
  Lammps lmp(new LAMMPS_NS::LAMMPS(6, const_cast<char **>(args), comm));
  lmp->input->one("plugin load " SPH_ASTRO_PLUGIN);
  return lmp;
}

// a ball of gas (type 1, fcc, rho = 1, radius 2.5) in vacuum with two sinks (type 2, masses
// 5 and 3) whose accretion radii overlap, velocities random; the sinks feel no force (pair
// zero), the gas its SPH forces (variable h). Sinks: fix nve and fix sph/astro/sink ID sink;
// compute sph/astro/sink ID s
void ball_with_sinks(const Lammps &lmp, const std::string &sink_args = "racc 0.8 G 1.0")
{
  commands(lmp,
           {"units lj", "atom_style atomic", "atom_modify map array sort 0 0.0", "boundary s s s",
            "lattice fcc 4.0", "region box block -3 3 -3 3 -3 3", "create_box 2 box",
            "fix mass all property/atom rmass ghost yes", "region ball sphere 0 0 0 2.5 units box",
            "create_atoms 1 region ball", "displace_atoms all random 0.04 0.04 0.04 4711 units box",
            "create_atoms 2 single 0.1 0.05 -0.02 units box",
            "create_atoms 2 single 0.75 -0.1 0.1 units box", "set type 1 mass 0.25",
            "set type 2 mass 5.0", "set atom 251 mass 3.0", "group gas type 1",
            "group sinks type 2",
            // (velocities from the positions: the same bits on any number of ranks,
            // which velocity create's scaling to a temperature does not give)
            "variable vx atom 0.05*sin(7.1*x+3.3*y+1.7*z)",
            "variable vy atom 0.05*sin(2.3*x-5.9*y+4.1*z)",
            "variable vz atom 0.05*sin(-3.7*x+1.3*y+6.7*z)", "velocity gas set v_vx v_vy v_vz",
            "velocity sinks set 0.02 -0.01 0.03",
            "pair_style hybrid/overlay sph/astro kernel m4 eos ideal 1.6666667 viscosity "
            "classic 1.0 2.0 zero 1.0",
            "pair_coeff * * zero", "pair_coeff 1 1 sph/astro", "fix gas gas sph/astro courant 0.3",
            "fix hvar gas sph/astro/h iterate hfact 1.2", "fix nve sinks nve",
            "fix sink sinks sph/astro/sink " + sink_args, "set group gas d_h " + num(H0),
            "set group gas d_u 1.0", "neighbor 0.2 bin", "neigh_modify every 1 delay 0 check yes",
            "compute s sinks sph/astro/sink sink", "thermo_style custom step atoms f_sink[3]"});
}

struct Totals {
  double mass = 0, p[3] = {0, 0, 0}, L[3] = {0, 0, 0};
  double pscale = 0, Lscale = 0;    // sum m|v|, sum m|x||v|
  double natoms = 0;
};

// the sinks' rows of compute s (evaluated now): ID, mass, spin (3), accreted mass, rate
std::vector<std::vector<double>> sink_rows(const Lammps &lmp)
{
  auto *c = lmp->modify->get_compute_by_id("s");
  c->compute_array();
  std::vector<std::vector<double>> rows;
  for (int k = 0; k < c->size_array_rows; k++)
    rows.emplace_back(c->array[k], c->array[k] + c->size_array_cols);
  return rows;
}

// total mass, momentum and angular momentum about the origin (orbital + spin) over all ranks
Totals totals(const Lammps &lmp)
{
  const auto *atom = lmp->atom;
  double local[11] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}, all[11];
  for (int i = 0; i < atom->nlocal; i++) {
    const double m = atom->rmass[i], *x = atom->x[i], *v = atom->v[i];
    local[0] += m;
    for (int d = 0; d < 3; d++) local[1 + d] += m * v[d];
    local[4] += m * (x[1] * v[2] - x[2] * v[1]);
    local[5] += m * (x[2] * v[0] - x[0] * v[2]);
    local[6] += m * (x[0] * v[1] - x[1] * v[0]);
    const double vn = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    local[7] += m * vn;
    local[8] += m * vn * std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    local[9] += 1.0;
  }
  MPI_Allreduce(local, all, 11, MPI_DOUBLE, MPI_SUM, lmp->world);
  Totals t;
  t.mass = all[0];
  for (int d = 0; d < 3; d++) {
    t.p[d] = all[1 + d];
    t.L[d] = all[4 + d];
  }
  for (const auto &row : sink_rows(lmp))
    for (int d = 0; d < 3; d++) t.L[d] += row[2 + d];
  t.pscale = all[7];
  t.Lscale = all[8];
  t.natoms = all[9];
  return t;
}

double fix_value(const Lammps &lmp, const char *id, int index)
{
  return lmp->modify->get_fix_by_id(id)->compute_vector(index);
}

void expect_conserved(const Totals &a, const Totals &b, double tol, const char *what)
{
  EXPECT_LT(std::fabs(b.mass - a.mass), tol * a.mass) << what;
  for (int d = 0; d < 3; d++) {
    EXPECT_LT(std::fabs(b.p[d] - a.p[d]), tol * a.pscale) << what << " momentum " << d;
    EXPECT_LT(std::fabs(b.L[d] - a.L[d]), tol * a.Lscale) << what << " angular momentum " << d;
  }
}

}    // namespace

// an accretion event (run 0: at the setup, nothing moves) and 60 steps with accretion keep the
// total mass, momentum and angular momentum (orbital + spin) to round-off; gas is accreted
// (otherwise the test proves nothing), by both sinks, and the atom count follows
TEST(Sink, AccretionConservesMassMomentumAngularMomentum)
{
  auto lmp = open_lammps();
  ball_with_sinks(lmp);
  const Totals before = totals(lmp);
  commands(lmp, {"run 0"});
  const Totals after = totals(lmp);
  const double events = fix_value(lmp, "sink", 2);
  ASSERT_GT(events, 0.0);
  EXPECT_EQ(after.natoms, before.natoms - events);
  EXPECT_EQ(static_cast<double>(lmp->atom->natoms), after.natoms);
  expect_conserved(before, after, 1e-14, "one accretion event");
  // the accreted mass is the gas mass that went
  const auto rows = sink_rows(lmp);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_DOUBLE_EQ(rows[0][5] + rows[1][5], 0.25 * events);
  EXPECT_DOUBLE_EQ(fix_value(lmp, "sink", 1), 0.25 * events);
  double spin = 0.0;
  for (const auto &row : rows) spin += std::fabs(row[2]) + std::fabs(row[3]) + std::fabs(row[4]);
  EXPECT_GT(spin, 0.0);    // the accreted gas's angular momentum about the sinks

  commands(lmp, {"run 60"});
  const Totals later = totals(lmp);
  const double events_later = fix_value(lmp, "sink", 2);
  EXPECT_GT(events_later, events);
  const auto rows_later = sink_rows(lmp);
  EXPECT_GT(rows_later[0][5], rows[0][5]);
  EXPECT_GT(rows_later[1][5], rows[1][5]);
  EXPECT_EQ(later.natoms, before.natoms - events_later);
  // (SPH forces are pairwise and central: the leapfrog keeps p and L to round-off too)
  expect_conserved(before, later, 1e-13, "60 steps with accretion");
}

// the accretion decisions and sums are the same on any number of ranks: the run on all ranks
// of the test against the same run on rank 0 alone (bit for bit at the setup's accretion, the
// same accreted particles after 40 steps, values to round-off growth)
TEST(Sink, SameOnOneAndSeveralRanks)
{
  int me, nprocs;
  MPI_Comm_rank(MPI_COMM_WORLD, &me);
  MPI_Comm_size(MPI_COMM_WORLD, &nprocs);
  std::vector<std::vector<double>> rows0, rows40;
  double events0, events40;
  {
    auto lmp = open_on(MPI_COMM_WORLD);
    ball_with_sinks(lmp);
    commands(lmp, {"run 0"});
    rows0 = sink_rows(lmp);
    events0 = fix_value(lmp, "sink", 2);
    commands(lmp, {"run 40"});
    rows40 = sink_rows(lmp);
    events40 = fix_value(lmp, "sink", 2);
  }
  ASSERT_GT(events0, 0.0);
  ASSERT_GT(events40, events0);    // (accretion within the steps too)
  MPI_Comm alone;
  MPI_Comm_split(MPI_COMM_WORLD, me == 0 ? 0 : MPI_UNDEFINED, 0, &alone);
  if (me == 0) {
    auto lmp = open_on(alone);
    ball_with_sinks(lmp);
    commands(lmp, {"run 0"});
    const auto one0 = sink_rows(lmp);
    EXPECT_EQ(fix_value(lmp, "sink", 2), events0);
    ASSERT_EQ(one0.size(), rows0.size());
    for (size_t k = 0; k < one0.size(); k++)
      for (size_t c = 0; c < 6; c++)
        EXPECT_EQ(one0[k][c], rows0[k][c])
            << "sink row " << k << " column " << c << " on " << nprocs << " ranks";
    commands(lmp, {"run 40"});
    const auto one40 = sink_rows(lmp);
    EXPECT_EQ(fix_value(lmp, "sink", 2), events40);
    ASSERT_EQ(one40.size(), rows40.size());
    for (size_t k = 0; k < one40.size(); k++) {
      EXPECT_EQ(one40[k][1], rows40[k][1]) << "sink mass " << k;    // the same gas accreted
      for (size_t c = 2; c < 5; c++)
        EXPECT_NEAR(one40[k][c], rows40[k][c], 1e-10 * (1.0 + std::fabs(one40[k][c])))
            << "sink spin " << k << " component " << c - 2;
    }
    MPI_Comm_free(&alone);
  }
  MPI_Barrier(MPI_COMM_WORLD);
}

// write_restart between two runs: the continued run from the file (fix sph/astro/sink defined
// again with its ID: spin and accreted mass come back per atom, the totals globally) ends with
// the same sinks and gas bit for bit (on 1 rank: on more, read_restart orders each rank's atoms
// otherwise, and the SPH sums differ in their last bits)
TEST(Sink, RestartContinuesBitForBit)
{
  int me;
  MPI_Comm_rank(MPI_COMM_WORLD, &me);
  const std::string file = "test_fix_sph_astro_sink.restart";
  std::vector<std::vector<double>> ref;
  std::map<int, double> ref_x;
  double ref_events, ref_macc;
  {
    auto lmp = open_lammps();
    ball_with_sinks(lmp);
    commands(lmp, {"run 30", "write_restart " + file, "run 30"});
    ref = sink_rows(lmp);
    ref_events = fix_value(lmp, "sink", 2);
    ref_macc = fix_value(lmp, "sink", 1);
    if (lmp->comm->nprocs == 1) ref_x = per_atom(lmp, "x", 0);
  }
  auto lmp = open_lammps();
  commands(lmp,
           {"read_restart " + file, "fix mass all property/atom rmass ghost yes",
            "pair_coeff * * zero", "pair_coeff 1 1 sph/astro", "fix gas gas sph/astro courant 0.3",
            "fix hvar gas sph/astro/h iterate hfact 1.2", "fix nve sinks nve",
            "fix sink sinks sph/astro/sink racc 0.8 G 1.0", "neighbor 0.2 bin",
            "neigh_modify every 1 delay 0 check yes", "compute s sinks sph/astro/sink sink"});
  // (the spins are back before the run)
  const auto read = sink_rows(lmp);
  ASSERT_EQ(read.size(), ref.size());
  double spin = 0.0;
  for (const auto &row : read) spin += std::fabs(row[2]) + std::fabs(row[5]);
  EXPECT_GT(spin, 0.0);
  commands(lmp, {"run 30"});
  const auto got = sink_rows(lmp);
  ASSERT_EQ(got.size(), ref.size());
  for (size_t k = 0; k < got.size(); k++)
    for (size_t c = 0; c < 6; c++) EXPECT_EQ(got[k][c], ref[k][c]) << "row " << k << " col " << c;
  EXPECT_EQ(fix_value(lmp, "sink", 2), ref_events);
  EXPECT_EQ(fix_value(lmp, "sink", 1), ref_macc);
  if (lmp->comm->nprocs == 1) {
    const auto x = per_atom(lmp, "x", 0);
    ASSERT_EQ(x.size(), ref_x.size());
    for (const auto &[tag, value] : x) EXPECT_EQ(value, ref_x.at(tag)) << "atom " << tag;
  }
  if (me == 0) std::remove(file.c_str());
}

// two sinks 0.2 apart with masses 5 and 3: their orbit bound C sqrt(r^3 / (G (M_a + M_b)))
// sets fix sph/astro's step (below the gas's), and the fix reports it
TEST(Sink, TimestepBoundOfSinkPairs)
{
  double expected;
  {
    auto lmp = open_lammps();
    ball_with_sinks(lmp, "racc 0.1 rin 0.05 G 1.0 dtfactor 0.25");
    commands(lmp,
             {"set atom 251 x 0.3 y 0.05 z -0.02", "velocity sinks set 0 0 0", "run 1",
              "variable r equal sqrt((x[250]-x[251])^2+(y[250]-y[251])^2+(z[250]-z[251])^2)",
              "variable m equal mass[250]+mass[251]"});
    auto equal = [&](const char *name) {
      auto *value = static_cast<double *>(lammps_extract_variable(lmp.get(), name, nullptr));
      const double result = *value;
      lammps_free(value);
      return result;
    };
    const double r = equal("r"), m = equal("m");
    ASSERT_NEAR(r, 0.2, 0.05);
    expected = 0.25 * std::sqrt(r * r * r / (1.0 * m));
    const double limit = fix_value(lmp, "sink", 4);
    EXPECT_LE(limit, expected * (1.0 + 1e-12));
    EXPECT_EQ(limit, expected);    // (the sinks are at rest: the orbit bound is the smallest)
    EXPECT_LE(lmp->update->dt, limit);
  }    // (one LAMMPS instance at a time: the plugin's styles go to the first)
  // without the sinks' bound the gas alone would step longer
  auto free = open_lammps();
  ball_with_sinks(free, "racc 0.1 rin 0.05 G 1.0 dtfactor 0.25");
  commands(free, {"set atom 251 x 2.0 y 2.0 z 2.0", "velocity sinks set 0 0 0", "run 1"});
  EXPECT_GT(free->update->dt, 2.0 * expected);
}

// a self-gravitating uniform ball of gas at rest (mass 1, radius 1, G 1, direct summation, the
// sinks softened with h 0.05) with creation above rho_crit = 0.1 (below its density 0.24):
// the thermal check of Bate, Bonnell & Price 1995 (alpha = E_th/|E_grav| <= 1/2 over the gas
// within racc) decides: for the gas within racc = 0.35 of a central particle (mass 0.043)
// alpha = 1.5 c_s^2 r / (0.6 G M) is about 1.8 at c_s = 0.3, which makes no sink in 10 steps,
// and 0.008 at c_s = 0.02, which makes sinks there (one per step at most: the whole ball is
// above rho_crit); each then holds the gas that was within racc of it, and the total mass
// stays to round-off
void self_gravitating_ball(const Lammps &lmp, double cs)
{
  commands(lmp,
           {"units lj",
            "atom_style atomic",
            "atom_modify map array sort 0 0.0",
            "boundary s s s",
            "lattice fcc 500",
            "region box block -1.2 1.2 -1.2 1.2 -1.2 1.2 units box",
            "create_box 2 box",
            "fix mass all property/atom rmass ghost yes",
            "region ball sphere 0 0 0 1.0 units box",
            "create_atoms 1 region ball",
            "displace_atoms all random 0.005 0.005 0.005 4711 units box",
            "group gas type 1",
            "group sinks type 2",
            "set group gas mass $(1.0/count(gas))",
            "pair_style hybrid/overlay sph/astro kernel m4 eos isothermal " + num(cs) +
                " viscosity classic 1.0 2.0 sph/astro/gravity 100.0 h 0.05",
            "pair_coeff 1 1 sph/astro",
            "pair_coeff * * sph/astro/gravity",
            "fix gas gas sph/astro courant 0.3",
            "fix hvar gas sph/astro/h iterate hfact 1.2",
            "fix nve sinks nve",
            "fix sink sinks sph/astro/sink racc 0.35 create 0.1 type 2",
            "set group gas d_h 0.15",
            "neighbor 0.05 bin",
            "neigh_modify every 1 delay 0 check yes",
            "compute s sinks sph/astro/sink sink"});
}

TEST(Sink, CreationNeedsTheThermalCheck)
{
  {
    auto lmp = open_lammps();
    self_gravitating_ball(lmp, 0.3);
    commands(lmp, {"run 10"});
    EXPECT_EQ(fix_value(lmp, "sink", 3), 0.0) << "warm gas made a sink";
  }
  auto lmp = open_lammps();
  self_gravitating_ball(lmp, 0.02);
  const Totals before = totals(lmp);
  commands(lmp, {"run 10"});
  // (the whole ball is above rho_crit: a sink every step at most, outside the others' racc)
  const double made = fix_value(lmp, "sink", 3);
  EXPECT_GE(made, 1.0) << "cold gas made no sink";
  EXPECT_LE(made, 10.0);
  const auto rows = sink_rows(lmp);
  ASSERT_EQ(static_cast<double>(rows.size()), made);
  for (const auto &row : rows) EXPECT_GT(row[5], 0.0) << "sink " << row[0] << " accreted nothing";
  const Totals after = totals(lmp);
  EXPECT_LT(std::fabs(after.mass - before.mass), 1e-14 * before.mass);
  EXPECT_EQ(after.natoms, before.natoms - fix_value(lmp, "sink", 2));
}

// bad input names the fix, the value and what is allowed
TEST(Sink, BadInput)
{
  auto lmp = open_lammps();
  ball_with_sinks(lmp);
  auto expect_error = [&](const std::string &line, const std::string &fragment) {
    const std::string message = error_of(lmp, line);
    EXPECT_NE(message.find(fragment), std::string::npos)
        << "command: " << line << "\nmessage: " << message << "\nexpected: " << fragment;
  };
  expect_error("fix bad sinks sph/astro/sink G 1.0", "the accretion radius racc is required");
  expect_error("fix bad sinks sph/astro/sink racc -1", "racc = -1 must be > 0");
  expect_error("fix bad sinks sph/astro/sink racc 0.5 rin 0.6", "rin = 0.6 is larger than racc");
  expect_error("fix bad sinks sph/astro/sink racc 0.5 foo 1", "unknown keyword 'foo'");
  expect_error("fix bad sinks sph/astro/sink racc 0.5 create 10", "create needs the type");
  expect_error("fix bad sinks sph/astro/sink racc 0.5 type 3", "type 3 is not an atom type");
  expect_error("fix bad sinks sph/astro/sink racc 0.5 dtfactor 2", "dtfactor = 2 must be in");
  // a sink type that pair sph/astro treats as gas
  commands(lmp, {"unfix sink", "fix sink sinks sph/astro/sink racc 0.5 G 1 create 10 type 1"});
  expect_error("run 0", "type 1 of the new sinks has a pair_coeff of pair_style sph/astro");
  // the gas group may not hold sinks
  commands(lmp, {"unfix sink", "fix sink all sph/astro/sink racc 0.5 G 1"});
  expect_error("run 0", "is also in fix sph/astro's group gas");
  // no G without a gravity pair style
  commands(lmp, {"unfix sink", "fix sink sinks sph/astro/sink racc 0.5"});
  expect_error("run 0", "no gravitational constant");
  // compute sph/astro/sink of a fix of another style
  commands(lmp,
           {"unfix sink", "fix sink sinks sph/astro/sink racc 0.5 G 1",
            "compute bad sinks sph/astro/sink gas", "thermo_style custom step c_bad[1][1]"});
  expect_error("run 0", "fix gas is a fix sph/astro, not sph/astro/sink");
  lmp.reset();
  // per-atom masses are needed
  auto plain = open_lammps();
  commands(plain,
           {"units lj", "atom_style atomic", "region box block 0 1 0 1 0 1", "create_box 1 box"});
  const std::string message = error_of(plain, "fix s all sph/astro/sink racc 0.5");
  EXPECT_NE(message.find("needs per-atom masses"), std::string::npos) << message;
}
