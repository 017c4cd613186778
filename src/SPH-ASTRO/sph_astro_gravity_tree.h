/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The gravity tree of kspace_style tree/sph/astro/gravity: an octree (Barnes & Hut 1986,
// Nature 324, 446) whose nodes carry the multipole moments of their mass to quadrupole order
// (monopole and second moment about the centre of mass; Hernquist 1987, ApJS 64, 715;
// McMillan & Aarseth 1993, ApJ 414, 200), the radius b_max around the centre of mass that holds
// all their mass (Salmon & Warren 1994, J. Comput. Phys. 111, 136) and the largest softening
// length among their particles (as GADGET's and Phantom's trees keep h_max per node).
//
// Items are particles (position, mass, softening length h, zeta/Omega of the adaptive
// softening) or, in a tree of imported items, multipoles of another rank's nodes (position =
// centre of mass, mass, second moment, radius b). The structure comes from Morton keys (Warren
// & Salmon 1993) of the positions at the build in the bounding cube of the items: items sorted
// by key (ties by a caller's number, the atom tag, so that the order does not depend on the
// order of the input), and a node is a run of items sharing a key prefix; chains of nodes with
// one child are collapsed. A leaf holds at most leaf_size items; items whose keys are equal
// (closer than the key resolution, which one item far from the rest makes coarse) are halved
// at the middle of their box instead, down to coincident items. A leaf's particles come before
// its multipole items.
//
// refit() recomputes every node's moments, b_max and h_max from the items' current positions,
// bottom-up, without changing the structure: the tree made at a re-neighbouring stays valid as
// the particles move (only its shape may loosen).
//
// walk() lists, for a group of targets inside a box, the nodes whose multipole expansion is
// accepted for every point of that box, and the leaves to be summed item by item (Barnes 1990,
// J. Comput. Phys. 87, 161: one walk per group of targets). A node is accepted when
//   (a) the box lies outside the sphere of radius b_max around the node's centre of mass by
//       more than the softening support: d - b_max >= R max(h_group, h_max), d the distance
//       from the centre of mass to the nearest point of the box, R the kernel radius (then no
//       particle of the node is inside any target's kernel and none of its targets inside its
//       particles' kernels: the Newtonian expansion is exact up to its truncation), and
//   (b) geometric criterion: b_max < theta d (Salmon & Warren 1994, the "b_max" form of the
//       Barnes & Hut opening angle); or relative criterion (Springel 2005, MNRAS 364, 1105,
//       eq. 18, to the order of the first term left out, the octupole for a quadrupole
//       expansion): G M b_max^3 / d^5 <= alpha |a_old|_min, |a_old|_min the smallest
//       acceleration of the group's targets at their last evaluation, and b_max < 0.9 d (the
//       expansion converges outside the sphere b_max; the bound keeps its remainder within
//       10x the octupole term). A group with a target not yet evaluated (|a_old| = 0) takes the
//       geometric criterion.

#ifndef LMP_SPH_ASTRO_GRAVITY_TREE_H
#define LMP_SPH_ASTRO_GRAVITY_TREE_H

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace SPHAstro {

// the items of a tree built from a list (a tree of imported items): particles and multipoles
struct GravityItems {
  std::vector<double> x, y, z, m, h, zo;    // centre, mass, softening length, zeta/Omega
  std::vector<int> mp;                      // index of the item's multipole (-1: a particle)
  std::vector<double> moments;    // per multipole: second moment (6), radius holding the mass
  std::vector<int64_t> tie;       // order among equal keys

  int size() const { return static_cast<int>(x.size()); }
  void clear();
  void add_particle(double px, double py, double pz, double pm, double ph, double pzo,
                    int64_t order);
  // qm: sum m s_a s_b about (px, py, pz), as xx yy zz xy xz yz
  void add_multipole(double px, double py, double pz, double pm, const double *qm, double pb,
                     int64_t order);
};

struct GravityNode {
  double x, y, z, m;    // centre of mass, mass
  double q[6];          // second moment about the centre of mass: xx yy zz xy xz yz
  double bmax;          // all of the node's mass lies within bmax of (x, y, z)
  double hmax;          // largest softening length of the node's particles (0: none)
  int first, count;     // items [first, first + count) in tree order
  int nparticles;       // leaves: items [first, first + nparticles) are particles
  int child, nchild;    // children: nodes [child, child + nchild); nchild = 0: a leaf
};

// a group of targets: the box holding them, their largest softening length and, for the
// relative criterion, their smallest acceleration at the last evaluation (0: unknown)
struct TargetBox {
  double lo[3], hi[3];
  double hmax;
  double amin;
};

struct OpeningCriterion {
  static constexpr double RELATIVE_THETA_MAX = 0.9;    // relative: b_max < 0.9 d as well
  double theta = 0.5;            // geometric: b_max < theta d (also for targets without |a_old|)
  double alpha = 0.0;            // > 0: relative criterion G M b_max^3 / d^5 <= alpha |a_old|
  double G = 1.0;                // gravitational constant (relative criterion)
  double kernel_radius = 2.0;    // R: the softening support is R h
  double cutoff = INFINITY;      // nodes farther than this from the targets' box are left out
};

class GravityTree {
 public:
  static constexpr int KEY_BITS = 21;    // per dimension: 63-bit Morton keys
  static constexpr int DEFAULT_LEAF_SIZE = 16;

  explicit GravityTree(int leaf_size = DEFAULT_LEAF_SIZE) : leaf_size_(leaf_size) {}

  // structure from the positions of particles 0..n-1 (x[i][0..2]), ties by tie[i]; the moments
  // need refit()
  void build(int n, const double *const *x, const int64_t *tie);
  // moments, b_max, h_max from the particles' current values, indexed as at the build:
  // item(i, x, y, z, m, h, zo) gives particle i's position, mass, softening length and
  // zeta/Omega
  template <class Item> void refit(Item &&item)
  {
    const int n = size();
    for (int k = 0; k < n; k++) item(perm_[k], x_[k], y_[k], z_[k], m_[k], h_[k], zo_[k]);
    moments();
  }
  // structure and moments of a list of particles and multipoles (whose arrays the tree takes:
  // items is empty afterwards)
  void build(GravityItems &items);

  int size() const { return static_cast<int>(x_.size()); }
  int nodes() const { return static_cast<int>(nodes_.size()); }
  bool empty() const { return nodes_.empty(); }
  const GravityNode &node(int k) const { return nodes_[k]; }
  const GravityNode &root() const { return nodes_[0]; }
  // the item at tree position k: its index at the build (particles of build(n, ...)) or in the
  // item list, and its current values
  int index(int k) const { return perm_[k]; }
  const double *x() const { return x_.data(); }
  const double *y() const { return y_.data(); }
  const double *z() const { return z_.data(); }
  const double *m() const { return m_.data(); }
  const double *h() const { return h_.data(); }
  const double *zo() const { return zo_.data(); }
  // multipole items (trees of imported items): second moment (6 values) and radius
  const double *item_q(int k) const { return &mp_moments_[7 * mp_[k]]; }
  double item_b(int k) const
  {
    return mp_.empty() || mp_[k] < 0 ? 0.0 : mp_moments_[7 * mp_[k] + 6];
  }
  int depth() const { return depth_; }

  // the accepted nodes (their multipoles serve every target of the box) and the leaves whose
  // items are summed one by one, in a fixed order (depth first); nodes whose sphere b_max lies
  // crit.cutoff or farther from the targets' box are left out
  void walk(const TargetBox &box, const OpeningCriterion &crit, std::vector<int> &accepted,
            std::vector<int> &leaves) const;
  // the same for several boxes: a node is accepted when it is for every one of them
  void walk(const std::vector<TargetBox> &boxes, const OpeningCriterion &crit,
            std::vector<int> &accepted, std::vector<int> &leaves) const;
  // is node k's multipole accepted for every point of box
  bool accepted(const GravityNode &n, const TargetBox &box, const OpeningCriterion &crit) const;

  // the nodes whose particles serve as targets in groups of at most group_size: the smallest
  // nodes holding at most group_size items (leaves where a leaf holds more), in tree order
  void groups(int group_size, std::vector<int> &out) const;

  double memory_usage() const;

 private:
  int leaf_size_;
  int depth_ = 0;
  std::vector<GravityNode> nodes_;
  std::vector<int> perm_;    // tree position -> index at the build
  std::vector<double> x_, y_, z_, m_, h_, zo_;
  std::vector<int> mp_;                 // trees of items: the item's multipole (-1: particle)
  std::vector<double> mp_moments_;      // ... its second moment and radius (7 each)
  std::vector<uint64_t> keys_;          // the build's keys in tree order
  std::vector<double> sx_, sy_, sz_;    // the build's positions in tree order
  mutable std::vector<int> stack_;      // of walk() and groups()

  void make_structure(int n, const double *px, const double *py, const double *pz,
                      const int64_t *tie, const std::vector<char> *is_multipole);
  void make_node(int index, int first, int count, int level);
  void split_equal_keys(int index, int first, int count, int level);
  void moments();
};

inline bool GravityTree::accepted(const GravityNode &n, const TargetBox &box,
                                  const OpeningCriterion &crit) const
{
  // distance from the centre of mass to the nearest point of the box
  double d2 = 0.0;
  const double c[3] = {n.x, n.y, n.z};
  for (int d = 0; d < 3; d++) {
    const double e = std::max(std::max(box.lo[d] - c[d], c[d] - box.hi[d]), 0.0);
    d2 += e * e;
  }
  // (a) outside the softening support of every pair
  const double rs = n.bmax + crit.kernel_radius * std::max(box.hmax, n.hmax);
  if (d2 <= rs * rs) return false;
  // (b) the expansion's error
  const double b2 = n.bmax * n.bmax;
  if (crit.alpha > 0.0 && box.amin > 0.0) {
    constexpr double tmax2 =
        OpeningCriterion::RELATIVE_THETA_MAX * OpeningCriterion::RELATIVE_THETA_MAX;
    return b2 < tmax2 * d2 &&
        crit.G * n.m * b2 * n.bmax <= crit.alpha * box.amin * d2 * d2 * std::sqrt(d2);
  }
  return b2 < crit.theta * crit.theta * d2;
}

}    // namespace SPHAstro

#endif
