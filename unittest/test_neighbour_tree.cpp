/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The neighbour tree (sph_astro_neighbour_tree.h) against brute force: every point with
// |x_j - c| < max(r_c, r_j) + pad, gather and scatter, with radii spread over two decades,
// points on a line and on a plane, coincident points, and points moved after the build.

#include "sph_astro_neighbour_tree.h"
#include "sph_astro_pair_loop.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using SPHAstro::NeighbourTree;

namespace {

struct Cloud {
  std::vector<double> coords, radius;
  std::vector<double *> x;
  std::vector<int> index;
  explicit Cloud(int n) : coords(3 * n), radius(n), x(n), index(n)
  {
    for (int i = 0; i < n; i++) {
      x[i] = &coords[3 * i];
      index[i] = i;
    }
  }
};

// shape 0: a clump in a tenuous cube (radius ~ local spacing); 1: a line; 2: a plane;
// 3: points on a coarse grid (many coincident coordinates and points); 4: a tenth of the points
// at one point and a tenth at distances 2^-k from it (each split at the middle of a box would
// part one of them from the rest: a level each), in a uniform cube
Cloud make_cloud(int shape, int n, unsigned seed)
{
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Cloud c(n);
  for (int i = 0; i < n; i++) {
    double *p = c.x[i];
    const bool clump = shape == 0 && i < n / 2;
    for (int d = 0; d < 3; d++) p[d] = clump ? 0.4 + 0.05 * u(gen) : u(gen);
    if (shape == 1) p[1] = p[2] = 0.5;
    if (shape == 2) p[2] = 0.25;
    if (shape == 3)
      for (int d = 0; d < 3; d++) p[d] = 0.125 * std::floor(8.0 * p[d]);
    if (shape == 4 && i < n / 5)
      for (int d = 0; d < 3; d++) p[d] = i < n / 10 ? 0.0 : std::ldexp(0.5, n / 10 - i);
    c.radius[i] = clump ? 0.01 * (1.0 + u(gen)) : 0.1 * (0.5 + u(gen));
  }
  return c;
}

std::vector<int> brute_force(const Cloud &c, const double *centre, double rc, double pad)
{
  std::vector<int> found;
  for (int j : c.index) {
    double r2 = 0.0;
    for (int d = 0; d < 3; d++) r2 += (c.x[j][d] - centre[d]) * (c.x[j][d] - centre[d]);
    const double reach = std::max(rc, c.radius[j]) + pad;
    if (r2 < reach * reach) found.push_back(j);
  }
  return found;
}

std::vector<int> tree_query(const NeighbourTree &tree, Cloud &c, const double *centre, double rc,
                            double pad, double motion)
{
  std::vector<int> found;
  tree.query(c.x.data(), c.radius.data(), centre, rc, pad, motion, [&](int j, double r2) {
    double expect = 0.0;
    for (int d = 0; d < 3; d++) expect += (c.x[j][d] - centre[d]) * (c.x[j][d] - centre[d]);
    EXPECT_DOUBLE_EQ(r2, expect);
    found.push_back(j);
  });
  std::sort(found.begin(), found.end());
  return found;
}

}    // namespace

TEST(NeighbourTree, FindsExactlyTheGatherAndScatterNeighbours)
{
  for (int shape = 0; shape < 5; shape++) {
    Cloud c = make_cloud(shape, 3000, 17u + shape);
    NeighbourTree tree;
    tree.build(c.x.data(), c.radius.data(), c.index.data(), static_cast<int>(c.index.size()));
    ASSERT_EQ(tree.size(), 3000);
    // (the queries' stacks hold one node per level)
    EXPECT_LE(tree.depth(), NeighbourTree::SPATIAL_DEPTH + 7) << "shape " << shape;
    if (shape == 4) EXPECT_GE(tree.depth(), NeighbourTree::SPATIAL_DEPTH) << "shape " << shape;
    std::size_t total = 0;
    for (int i = 0; i < 3000; i += 7) {
      for (double pad : {0.0, 0.02}) {
        const auto expect = brute_force(c, c.x[i], c.radius[i], pad);
        const auto got = tree_query(tree, c, c.x[i], c.radius[i], pad, 0.0);
        ASSERT_EQ(got, expect) << "shape " << shape << ", point " << i << ", pad " << pad;
        total += got.size();
      }
    }
    EXPECT_GT(total, 3000u) << "shape " << shape;
  }
}

// points moved after the build by up to 'motion': queries at the current positions still find
// every neighbour when told how far points may have moved
TEST(NeighbourTree, FindsNeighboursOfMovedPointsWithinTheMotionBound)
{
  Cloud c = make_cloud(0, 2000, 99u);
  NeighbourTree tree;
  tree.build(c.x.data(), c.radius.data(), c.index.data(), 2000);
  std::mt19937 gen(5u);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double motion = 0.03;
  for (double &v : c.coords) v += motion / std::sqrt(3.0) * u(gen);
  int differs = 0;
  for (int i = 0; i < 2000; i += 5) {
    const auto expect = brute_force(c, c.x[i], c.radius[i], 0.0);
    ASSERT_EQ(tree_query(tree, c, c.x[i], c.radius[i], 0.0, motion), expect) << "point " << i;
    differs += tree_query(tree, c, c.x[i], c.radius[i], 0.0, 0.0) != expect;
  }
  // without the bound some queries miss points (the test can fail)
  EXPECT_GT(differs, 0);
}

TEST(NeighbourTree, EmptyAndSinglePointTrees)
{
  Cloud c = make_cloud(0, 1, 1u);
  NeighbourTree tree;
  tree.build(c.x.data(), c.radius.data(), c.index.data(), 0);
  const double centre[3] = {0.5, 0.5, 0.5};
  EXPECT_TRUE(tree_query(tree, c, centre, 10.0, 0.0, 0.0).empty());
  tree.build(c.x.data(), c.radius.data(), c.index.data(), 1);
  EXPECT_EQ(tree_query(tree, c, c.x[0], 0.0, 0.0, 0.0).size(), 1u);
}

// the leaf form gives every point of every leaf the same neighbours as its own query
TEST(NeighbourTree, LeafQueriesFindWhatPointQueriesFind)
{
  for (int shape = 0; shape < 4; shape++) {
    Cloud c = make_cloud(shape, 2000, 31u + shape);
    NeighbourTree tree;
    tree.build(c.x.data(), c.radius.data(), c.index.data(), 2000);
    int served = 0;
    for (int l = 0; l < tree.leaves(); l++)
      tree.query_leaf(l, 0.01, [&](int k, const int *found, int n) {
        const int i = tree.point(k);
        std::vector<int> got;
        for (int m = 0; m < n; m++) got.push_back(tree.point(found[m]));
        ASSERT_TRUE(std::is_sorted(got.begin(), got.end())) << "shape " << shape;
        ASSERT_EQ(got, brute_force(c, c.x[i], c.radius[i], 0.01))
            << "shape " << shape << ", point " << i;
        served++;
      });
    EXPECT_EQ(served, 2000) << "shape " << shape;
  }
}

// the candidates' sort by index: as std::sort for indices of up to 1, 11, 12, 22, 23 and 31 bits
TEST(NeighbourTree, RadixSortByIndexIsTheSort)
{
  std::mt19937 gen(3u);
  std::vector<unsigned long long> scratch;
  std::vector<int> count;
  for (unsigned top : {1u, 2047u, 4095u, (1u << 22) - 1u, (1u << 23) - 1u, 2147483647u}) {
    std::uniform_int_distribution<unsigned> index(0, top);
    for (int n : {0, 1, 7, 900, 5000}) {
      std::vector<unsigned long long> keys;
      for (int m = 0; m < n; m++)
        keys.push_back((static_cast<unsigned long long>(index(gen)) << 32) | gen());
      std::vector<unsigned long long> expect = keys;
      std::stable_sort(expect.begin(), expect.end(), [](auto a, auto b) {
        return (a >> 32) < (b >> 32);
      });
      NeighbourTree::sort_by_index(keys, scratch, count);
      EXPECT_EQ(keys, expect) << "top " << top << ", n " << n;
    }
  }
}

// the selection of a leaf's candidates (AVX-512, 16 per step, where the processor has it) keeps
// exactly the candidates the scalar comparison keeps, in order: counts that are not multiples
// of 16, radii above and below the point's, and candidates placed on the reach itself, where
// one rounding more or less (a fused multiply-add) would flip the comparison
TEST(NeighbourTree, CandidateSelectionIsTheScalarComparison)
{
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> pos(-1.0, 1.0), rad(0.05, 0.6), unit(0.0, 1.0);
  int ties = 0;
  for (int nc : {0, 1, 7, 15, 16, 17, 31, 32, 33, 100, 257}) {
    for (int trial = 0; trial < 20; trial++) {
      std::vector<double> cx(nc), cy(nc), cz(nc), cr(nc);
      std::vector<int> index(nc), found(nc, -1), expected;
      const double c[3] = {pos(gen), pos(gen), pos(gen)}, rc = rad(gen), pad = 0.1 * unit(gen);
      for (int m = 0; m < nc; m++) {
        cr[m] = rad(gen);
        index[m] = 3 * m + 1;
        double d[3] = {pos(gen), pos(gen), pos(gen)};
        if (m % 3 == 0) {    // on the reach: a direction scaled to max(rc, cr) + pad
          const double norm = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
          for (double &v : d) v *= ((rc > cr[m] ? rc : cr[m]) + pad) / norm;
        }
        cx[m] = c[0] + d[0];
        cy[m] = c[1] + d[1];
        cz[m] = c[2] + d[2];
        const double dx = cx[m] - c[0], dy = cy[m] - c[1], dz = cz[m] - c[2];
        const double reach = (rc > cr[m] ? rc : cr[m]) + pad;
        volatile double d2 = dx * dx;    // (one rounding per operation, as the selection)
        d2 = d2 + dy * dy;
        d2 = d2 + dz * dz;
        volatile double reach2 = reach * reach;
        if (d2 < reach2) expected.push_back(index[m]);
        ties += m % 3 == 0 && (d2 < reach2);
      }
      const int n = NeighbourTree::select_within(cx.data(), cy.data(), cz.data(), cr.data(),
                                                 index.data(), nc, c, rc, pad, found.data());
      ASSERT_EQ(n, static_cast<int>(expected.size())) << nc << " candidates";
      for (int k = 0; k < n; k++) EXPECT_EQ(found[k], expected[k]) << k;
    }
  }
  EXPECT_GT(ties, 0);    // some candidates on the reach fall inside by rounding, some outside
}

// the h iteration's entries (sph_astro_pair_loop.h): gathered once within R h_near, then at
// every support up to it the same entries, in the same row order and with the same
// separations, as a pass over the whole row; a row's special-bond bits are masked off
TEST(NearEntries, AreTheRowsEntriesInsideEachSupportInRowOrder)
{
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> coord(0.0, 1.0);
  const int n = 400;
  std::vector<double> flat(3 * n);
  std::vector<double *> x(n);
  for (int k = 0; k < n; k++) {
    x[k] = &flat[3 * k];
    for (int d = 0; d < 3; d++) x[k][d] = coord(gen);
  }
  // atoms 0 and 5 exactly 0.5 apart (dyadic coordinates: no rounding): kept by the gather
  // (near2 = 0.5625), on the bound of support2 = 0.25, where each() must leave it out
  for (int d = 0; d < 3; d++) x[0][d] = x[5][d] = 0.25;
  x[5][0] = 0.75;
  SPHAstro::NearEntries near;
  for (int jnum : {n - 1, 57, 0, n - 1}) {
    std::vector<int> row;
    for (int j = 1; j <= jnum; j++) row.push_back(j | (j % 7 == 0 ? 1 << 30 : 0));
    std::shuffle(row.begin(), row.end(), gen);
    const double near2 = 0.5625;
    near.gather(x.data(), 0, row.data(), jnum, near2);
    for (double support2 : {0.0, 0.01, 0.09, 0.25, 0.5625}) {
      std::vector<int> want, got;
      std::vector<double> want_d, got_d;
      for (int jj = 0; jj < jnum; jj++) {
        const int j = row[jj] & NEIGHMASK;
        const double dx = x[0][0] - x[j][0], dy = x[0][1] - x[j][1], dz = x[0][2] - x[j][2];
        const double r2 = dx * dx + dy * dy + dz * dz;
        if (r2 >= support2) continue;
        want.push_back(j);
        want_d.insert(want_d.end(), {dx, dy, dz, r2});
      }
      near.each(support2, [&](int j, double dx, double dy, double dz, double r2) {
        got.push_back(j);
        got_d.insert(got_d.end(), {dx, dy, dz, r2});
      });
      EXPECT_EQ(got, want) << "jnum " << jnum << ", support2 " << support2;
      EXPECT_EQ(got_d, want_d);    // (bit for bit)
      if (support2 > 0.05 && jnum > 100) EXPECT_GT(want.size(), 5u);
      if (jnum > 100)    // (atom 5 on the bound 0.25, inside 0.5625)
        EXPECT_EQ(std::count(got.begin(), got.end(), 5), support2 > 0.25 ? 1 : 0);
    }
  }
}
