/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// LAMMPS-driven tests of fix sph/astro/h: the h-rho iteration, dh/dt, h collections, lists
// that follow h and the pruned lists.

#include "styles_fixture.h"

#include "compute.h"
#include "fix.h"
#include "force.h"
#include "neigh_list.h"
#include "pair.h"
#include "sph_astro_pruned_list.h"

#include <cmath>
#include <cstdio>

using namespace sph_astro_test;
using LAMMPS_NS::LAMMPS;

// ------------------------------------------------------ variable smoothing
// length

static double energy_error_gradh(double dt)
{
  return energy_error(dt, PAIR, "fix hvar all sph/astro/h iterate hfact 1.2 tol 1e-10 margin 2.0");
}

TEST(FixSPHAstroH, GradHEnergyErrorIsSecondOrderInTimestep)
{
  // with h converged tightly the grad-h equations conserve energy up to time
  // integration
  const double e1 = energy_error_gradh(0.02), e2 = energy_error_gradh(0.01),
               e3 = energy_error_gradh(0.005);
  printf("grad-h energy error: dt 0.02 %.3e, 0.01 %.3e, 0.005 %.3e\n", e1, e2, e3);
  ASSERT_GT(e3, 0.0);
  EXPECT_NEAR(e1 / e2, 4.0, 1.0);
  EXPECT_NEAR(e2 / e3, 4.0, 1.0);
}

TEST(FixSPHAstroH, IterationConvergesOnADisorderedGlass)
{
  auto lmp = open_lammps();
  // strongly disordered lattice, initial h off by 30 %
  gas(lmp, "box", 4, PAIR, "sph/astro", 1.0, 0.25);
  commands(
      lmp,
      {"set group all d_h 0.55", "fix hvar all sph/astro/h iterate hfact 1.2 tol 1e-8", "run 0"});
  auto h = per_atom(lmp, "h");
  auto rho = per_atom(lmp, "rho");
  double worst = 0.0;
  for (const auto &[id, hi] : h) {
    const double target = 1.2 * std::cbrt(0.25 / rho[id]);
    worst = std::max(worst, std::fabs(hi - target) / target);
  }
  auto *fix = lmp->modify->get_fix_by_id("hvar");
  printf("h iteration: mean %.2f max %.0f iterations, worst |h - hfact "
         "(m/rho)^(1/3)|/h = %.2e\n",
         fix->compute_vector(0), fix->compute_vector(1), worst);
  EXPECT_LT(worst, 1e-7);
  EXPECT_EQ(fix->compute_vector(2), 0.0);
  EXPECT_EQ(fix->compute_vector(3), 0.0);
}

// mean and largest neighbour-list length of the local atoms of the pair's list(s)
static std::pair<double, int> list_lengths(const std::unique_ptr<LAMMPS> &lmp, int type_only)
{
  auto *list = lmp->force->pair->list;
  double sum = 0.0;
  int n = 0, most = 0;
  for (int ii = 0; ii < list->inum; ii++) {
    const int i = list->ilist[ii];
    if (type_only && lmp->atom->type[i] != type_only) continue;
    sum += list->numneigh[i];
    most = std::max(most, list->numneigh[i]);
    n++;
  }
  return {n ? sum / n : 0.0, most};
}

// a dense fcc clump (lattice constant 1, rho = 1) in a tenuous fcc gas (lattice constant
// a_out) of equal-mass particles, one atom type; h iterated from a rough start
static std::unique_ptr<LAMMPS> clump_in_tenuous_gas(double a_out, int cells_out, int clump,
                                                    const std::string &hfix_extra,
                                                    const std::string &nbin)
{
  auto lmp = open_lammps();
  const double half = 0.5 * a_out * cells_out, c = 0.5 * clump;
  const double n_out = 4.0 / (a_out * a_out * a_out);    // number density (lattice fcc)
  const double rho_out = 0.25 * n_out;                   // mass density
  const std::string box = num(-half) + " " + num(half);
  const std::string cl = num(-c) + " " + num(c);
  commands(lmp,
           {"units lj",
            "atom_style atomic",
            "atom_modify map array",
            "boundary p p p",
            "region box block " + box + " " + box + " " + box + " units box",
            "create_box 1 box",
            "lattice fcc " + num(n_out) + " origin 0.25 0.25 0.25",
            "region clump block " + cl + " " + cl + " " + cl + " units box",
            "region outside block " + cl + " " + cl + " " + cl + " side out units box",
            "create_atoms 1 region outside",
            "lattice fcc 4.0 origin 0.25 0.25 0.25",
            "create_atoms 1 region clump",
            "mass 1 0.25",
            std::string("pair_style ") + PAIR,
            "pair_coeff * *",
            "fix gas all sph/astro",
            "variable inside atom (abs(x)<" + num(c + 0.1) + ")*(abs(y)<" + num(c + 0.1) +
                ")*(abs(z)<" + num(c + 0.1) + ")",
            "variable h0 atom 1.2*(0.25/(" + num(rho_out) + "+v_inside))^(1/3)",
            "set group all d_h v_h0",
            "set group all d_u 1.0",
            "velocity all set 0 0 0",
            "fix hvar all sph/astro/h iterate hfact 1.2 tol 1e-8 margin 1.5 " + hfix_extra,
            "neighbor 0.3 " + nbin,
            "neigh_modify one 20000 page 200000",
            "run 1"});
  return lmp;
}

static double worst_h_error(const std::unique_ptr<LAMMPS> &lmp, double &hmin, double &hmax)
{
  auto h = per_atom(lmp, "h");
  auto rho = per_atom(lmp, "rho");
  double worst = 0.0;
  hmin = INFINITY;
  hmax = 0.0;
  for (const auto &[id, hi] : h) {
    hmin = std::min(hmin, hi);
    hmax = std::max(hmax, hi);
    const double target = 1.2 * std::cbrt(0.25 / rho[id]);
    worst = std::max(worst, std::fabs(hi - target) / target);
  }
  return worst;
}

TEST(FixSPHAstroH, IterationConvergesOnAMillionToOneDensityContrast)
{
  // rho 1 against 1e-6: h spans two decades
  auto lmp = clump_in_tenuous_gas(100.0, 2, 6, "", "bin");
  double hmin, hmax;
  const double worst = worst_h_error(lmp, hmin, hmax);
  auto *fix = lmp->modify->get_fix_by_id("hvar");
  printf("1e6 contrast: h %.3g..%.3g (ratio %.0f), mean iterations %.2f (max %.0f), failures "
         "%.0f, capped %.0f\n",
         hmin, hmax, hmax / hmin, fix->compute_vector(0), fix->compute_vector(1),
         fix->compute_vector(2), fix->compute_vector(3));
  EXPECT_LT(worst, 1e-6);
  EXPECT_EQ(fix->compute_vector(2), 0.0);
  EXPECT_EQ(fix->compute_vector(3), 0.0);
  EXPECT_GT(hmax / hmin, 50.0);
  const double hdense = 1.2 * std::cbrt(0.25);    // the clump's inside: rho = 1
  EXPECT_NEAR(hmin, hdense, 0.02 * hdense);
}

TEST(FixSPHAstroH, CollectionsKeepTheListsOfSmallSmoothingLengthsShort)
{
  // rho 1 against 1e-3 (h ratio 10), 6912 clump particles: with one cutoff every clump
  // particle's list spans the tenuous gas' kernel (the whole clump); with h collections it
  // spans its own. Same h either way.
  std::vector<double> mean(2), hmin(2), hmax(2);
  for (int k : {0, 1}) {
    auto lmp = clump_in_tenuous_gas(10.0, 6, 12, k ? "collections auto" : "", k ? "multi" : "bin");
    const double worst = worst_h_error(lmp, hmin[k], hmax[k]);
    auto *fix = lmp->modify->get_fix_by_id("hvar");
    mean[k] = list_lengths(lmp, 0).first;
    printf("1e3 contrast, %s: h %.3g..%.3g, mean list length %.0f, capped %.0f\n",
           k ? "collections" : "one cutoff", hmin[k], hmax[k], mean[k], fix->compute_vector(3));
    EXPECT_LT(worst, 1e-6);
    EXPECT_EQ(fix->compute_vector(2), 0.0);
    EXPECT_EQ(fix->compute_vector(3), 0.0);
  }
  EXPECT_NEAR(hmin[1], hmin[0], 1e-9 * hmin[0]);
  EXPECT_NEAR(hmax[1], hmax[0], 1e-9 * hmax[0]);
  EXPECT_LT(mean[1], 0.2 * mean[0]);
}

// an expanding hot ball: h grows past margin x its start value; sph/astro/run rebuilds the
// lists (rebuild) and the collections follow h, with the same result as one run with lists
// wide enough from the start
static std::map<int, double> expanding_ball(const std::string &hfix, const std::string &nbin,
                                            const std::string &run, std::vector<double> &stats,
                                            double skin = 0.1, const std::string &pair = PAIR)
{
  auto lmp = open_lammps();
  gas(lmp, "ball", 6, pair, "sph/astro dt fixed", 1.0, 0.04);
  commands(lmp,
           {hfix + " tol 1e-10", "neighbor " + num(skin) + " " + nbin,
            "neigh_modify every 1 delay 0 check yes one 10000", "timestep 0.004", run});
  auto *fix = lmp->modify->get_fix_by_id("hvar");
  stats.clear();
  for (int k = 0; k < 9; k++) stats.push_back(fix->compute_vector(k));
  return per_atom(lmp, "x", 0);
}

TEST(FixSPHAstroH, ListsFollowGrowingSmoothingLengths)
{
  std::vector<double> ref_stats, stats;
  const auto ref =
      expanding_ball("fix hvar all sph/astro/h iterate margin 4.0", "bin", "run 150", ref_stats);
  EXPECT_EQ(ref_stats[3], 0.0);    // margin 4: nobody reaches the cap
  // margin 1.3 alone: particles are held at the cap
  expanding_ball("fix hvar all sph/astro/h iterate margin 1.3", "bin", "run 150", stats);
  EXPECT_GT(stats[3], 0.0);
  // margin 1.3 with rebuild (and collections, with a skin wide enough that the lists are
  // rebuilt because h outgrows its collection, not only because atoms move, and without the
  // pruned lists, whose list builds would come first): no particle at the cap, the same
  // trajectory
  for (const std::string &variant : {"rebuild 0.9", "rebuild 0.9 collections auto"}) {
    const bool coll = variant.find("collections") != std::string::npos;
    const auto x = expanding_ball("fix hvar all sph/astro/h iterate margin 1.3 " + variant,
                                  coll ? "multi" : "bin", "sph/astro/run 150", stats,
                                  coll ? 0.8 : 0.1, std::string(PAIR) + (coll ? " prune no" : ""));
    printf("%s: %.0f runs ended for a rebuild, %.0f collection rebuilds, capped %.0f\n",
           variant.c_str(), stats[4], stats[5], stats[3]);
    EXPECT_GE(stats[4], 1.0) << variant;
    EXPECT_EQ(stats[3], 0.0) << variant;
    if (coll) EXPECT_GE(stats[5], 1.0);
    ASSERT_EQ(x.size(), ref.size());
    double worst = 0.0;
    for (const auto &[id, value] : ref) worst = std::max(worst, std::fabs(x.at(id) - value));
    // the same to the h tolerance: a round-off change can add a Newton iteration
    EXPECT_LT(worst, 1e-8) << variant;
  }
}

// a gas of the given shape with pair sph/astro prune yes (prune = 1) or prune no
static std::unique_ptr<LAMMPS> gas_pruned(int prune, const std::string &shape, int n,
                                          const std::string &fix)
{
  auto lmp = open_lammps();
  gas(lmp, shape, n, std::string(PAIR) + (prune ? " prune yes" : " prune no"), fix, 1.0, 0.04);
  return lmp;
}

// LAMMPS' half-from-full rule, npair_halffull.cpp (newton on, orthogonal box) line by line:
// the reference for the branch-free form the prune scan uses (SPHAstro::HalfFromFull::keeps)
static bool lammps_halffull_keeps(double **x, int nlocal, bool newton, int i, int j)
{
  if (!newton) return j > i;
  if (j < nlocal) return i < j;
  const double *xi = x[i], *xj = x[j];
  if (xj[2] < xi[2]) return false;
  if (xj[2] == xi[2]) {
    if (xj[1] < xi[1]) return false;
    if (xj[1] == xi[1] && xj[0] < xi[0]) return false;
  }
  return true;
}

// the rule of the prune scan decides every pair as LAMMPS' does: owned and ghost atoms, newton
// on and off, coordinates on a coarse grid so that equal z, equal z and y, and equal z, y and
// x all occur
TEST(PrunedLists, BranchFreeHalfRuleIsLAMMPSRule)
{
  const int nlocal = 40, nall = 160;
  std::vector<double> coords(3 * nall);
  std::vector<double *> x(nall);
  unsigned state = 12345u;
  for (int k = 0; k < nall; k++) {
    for (int d = 0; d < 3; d++) {
      state = state * 1103515245u + 12345u;
      coords[3 * k + d] = 0.5 * static_cast<double>((state >> 16) % 3);
    }
    x[k] = &coords[3 * k];
  }
  int kept = 0, decided = 0;
  for (bool newton : {false, true}) {
    const SPHAstro::HalfFromFull rule{nlocal, newton, false, 0.01};
    for (int i = 0; i < nlocal; i++)
      for (int j = 0; j < nall; j++) {
        if (j == i) continue;
        const bool reference = lammps_halffull_keeps(x.data(), nlocal, newton, i, j);
        ASSERT_EQ(rule.keeps(x.data(), i, j), reference)
            << "newton " << newton << ", i " << i << ", j " << j;
        kept += reference;
        decided++;
      }
  }
  // both answers occur (the grid of 27 points holds many ties)
  EXPECT_GT(kept, decided / 4);
  EXPECT_LT(kept, 3 * decided / 4);
}

// pruned lists (pair sph/astro prune, sph_astro_pruned_list.h): the same sums in the same order
// as over LAMMPS' lists, so the same run bit for bit while the pruning adds no list build. A
// periodic box of gas with 20 % pressure differences: h changes little; with fix sph/astro/h
// the lists carry the h cap (margin 1.5), which the pruned lists leave out
TEST(PrunedLists, GiveTheRunOfLAMMPSListsBitForBit)
{
  for (const std::string hfix :
       {"", "fix hvar all sph/astro/h dhdt", "fix hvar all sph/astro/h iterate"}) {
    std::map<std::string, std::map<int, double>> result[2];
    double lengths[2][3] = {};
    for (int prune : {0, 1}) {
      auto lmp = gas_pruned(prune, "box", 4, "sph/astro courant 0.3");
      if (!hfix.empty()) commands(lmp, {hfix});
      commands(lmp, {"run 60"});
      for (const char *field : {"u", "h", "rho"}) result[prune][field] = per_atom(lmp, field, 0);
      for (int c = 0; c < 3; c++) {
        result[prune]["x" + std::to_string(c)] = per_atom(lmp, "x", c);
        result[prune]["v" + std::to_string(c)] = per_atom(lmp, "v", c);
      }
      int dim;
      const auto *pruned =
          static_cast<double *>(lmp->force->pair->extract("pruned_list_lengths", dim));
      ASSERT_NE(pruned, nullptr);
      lengths[prune][0] = list_lengths(lmp, 0).first;
      lengths[prune][1] = pruned[0];
      lengths[prune][2] = pruned[1];
      if (!hfix.empty()) {
        auto *fix = lmp->modify->get_fix_by_id("hvar");
        EXPECT_EQ(fix->compute_vector(6), 0.0) << hfix;    // no build added for the pruning
        EXPECT_EQ(fix->compute_vector(7), 0.0) << hfix;    // no pass on LAMMPS' lists
        EXPECT_EQ(fix->compute_vector(8), 0.0) << hfix;
      }
    }
    // (iterate with prune yes: LAMMPS makes only the full list, which Pair::list then is)
    printf("%s: LAMMPS list %.1f per atom, pruned half %.1f (full %.1f); without pruning %.1f\n",
           hfix.empty() ? "fixed h" : hfix.c_str(), lengths[1][0], lengths[1][1], lengths[1][2],
           lengths[0][1]);
    EXPECT_EQ(lengths[0][1], 0.0);    // prune no: no pruned list
    // fixed h without fix sph/astro/h: one h, no margin; the pruned list would keep every entry
    // of LAMMPS' list, which is used as it is (nothing_to_prune)
    if (hfix.empty())
      EXPECT_EQ(lengths[1][1], 0.0);
    else {
      EXPECT_GT(lengths[1][1], 0.0) << hfix;
      EXPECT_LT(lengths[1][1], 0.6 * lengths[1][0]) << hfix;
    }
    for (const auto &[field, values] : result[0]) {
      ASSERT_EQ(values.size(), result[1][field].size());
      for (const auto &[id, value] : values)
        ASSERT_EQ(value, result[1][field].at(id)) << hfix << " " << field << " atom " << id;
    }
  }
}

// the pruned lists take memory for the entries they keep (in LAMMPS' list pages), not for all
// of LAMMPS' entries. With the h iteration and margin 1.5 LAMMPS' full list holds 249 entries
// per atom, the pruned half and full lists 60 and 120: with the half-rule byte per LAMMPS
// entry and the per-atom row arrays (ghosts included) they took 1.27 times LAMMPS' list (6 912
// atoms). Sized for all of LAMMPS' entries, as until 2026-12-02, they took 2.8 times it, and a
// Noh run of 1.07 million particles ran out of memory.
TEST(PrunedLists, TakeMemoryForTheEntriesTheyKeep)
{
  double pair_bytes[2] = {}, lammps_bytes = 0.0;
  for (int prune : {0, 1}) {
    auto lmp = gas_pruned(prune, "box", 12, "sph/astro courant 0.3");
    commands(lmp,
             {"fix hvar all sph/astro/h iterate", "neigh_modify one 1000 page 10000", "run 0"});
    pair_bytes[prune] = lmp->force->pair->memory_usage();
    if (prune) {
      const auto *list = lmp->force->pair->list;    // LAMMPS' full list (iterate + prune)
      ASSERT_TRUE(list->ghost == 0 && list->inum == lmp->atom->nlocal);
      double entries = 0.0;
      for (int ii = 0; ii < list->inum; ii++) entries += list->numneigh[list->ilist[ii]];
      lammps_bytes = sizeof(int) * entries;
    }
  }
  const double extra = pair_bytes[1] - pair_bytes[0];
  printf("pruned lists: %.0f kB against %.0f kB of LAMMPS' full list\n", extra / 1024.0,
         lammps_bytes / 1024.0);
  EXPECT_GT(extra, 0.0);
  EXPECT_LT(extra, 1.5 * lammps_bytes);
}

// an expanding hot ball (h grows to 1.5 x its start): the setup's h iteration takes the
// surface h past the pruned limit (those iterations use LAMMPS' lists); after that fix
// sph/astro/h has LAMMPS build the lists in time, so no half-list pass falls back (a few
// surface atoms' Newton or bisection trials overshoot the limit and finish on LAMMPS' list),
// and the trajectory is that of prune no to round-off (the added list builds reorder the sums)
TEST(PrunedLists, FollowGrowingSmoothingLengths)
{
  std::map<int, double> x[2];
  double at_setup[2][2] = {}, after[2][3] = {}, natoms = 0.0;
  for (int prune : {0, 1}) {
    auto lmp = gas_pruned(prune, "ball", 6, "sph/astro dt fixed");
    commands(lmp,
             {"fix hvar all sph/astro/h iterate margin 4.0 tol 1e-10", "neighbor 0.1 bin",
              "neigh_modify every 1 delay 0 check yes one 10000", "timestep 0.004", "run 0"});
    auto *fix = lmp->modify->get_fix_by_id("hvar");
    at_setup[prune][0] = fix->compute_vector(7);
    at_setup[prune][1] = fix->compute_vector(8);
    commands(lmp, {"run 150"});
    for (int k = 0; k < 3; k++) after[prune][k] = fix->compute_vector(6 + k);
    EXPECT_EQ(fix->compute_vector(3), 0.0);    // nobody at the h cap
    x[prune] = per_atom(lmp, "x", 0);
    natoms = static_cast<double>(lmp->atom->natoms);
  }
  printf("expanding ball: %.0f list builds forced by the pruned lists; fallbacks at the first "
         "setup %.0f passes, %.0f atoms; after 150 steps %.0f, %.0f\n",
         after[1][0], at_setup[1][0], at_setup[1][1], after[1][1], after[1][2]);
  EXPECT_EQ(after[0][0] + after[0][1] + after[0][2], 0.0);    // prune no: nothing to count
  EXPECT_GE(after[1][0], 1.0);
  EXPECT_EQ(after[1][1], at_setup[1][0]);
  // measured 238 of 150 x 459 atom-iterations (0.35 %)
  EXPECT_LT(after[1][2] - at_setup[1][1], 0.005 * 150 * natoms);
  double worst = 0.0;
  for (const auto &[id, value] : x[0]) worst = std::max(worst, std::fabs(x[1].at(id) - value));
  EXPECT_LT(worst, 1e-8);
}

// an h past the pruned limit: raised between runs with run pre no (dhdt), or by a larger hfact
// at a setup (iterate). The passes use LAMMPS' lists (grad-h: the full list for the h
// iteration, the half list made from it by LAMMPS' rule as decided at the build), and the
// result is that of prune no bit for bit
TEST(PrunedLists, FallBackToLAMMPSListsForAnHBeyondTheLimit)
{
  const double h_raised = 1.6 * 1.2 * std::cbrt(0.25);
  for (const std::string mode : {"dhdt", "iterate"}) {
    std::map<std::string, std::map<int, double>> result[2];
    double fallbacks[2][2] = {};
    for (int prune : {0, 1}) {
      auto lmp = gas_pruned(prune, "box", 4, "sph/astro courant 0.3");
      commands(lmp, {"fix hvar all sph/astro/h " + mode + " margin 3.0", "run 5"});
      if (mode == "dhdt")    // with run pre no, h is raised after the lists were pruned
        commands(lmp, {"set atom 1*40 d_h " + num(h_raised), "run 1 pre no"});
      else    // the setup prunes for the old h, then iterates h to 1.5 (m/rho)^(1/3), not 1.2
        commands(lmp,
                 {"unfix hvar", "fix hvar all sph/astro/h iterate hfact 1.5 margin 3.0", "run 0"});
      for (const char *field : {"rho", "h", "u"}) result[prune][field] = per_atom(lmp, field, 0);
      result[prune]["fx"] = per_atom(lmp, "f", 0);
      auto *fix = lmp->modify->get_fix_by_id("hvar");
      fallbacks[prune][0] = fix->compute_vector(7);
      fallbacks[prune][1] = fix->compute_vector(8);
    }
    printf("%s: %.0f passes and %.0f atoms' h iterations fell back to LAMMPS' lists\n",
           mode.c_str(), fallbacks[1][0], fallbacks[1][1]);
    EXPECT_EQ(fallbacks[0][0] + fallbacks[0][1], 0.0);
    EXPECT_GE(fallbacks[1][0], 1.0) << mode;
    if (mode == "iterate") EXPECT_GE(fallbacks[1][1], 1.0);
    for (const auto &[field, values] : result[0])
      for (const auto &[id, value] : values)
        ASSERT_EQ(value, result[1][field].at(id)) << mode << " " << field << " atom " << id;
  }
}

TEST(FixSPHAstroH, DhdtFollowsTheDivergence)
{
  // uniform expansion v = H x in a ball: div v = 3 H, so h grows as exp(H t)
  auto lmp = open_lammps();
  gas(lmp, "ball", 8, "sph/astro eos ideal 1.6666667 viscosity none", "sph/astro dt fixed", 1e-6,
      0.0);
  const double h0 = 1.2 * std::cbrt(0.25);
  commands(lmp,
           {"variable vx atom 0.1*x", "variable vy atom 0.1*y", "variable vz atom 0.1*z",
            "velocity all set v_vx v_vy v_vz", "fix hvar all sph/astro/h dhdt margin 2.0",
            "timestep 0.01", "thermo 100", "run 100"});
  // the particle closest to the centre (its kernel sees the uniform flow)
  auto h = per_atom(lmp, "h");
  std::map<int, double> r2;
  for (int d = 0; d < 3; d++)
    for (const auto &[id, x] : per_atom(lmp, "x", d)) r2[id] += x * x;
  int centre = r2.begin()->first;
  for (const auto &[id, value] : r2)
    if (value < r2[centre]) centre = id;
  const double rate = std::log(h[centre] / h0) / 1.0;    // should be H = 0.1 (div v / 3)
  printf("dh/dt: ln(h/h0)/t = %.5f at the centre, expected 0.1\n", rate);
  EXPECT_NEAR(rate, 0.1, 0.003);
}

// ------------------------------------------------- viscosity switch,
// conductivity
