/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The gravity tree without LAMMPS (sph_astro_gravity_tree.h, sph_astro_gravity_interactions.h):
// its structure and moments against brute-force sums, the walk's sums against direct
// summation (exact when every node is opened, within the multipole error otherwise), the
// order-independence of the build, far and coincident particles, and trees of imported
// multipoles.

#include "sph_astro_gravity_interactions.h"
#include "sph_astro_gravity_kernel.h"
#include "sph_astro_gravity_pair.h"
#include "sph_astro_gravity_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

using namespace SPHAstro;

namespace {

struct Cloud {
  std::vector<double> xyz, m, h, zo;
  std::vector<double *> x;
  std::vector<int64_t> tie;
  int n() const { return static_cast<int>(m.size()); }
  void index()
  {
    x.resize(n());
    tie.resize(n());
    for (int i = 0; i < n(); i++) {
      x[i] = &xyz[3 * i];
      tie[i] = 1000 + i;
    }
  }
};

// n particles in a ball of radius 1 (uniform), masses in [0.5, 1.5]/n, h in [h0, 2 h0]
Cloud ball(int n, double h0, unsigned seed = 1)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), v(0.0, 1.0);
  Cloud c;
  while (c.n() < n) {
    const double p[3] = {u(rng), u(rng), u(rng)};
    if (p[0] * p[0] + p[1] * p[1] + p[2] * p[2] > 1.0) continue;
    c.xyz.insert(c.xyz.end(), p, p + 3);
    c.m.push_back((0.5 + v(rng)) / n);
    c.h.push_back(h0 * (1.0 + v(rng)));
    c.zo.push_back(-0.1 * v(rng));
  }
  c.index();
  return c;
}

// acceleration and potential (per unit G) of particle i by direct summation with the pair
// terms of pair sph/astro/gravity (M4; zeta terms when ZETA)
template <bool ZETA> void direct(const Cloud &c, int i, double a[3], double &phi)
{
  const SoftenedKernel &soft = softened_kernel(KernelType::CUBIC);
  a[0] = a[1] = a[2] = phi = 0.0;
  for (int j = 0; j < c.n(); j++) {
    if (j == i) continue;
    const double d[3] = {c.x[i][0] - c.x[j][0], c.x[i][1] - c.x[j][1], c.x[i][2] - c.x[j][2]};
    const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    double p, D;
    if (r < 2.0 * std::max(c.h[i], c.h[j])) {
      softened_pair_inside<true>(soft, r, c.h[i], c.h[j], p, D);
      if (ZETA && r > 0.0)
        D += zeta_pair_term(KernelType::CUBIC, r, c.h[i], c.h[j], c.zo[i], c.zo[j]);
    } else {
      p = -1.0 / r;
      D = 1.0 / (r * r);
    }
    phi += c.m[j] * p;
    if (r > 0.0)
      for (int k = 0; k < 3; k++) a[k] -= c.m[j] * D * d[k] / r;
  }
}

// every particle's acceleration and potential from the tree (no imports), by groups
template <bool ZETA>
void tree_sums(const GravityTree &t, const OpeningCriterion &crit, int group,
               std::vector<double> &acc, std::vector<double> &pot, double *interactions = nullptr)
{
  const SoftenedKernel &soft = softened_kernel(KernelType::CUBIC);
  std::vector<int> groups, accepted, leaves;
  t.groups(group, groups);
  GravityInteractions lists;
  acc.assign(3 * t.size(), 0.0);
  pot.assign(t.size(), 0.0);
  double count = 0.0;
  for (int g : groups) {
    const GravityNode &n = t.node(g);
    TargetBox box{{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}, 0.0, 0.0};
    for (int k = n.first; k < n.first + n.count; k++) {
      const double p[3] = {t.x()[k], t.y()[k], t.z()[k]};
      for (int d = 0; d < 3; d++) {
        box.lo[d] = std::min(box.lo[d], p[d]);
        box.hi[d] = std::max(box.hi[d], p[d]);
      }
      box.hmax = std::max(box.hmax, t.h()[k]);
    }
    lists.clear();
    accepted.clear();
    leaves.clear();
    t.walk(box, crit, accepted, leaves);
    for (int a : accepted) lists.add_node(t.node(a));
    for (int l : leaves) lists.add_leaf(t, t.node(l), 0);
    lists.finish();
    for (int k = n.first; k < n.first + n.count; k++) {
      const int i = t.index(k);
      lists.evaluate<true, ZETA>(t.x()[k], t.y()[k], t.z()[k], t.h()[k], t.zo()[k], k, soft,
                                 KernelType::CUBIC, 2.0, &acc[3 * i], pot[i]);
      count += lists.multipoles() + lists.particles();
    }
  }
  if (interactions) *interactions = count / t.size();
}

GravityTree make_tree(Cloud &c, int leaf = 8)
{
  GravityTree t(leaf);
  t.build(c.n(), c.x.data(), c.tie.data());
  t.refit([&c](int i, double &x, double &y, double &z, double &m, double &h, double &zo) {
    x = c.x[i][0];
    y = c.x[i][1];
    z = c.x[i][2];
    m = c.m[i];
    h = c.h[i];
    zo = c.zo[i];
  });
  return t;
}

}    // namespace

TEST(GravityTree, EveryParticleOnceLeavesSmallChildrenPartitionTheirParent)
{
  Cloud c = ball(3000, 0.01);
  GravityTree t = make_tree(c, 8);
  ASSERT_EQ(t.size(), c.n());
  std::vector<int> seen(c.n(), 0);
  for (int k = 0; k < t.size(); k++) seen[t.index(k)]++;
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int s) {
    return s == 1;
  }));
  for (int k = 0; k < t.nodes(); k++) {
    const GravityNode &n = t.node(k);
    if (n.nchild == 0) {
      EXPECT_LE(n.count, 8);
      continue;
    }
    EXPECT_GE(n.nchild, 2);
    int first = n.first;
    for (int ch = n.child; ch < n.child + n.nchild; ch++) {
      EXPECT_EQ(t.node(ch).first, first);
      first += t.node(ch).count;
    }
    EXPECT_EQ(first, n.first + n.count);
  }
}

TEST(GravityTree, MomentsEqualBruteForceSums)
{
  Cloud c = ball(2000, 0.02);
  GravityTree t = make_tree(c);
  for (int k : {0, 1, t.nodes() / 3, t.nodes() - 1}) {
    const GravityNode &n = t.node(k);
    double M = 0.0, X[3] = {0.0, 0.0, 0.0}, hmax = 0.0;
    for (int j = n.first; j < n.first + n.count; j++) {
      const int i = t.index(j);
      M += c.m[i];
      for (int d = 0; d < 3; d++) X[d] += c.m[i] * c.x[i][d];
      hmax = std::max(hmax, c.h[i]);
    }
    for (double &v : X) v /= M;
    double q[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0}, bmax = 0.0;
    for (int j = n.first; j < n.first + n.count; j++) {
      const int i = t.index(j);
      const double s[3] = {c.x[i][0] - X[0], c.x[i][1] - X[1], c.x[i][2] - X[2]};
      q[0] += c.m[i] * s[0] * s[0];
      q[1] += c.m[i] * s[1] * s[1];
      q[2] += c.m[i] * s[2] * s[2];
      q[3] += c.m[i] * s[0] * s[1];
      q[4] += c.m[i] * s[0] * s[2];
      q[5] += c.m[i] * s[1] * s[2];
      bmax = std::max(bmax, std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]));
    }
    EXPECT_NEAR(n.m, M, 1e-14 * M);
    EXPECT_NEAR(n.x, X[0], 1e-13);
    EXPECT_NEAR(n.y, X[1], 1e-13);
    EXPECT_NEAR(n.z, X[2], 1e-13);
    for (int a = 0; a < 6; a++) EXPECT_NEAR(n.q[a], q[a], 1e-12 * (std::fabs(q[0]) + 1e-300));
    EXPECT_GE(n.bmax, bmax * (1.0 - 1e-14));    // a bound on the particles' distances
    EXPECT_EQ(n.hmax, hmax);
  }
}

TEST(GravityTree, OpeningEveryNodeIsDirectSummation)
{
  Cloud c = ball(1500, 0.03);
  GravityTree t = make_tree(c);
  OpeningCriterion crit;
  crit.theta = 1e-9;
  std::vector<double> acc, pot;
  tree_sums<true>(t, crit, 32, acc, pot);
  for (int i = 0; i < c.n(); i += 7) {
    double a[3], phi;
    direct<true>(c, i, a, phi);
    const double amag = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int d = 0; d < 3; d++) EXPECT_NEAR(acc[3 * i + d], a[d], 1e-12 * amag);
    EXPECT_NEAR(pot[i], phi, 1e-12 * std::fabs(phi));
  }
}

// the per-particle RMS relative force error of the tree against direct summation
double rms_error(Cloud &c, const OpeningCriterion &crit, double *interactions = nullptr)
{
  GravityTree t = make_tree(c);
  std::vector<double> acc, pot;
  tree_sums<false>(t, crit, 32, acc, pot, interactions);
  double s2 = 0.0;
  for (int i = 0; i < c.n(); i++) {
    double a[3], phi;
    direct<false>(c, i, a, phi);
    double d2 = 0.0, a2 = 0.0;
    for (int d = 0; d < 3; d++) {
      d2 += (acc[3 * i + d] - a[d]) * (acc[3 * i + d] - a[d]);
      a2 += a[d] * a[d];
    }
    s2 += d2 / a2;
  }
  return std::sqrt(s2 / c.n());
}

TEST(GravityTree, ErrorFallsWithTheOpeningAngleAndTheQuadrupoleCounts)
{
  Cloud c = ball(4000, 1e-4);
  double errors[3], cost[3];
  const double thetas[3] = {0.7, 0.5, 0.3};
  for (int k = 0; k < 3; k++) {
    OpeningCriterion crit;
    crit.theta = thetas[k];
    errors[k] = rms_error(c, crit, &cost[k]);
  }
  // measured (4 000 particles): 9.2e-3, 2.2e-3, 4.0e-4
  EXPECT_LT(errors[0], 1.2e-2);
  EXPECT_LT(errors[1], 3e-3);
  EXPECT_LT(errors[2], 6e-4);
  EXPECT_GT(errors[0], errors[1]);
  EXPECT_GT(errors[1], errors[2]);
  EXPECT_LT(cost[0], cost[2]);
}

TEST(GravityTree, RelativeCriterionFollowsAlpha)
{
  Cloud c = ball(4000, 1e-4);
  // the targets' accelerations of a first (geometric) evaluation, as |a_old|
  GravityTree t = make_tree(c);
  std::vector<double> acc, pot;
  OpeningCriterion geometric;
  geometric.theta = 0.5;
  tree_sums<false>(t, geometric, 32, acc, pot);
  double amin = INFINITY;
  for (int i = 0; i < c.n(); i++)
    amin = std::min(amin,
                    std::sqrt(acc[3 * i] * acc[3 * i] + acc[3 * i + 1] * acc[3 * i + 1] +
                              acc[3 * i + 2] * acc[3 * i + 2]));
  // with the smallest |a| of the cloud for every group: stricter than per group, enough to
  // see alpha act
  OpeningCriterion tight, loose;
  tight.alpha = 1e-3;
  loose.alpha = 1e-1;
  auto error = [&](const OpeningCriterion &crit) {
    const SoftenedKernel &soft = softened_kernel(KernelType::CUBIC);
    std::vector<int> groups, accepted, leaves;
    t.groups(32, groups);
    GravityInteractions lists;
    double s2 = 0.0;
    for (int g : groups) {
      const GravityNode &n = t.node(g);
      const double b = n.bmax;    // (a box around the node's sphere)
      TargetBox box{{n.x - b, n.y - b, n.z - b}, {n.x + b, n.y + b, n.z + b}, n.hmax, amin};
      lists.clear();
      accepted.clear();
      leaves.clear();
      t.walk(box, crit, accepted, leaves);
      for (int a : accepted) lists.add_node(t.node(a));
      for (int l : leaves) lists.add_leaf(t, t.node(l), 0);
      lists.finish();
      for (int k = n.first; k < n.first + n.count; k++) {
        double a[3], p, ref[3], pref;
        lists.evaluate<true, false>(t.x()[k], t.y()[k], t.z()[k], t.h()[k], 0.0, k, soft,
                                    KernelType::CUBIC, 2.0, a, p);
        direct<false>(c, t.index(k), ref, pref);
        const double d2 = (a[0] - ref[0]) * (a[0] - ref[0]) + (a[1] - ref[1]) * (a[1] - ref[1]) +
            (a[2] - ref[2]) * (a[2] - ref[2]);
        s2 += d2 / (ref[0] * ref[0] + ref[1] * ref[1] + ref[2] * ref[2]);
      }
    }
    return std::sqrt(s2 / c.n());
  };
  const double e_tight = error(tight), e_loose = error(loose);
  EXPECT_LT(e_tight, 5e-4);
  EXPECT_GT(e_loose, 3.0 * e_tight);
}

TEST(GravityTree, BuildDoesNotDependOnTheInputOrder)
{
  Cloud c = ball(2000, 0.02, 7);
  // the same particles in another order, with the same tie numbers
  std::vector<int> perm(c.n());
  std::iota(perm.begin(), perm.end(), 0);
  std::mt19937 rng(3);
  std::shuffle(perm.begin(), perm.end(), rng);
  Cloud d;
  for (int i : perm) {
    d.xyz.insert(d.xyz.end(), &c.xyz[3 * i], &c.xyz[3 * i] + 3);
    d.m.push_back(c.m[i]);
    d.h.push_back(c.h[i]);
    d.zo.push_back(c.zo[i]);
  }
  d.index();
  for (int k = 0; k < d.n(); k++) d.tie[k] = c.tie[perm[k]];
  GravityTree a = make_tree(c), b = make_tree(d);
  ASSERT_EQ(a.nodes(), b.nodes());
  for (int k = 0; k < a.size(); k++) {
    EXPECT_EQ(a.x()[k], b.x()[k]);
    EXPECT_EQ(perm[b.index(k)], a.index(k));
  }
  OpeningCriterion crit;
  std::vector<double> fa, pa, fb, pb;
  tree_sums<true>(a, crit, 32, fa, pa);
  tree_sums<true>(b, crit, 32, fb, pb);
  for (int k = 0; k < d.n(); k++)
    for (int dd = 0; dd < 3; dd++) EXPECT_EQ(fb[3 * k + dd], fa[3 * perm[k] + dd]);
}

TEST(GravityTree, OneFarParticleKeepsLeavesSmall)
{
  // keys quantise the bounding cube in 2^21 cells: a particle 1e12 away puts all the others in
  // one cell; they are split at the middle of their box instead
  Cloud c = ball(2000, 0.01);
  c.xyz.insert(c.xyz.end(), {1e12, 0.0, 0.0});
  c.m.push_back(1e-3);
  c.h.push_back(0.01);
  c.zo.push_back(0.0);
  c.index();
  GravityTree t = make_tree(c);
  int largest = 0;
  for (int k = 0; k < t.nodes(); k++)
    if (t.node(k).nchild == 0) largest = std::max(largest, t.node(k).count);
  EXPECT_LE(largest, 8);
  double interactions;
  OpeningCriterion crit;
  std::vector<double> acc, pot;
  tree_sums<false>(t, crit, 32, acc, pot, &interactions);
  EXPECT_LT(interactions, 1000.0);    // not every particle
  double a[3], phi;
  direct<false>(c, 0, a, phi);
  EXPECT_NEAR(acc[0], a[0], 5e-3 * std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]));
}

TEST(GravityTree, CoincidentParticlesHaveAFinitePotentialAndNoForce)
{
  Cloud c;
  for (int i = 0; i < 50; i++) {
    c.xyz.insert(c.xyz.end(), {0.25, 0.5, 0.75});
    c.m.push_back(0.02);
    c.h.push_back(0.1);
    c.zo.push_back(-0.01);
  }
  c.index();
  GravityTree t = make_tree(c);
  std::vector<double> acc, pot;
  OpeningCriterion crit;
  tree_sums<true>(t, crit, 32, acc, pot);
  const double phi0 = 49 * 0.02 * -1.4 / 0.1;    // phi(0, h) = -1.4/h for M4
  for (int i = 0; i < c.n(); i++) {
    EXPECT_EQ(acc[3 * i] * acc[3 * i] + acc[3 * i + 1] * acc[3 * i + 1], 0.0);
    EXPECT_NEAR(pot[i], phi0, 1e-12 * std::fabs(phi0));
  }
}

TEST(GravityTree, ImportedMultipolesActAsTheirParticles)
{
  // cluster A at the origin, cluster B at distance 10: B sent as its root's multipole
  Cloud a = ball(300, 0.01, 11), b = ball(500, 0.01, 12);
  for (int i = 0; i < b.n(); i++) b.xyz[3 * i] += 10.0;
  b.index();
  GravityTree tb = make_tree(b);
  GravityItems items;
  const GravityNode &root = tb.root();
  items.add_multipole(root.x, root.y, root.z, root.m, root.q, root.bmax, 1);
  GravityTree imported;
  imported.build(items);
  ASSERT_EQ(imported.size(), 1);
  EXPECT_EQ(imported.root().nparticles, 0);
  const SoftenedKernel &soft = softened_kernel(KernelType::CUBIC);
  GravityInteractions lists;
  std::vector<int> accepted, leaves;
  TargetBox box{{-1.0, -1.0, -1.0}, {1.0, 1.0, 1.0}, 0.02, 0.0};
  OpeningCriterion crit;
  imported.walk(box, crit, accepted, leaves);
  for (int n : accepted) lists.add_node(imported.node(n));
  for (int l : leaves) lists.add_leaf(imported, imported.node(l), -1);
  lists.finish();
  EXPECT_EQ(lists.multipoles(), 1);
  for (int i = 0; i < a.n(); i += 13) {
    double acc[3], pot;
    lists.evaluate<true, false>(a.x[i][0], a.x[i][1], a.x[i][2], a.h[i], 0.0, -1, soft,
                                KernelType::CUBIC, 2.0, acc, pot);
    double ref[3] = {0.0, 0.0, 0.0}, pref = 0.0;
    for (int j = 0; j < b.n(); j++) {
      const double d[3] = {a.x[i][0] - b.x[j][0], a.x[i][1] - b.x[j][1], a.x[i][2] - b.x[j][2]};
      const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      pref -= b.m[j] / r;
      for (int k = 0; k < 3; k++) ref[k] -= b.m[j] * d[k] / (r * r * r);
    }
    // (b/d)^3 ~ (1/9)^3: the octupole and beyond
    const double amag = std::sqrt(ref[0] * ref[0] + ref[1] * ref[1] + ref[2] * ref[2]);
    for (int k = 0; k < 3; k++) EXPECT_NEAR(acc[k], ref[k], 3e-3 * amag);
    EXPECT_NEAR(pot, pref, 1e-3 * std::fabs(pref));
  }
}
