/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The package's neighbour search: a k-d tree over a rank's owned and ghost particles whose
// nodes know the bounding box of their particles and the largest search radius r_j among them,
// as the trees of Phantom (Price et al. 2018, PASA 35, e031, sec. 2.1.5) and GADGET (Springel
// 2005, MNRAS 364, 1105, sec. 3.1) keep h_max per node. A query visits exactly the particles j
// with
//     |x_j - c| < max(r_c, r_j) + pad
// (gather and scatter neighbours of a point c with radius r_c), descending only into nodes
// whose box lies closer than max(r_c, r_max of the node) + pad (+ how far particles may have
// moved since the build). The cost of a query follows the number of particles it finds, not
// the range of r: a particle in a dense clump does not scan the neighbourhood of the largest h.
//
// Nodes split their points at the middle of their box's longest side (cells of regular shape,
// as GADGET's octree has). The tree keeps the positions and radii of the build in its
// own order (contiguous leaves).
// query_leaf() serves all particles of one leaf at once: one traversal collects the candidates
// of the leaf's box, and each particle of the leaf then keeps its own from them.

#ifndef LMP_SPH_ASTRO_NEIGHBOUR_TREE_H
#define LMP_SPH_ASTRO_NEIGHBOUR_TREE_H

#include <algorithm>
#include <cstddef>
#include <vector>

namespace SPHAstro {

class NeighbourTree {
 public:
  static constexpr int LEAF_SIZE = 32;
  // splits at the middle of a node's box down to this depth, at the median below; a query's
  // stack holds one node per level: SPATIAL_DEPTH + 26 levels of median splits for n < 2^31
  static constexpr int SPATIAL_DEPTH = 48;
  static constexpr int STACK = 128;

  // build over the points index[0..n) of x, with search radii radius[] (per point of x)
  void build(double **x, const double *radius, const int *index, int n);
  int size() const { return static_cast<int>(perm_.size()); }
  // the largest depth of a node (the root: 0)
  int depth() const { return depth_; }
  int leaves() const { return static_cast<int>(leaves_.size()); }
  // the points of leaf l: tree positions [begin, end); their indices point(k)
  int leaf_begin(int l) const { return nodes_[leaves_[l]].begin; }
  int leaf_end(int l) const { return nodes_[leaves_[l]].end; }
  int point(int k) const { return perm_[k]; }
  // the tree position of point index p (-1 if not in the tree), and its position at the build
  int slot(int p) const { return p < static_cast<int>(slot_.size()) ? slot_[p] : -1; }
  const double *build_position(int k) const { return items_[k].x; }
  // new search radii (radius[], per point as at the build): the nodes' largest radii follow
  void update_radii(const double *radius);

  // visit(j, r2) for every point j of the tree with |x_j - c|^2 = r2 < (max(rc, radius_j) +
  // pad)^2, at the current positions x; motion: how far points may have moved since the build
  // (0 at the build), so that no node that could hold such a point is skipped
  template <class VISIT>
  void query(double **x, const double *radius, const double *c, double rc, double pad,
             double motion, VISIT &&visit) const
  {
    if (nodes_.empty()) return;
    int stack[STACK];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node &node = nodes_[stack[--top]];
      const double reach = (rc > node.rmax ? rc : node.rmax) + pad + motion;
      if (box_point_distance2(node, c) >= reach * reach) continue;
      if (node.left < 0) {
        for (int k = node.begin; k < node.end; k++) {
          const int j = perm_[k];
          const double dx = x[j][0] - c[0], dy = x[j][1] - c[1], dz = x[j][2] - c[2];
          const double r2 = dx * dx + dy * dy + dz * dz;
          const double rj = (rc > radius[j] ? rc : radius[j]) + pad;
          if (r2 < rj * rj) visit(j, r2);
        }
      } else {
        stack[top++] = node.left + 1;
        stack[top++] = node.left;
      }
    }
  }

  // every point of leaf l with its neighbours at the build's positions: for each tree
  // position k of the leaf, row(k, candidates, n) gets the tree positions c of all points with
  // |x_c - x_k| < max(r_k, r_c) + pad (k itself included), in the order of their point index
  template <class ROW> void query_leaf(int l, double pad, ROW &&row)
  {
    const Node &leaf = nodes_[leaves_[l]];
    candidates_.clear();
    int stack[STACK];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node &node = nodes_[stack[--top]];
      const double reach = (leaf.rmax > node.rmax ? leaf.rmax : node.rmax) + pad;
      if (box_box_distance2(node, leaf) >= reach * reach) continue;
      if (node.left < 0) {
        std::size_t n = candidates_.size();
        candidates_.resize(n + (node.end - node.begin));
        for (int c = node.begin; c < node.end; c++) {
          const double rc = std::max(leaf.rmax, items_[c].radius) + pad;
          candidates_[n] = c;
          n += box_point_distance2(leaf, items_[c].x) < rc * rc;
        }
        candidates_.resize(n);
      } else {
        stack[top++] = node.left + 1;
        stack[top++] = node.left;
      }
    }
    // by point index: keys (index, tree position) sort without indirection
    const int nc = static_cast<int>(candidates_.size());
    keys_.resize(nc);
    for (int m = 0; m < nc; m++)
      keys_[m] = (static_cast<unsigned long long>(perm_[candidates_[m]]) << 32) |
          static_cast<unsigned>(candidates_[m]);
    sort_by_index(keys_, sorted_, digit_count_);
    // the candidates' positions and radii side by side for the scans below
    cand_.resize(4 * static_cast<std::size_t>(nc));
    found_.resize(nc);
    int *cand_index = candidates_.data();
    double *cx = cand_.data(), *cy = cx + nc, *cz = cy + nc, *cr = cz + nc;
    for (int m = 0; m < nc; m++) {
      const int c = static_cast<int>(keys_[m] & 0xffffffffULL);
      cand_index[m] = c;
      cx[m] = items_[c].x[0];
      cy[m] = items_[c].x[1];
      cz[m] = items_[c].x[2];
      cr[m] = items_[c].radius;
    }
    int *found = found_.data();
    for (int k = leaf.begin; k < leaf.end; k++) {
      const int n =
          select_within(cx, cy, cz, cr, cand_index, nc, items_[k].x, items_[k].radius, pad, found);
      row(k, found, n);
    }
  }

  // the candidates m < nc (positions cx, cy, cz, radii cr) with
  //     (cx_m - c_x)^2 + (cy_m - c_y)^2 + (cz_m - c_z)^2 < (max(rc, cr_m) + pad)^2:
  // their index[m], in order, into found; returns how many. With AVX-512 where the processor has
  // it (chosen at run time), 16 candidates per step with the same roundings: the same result
  static int select_within(const double *cx, const double *cy, const double *cz, const double *cr,
                           const int *index, int nc, const double *c, double rc, double pad,
                           int *found);

  // keys (index << 32 | payload, index < 2^31) in increasing index, payloads of equal indices
  // in their order: a least significant digit first radix sort over the bits of the largest
  // index (no comparisons to mispredict); scratch and count are its work space
  static void sort_by_index(std::vector<unsigned long long> &keys,
                            std::vector<unsigned long long> &scratch, std::vector<int> &count);

  double memory_usage() const
  {
    return static_cast<double>(
        nodes_.capacity() * sizeof(Node) +
        (perm_.capacity() + leaves_.capacity() + candidates_.capacity() + found_.capacity() +
         slot_.capacity()) *
            sizeof(int) +
        (keys_.capacity() + sorted_.capacity() + cand_.capacity()) * sizeof(double) +
        digit_count_.capacity() * sizeof(int) + items_.capacity() * sizeof(Item));
  }

 private:
  struct Node {
    double lo[3], hi[3];
    double rmax;
    int begin, end;    // points perm_[begin..end)
    int left;          // children left, left + 1; -1: leaf
  };
  std::vector<Node> nodes_;
  std::vector<int> perm_, leaves_, candidates_, found_, slot_;
  std::vector<unsigned long long> keys_;
  std::vector<double> cand_;    // x, y, z, r of a leaf's candidates
  struct Item {
    double x[3];
    double radius;
    int index;
  };
  std::vector<Item> items_;    // positions and radii at the build, in tree order

  int depth_ = 0;

  void make_node(int id, int begin, int end, int depth);
  std::vector<unsigned long long> sorted_;
  std::vector<int> digit_count_;

  // (branch-free: the comparisons of a traversal are unpredictable)
  static double box_point_distance2(const Node &node, const double *c)
  {
    double d2 = 0.0;
    for (int d = 0; d < 3; d++) {
      const double gap = std::max(std::max(node.lo[d] - c[d], c[d] - node.hi[d]), 0.0);
      d2 += gap * gap;
    }
    return d2;
  }
  static double box_box_distance2(const Node &a, const Node &b)
  {
    double d2 = 0.0;
    for (int d = 0; d < 3; d++) {
      const double gap = std::max(std::max(a.lo[d] - b.hi[d], b.lo[d] - a.hi[d]), 0.0);
      d2 += gap * gap;
    }
    return d2;
  }
};

}    // namespace SPHAstro

#endif
