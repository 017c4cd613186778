/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Individual timesteps without LAMMPS: the time line's bins (sph_astro_time_bins.h), the
// due pairs of a step (sph_astro_due_pairs.h) against brute force, and the record of the
// evaluated pairs (sph_astro_evaluated_pairs.h).

#include "sph_astro_due_pairs.h"
#include "sph_astro_evaluated_pairs.h"
#include "sph_astro_time_bins.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

using namespace SPHAstro;

TEST(TimeBins, BinIsTheLongestStepWithinTheCriterion)
{
  const double dt_max = 0.3;
  EXPECT_EQ(TimeBins::bin_for(dt_max, 1.0), 0);
  EXPECT_EQ(TimeBins::bin_for(dt_max, INFINITY), 0);
  EXPECT_EQ(TimeBins::bin_for(dt_max, 0.3), 0);
  EXPECT_EQ(TimeBins::bin_for(dt_max, 0.29999), 1);
  EXPECT_EQ(TimeBins::bin_for(dt_max, 0.15), 1);
  EXPECT_EQ(TimeBins::bin_for(dt_max, 0.1), 2);
  EXPECT_GT(TimeBins::bin_for(dt_max, 0.0), TimeBins::MAX_BIN);
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> logdt(-40.0, 2.0);
  for (int k = 0; k < 10000; k++) {
    const double dt = dt_max * std::exp2(logdt(gen));
    const int b = TimeBins::bin_for(dt_max, dt);
    ASSERT_LE(std::ldexp(dt_max, -b), dt);
    if (b > 0) ASSERT_GT(std::ldexp(dt_max, -(b - 1)), dt);
  }
}

TEST(TimeBins, LongerStepsOnlyWhereTheirGridPasses)
{
  const double L3 = TimeBins::ticks(3);
  EXPECT_EQ(TimeBins::ticks(0), TimeBins::cycle());
  EXPECT_EQ(L3, std::ldexp(1.0, TimeBins::MAX_BIN - 3));
  // shorter at once
  EXPECT_EQ(TimeBins::next_bin(3, 7, L3), 7);
  // longer: one bin, where bin 2's grid (2 L3) passes
  EXPECT_EQ(TimeBins::next_bin(3, 0, 2 * L3), 2);
  EXPECT_EQ(TimeBins::next_bin(3, 0, 3 * L3), 3);
  EXPECT_EQ(TimeBins::next_bin(0, 0, 0.0), 0);
  EXPECT_TRUE(TimeBins::synchronised(4 * L3, 1));
  EXPECT_FALSE(TimeBins::synchronised(2 * L3, 1));
  // a woken particle ends at the next point of its new grid, after now
  EXPECT_EQ(TimeBins::wake_end(5 * L3, 3), 6 * L3);
  EXPECT_EQ(TimeBins::wake_end(5 * L3, 1), 8 * L3);
  EXPECT_EQ(TimeBins::wake_end(8 * L3, 1), 12 * L3);
}

// the coarsest bin whose grid holds a time: the next grid points after a time of different
// bins (the closes a sleeping particle's pairs wait for) differ in it
TEST(TimeBins, CoarsestBinTellsNextGridPointsApart)
{
  const double L3 = TimeBins::ticks(3);
  EXPECT_EQ(TimeBins::coarsest_bin(L3), 3);
  EXPECT_EQ(TimeBins::coarsest_bin(3 * L3), 3);
  EXPECT_EQ(TimeBins::coarsest_bin(6 * L3), 2);
  EXPECT_EQ(TimeBins::coarsest_bin(TimeBins::cycle()), 0);
  EXPECT_EQ(TimeBins::coarsest_bin(1.0), TimeBins::MAX_BIN);
  // after t = 5 L3 the next points of bins 0..6: equal coarsest bins, equal times
  const double t = 5 * L3;
  std::map<int, double> next_of;
  for (int b = 0; b <= 6; b++) {
    const double next = TimeBins::wake_end(t, b);
    const int c = TimeBins::coarsest_bin(next);
    EXPECT_LE(c, b) << b;
    auto [it, fresh] = next_of.emplace(c, next);
    EXPECT_TRUE(fresh || it->second == next) << b;
  }
  EXPECT_GE(next_of.size(), 3u);
}

namespace {
// a random half list: owned atoms 0..nlocal, ghosts up to nall, rows sorted by atom index
struct RandomHalfList {
  std::vector<std::vector<int>> rows;
  std::vector<int> ilist, numneigh;
  std::vector<int *> first;
  RandomHalfList(int nlocal, int nall, int per_row, unsigned seed) : rows(nlocal)
  {
    std::mt19937 gen(seed);
    std::uniform_int_distribution<int> pick(0, nall - 1);
    for (int i = 0; i < nlocal; i++) {
      std::set<int> row;
      for (int k = 0; k < per_row; k++) {
        const int j = pick(gen);
        if (j != i && !(j < nlocal && j < i)) row.insert(j);    // each owned pair once
      }
      rows[i].assign(row.begin(), row.end());
      if (i % 7 != 3) ilist.push_back(i);    // some atoms are not SPH atoms
    }
    numneigh.resize(nlocal);
    first.resize(nlocal);
    for (int i = 0; i < nlocal; i++) {
      numneigh[i] = static_cast<int>(rows[i].size());
      first[i] = rows[i].data();
    }
  }
  NeighView view()
  {
    return {static_cast<int>(ilist.size()), ilist.data(), numneigh.data(), first.data()};
  }
};
}    // namespace

TEST(DuePairs, ExactlyThePairsWithAnActiveAtomInTheListsOrder)
{
  const int nlocal = 400, nall = 700;
  RandomHalfList list(nlocal, nall, 30, 11);
  const NeighView half = list.view();
  DuePairs due;
  due.index(half, nall);
  std::mt19937 gen(5);
  for (double share : {0.0, 0.02, 0.3, 1.0}) {
    std::bernoulli_distribution flip(share);
    std::vector<char> active(nall);
    for (auto &a : active) a = flip(gen);
    const NeighView v = due.select(half, nlocal, nall, active.data());
    // expected: every row's entries with an active end, in the row's order
    std::vector<std::pair<int, int>> expected, got;
    std::vector<int> expected_rows;
    for (int ii = 0; ii < half.inum; ii++) {
      const int i = half.ilist[ii];
      bool any = false;
      for (int j : list.rows[i])
        if (active[i] || active[j]) {
          expected.emplace_back(i, j);
          any = true;
        }
      if (any || active[i]) expected_rows.push_back(i);
    }
    for (int ii = 0; ii < v.inum; ii++) {
      const int i = v.ilist[ii];
      for (int k = 0; k < v.numneigh[i]; k++) got.emplace_back(i, v.firstneigh[i][k]);
    }
    EXPECT_EQ(got, expected) << "share " << share;
    EXPECT_EQ(std::vector<int>(v.ilist, v.ilist + v.inum), expected_rows);
    if (share == 1.0)
      EXPECT_EQ(got.size(), [&] {
        std::size_t n = 0;
        for (int i : list.ilist) n += list.rows[i].size();
        return n;
      }());
  }
}

// the force pass's record of its pairs (sph_astro_evaluated_pairs.h): rows without pairs are
// left out, each pair is visited once with its row's atom, its partner, whether this rank
// updates the partner, and its force's (and du/dt terms') index
TEST(EvaluatedPairs, EachRecordedPairIsVisitedOnceWithItsRowAtom)
{
  EvaluatedPairs pairs;
  pairs.clear(true, true);
  const std::vector<std::vector<std::pair<int, bool>>> rows = {
      {{5, true}, {7, false}}, {}, {{0, true}}, {}, {{9, false}, {3, true}, {4, true}}};
  std::vector<std::tuple<int, int, bool, double>> expected;
  double f = 0.5;
  for (std::size_t i = 0; i < rows.size(); i++) {
    const int begin = static_cast<int>(pairs.partner.size());
    for (const auto &[j, update_j] : rows[i]) {
      pairs.add(j, update_j, f, 2.0 * f, 3.0 * f);
      expected.emplace_back(static_cast<int>(i), j, update_j, f);
      f += 1.0;
    }
    pairs.end_row(static_cast<int>(i), begin);
  }
  EXPECT_EQ(pairs.rows.size(), 3u);
  std::vector<std::tuple<int, int, bool, double>> visited;
  pairs.for_each([&](int i, int j, bool update_j, int k) {
    visited.emplace_back(i, j, update_j, pairs.fpair[k]);
    EXPECT_EQ(pairs.heat[2 * k], 2.0 * pairs.fpair[k]);
    EXPECT_EQ(pairs.heat[2 * k + 1], 3.0 * pairs.fpair[k]);
  });
  EXPECT_EQ(visited, expected);

  pairs.clear(false, true);    // the limiter alone: no forces or du/dt terms kept
  pairs.add(2, true, 1.0, 1.0, 1.0);
  pairs.end_row(1, 0);
  EXPECT_TRUE(pairs.fpair.empty());
  EXPECT_TRUE(pairs.heat.empty());
  int count = 0;
  pairs.for_each([&](int i, int j, bool update_j, int) {
    EXPECT_EQ(i, 1);
    EXPECT_EQ(j, 2);
    EXPECT_TRUE(update_j);
    count++;
  });
  EXPECT_EQ(count, 1);
}
