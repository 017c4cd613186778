/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

#include "sph_astro_neighbour_tree.h"

#include <algorithm>

namespace SPHAstro {

void NeighbourTree::build(double **x, const double *radius, const int *index, int n)
{
  nodes_.clear();
  leaves_.clear();
  slot_.clear();
  perm_.resize(n);
  if (n == 0) return;
  // (the points' copies side by side: the splits move them, not indices into x; they stay as
  // the build's positions and radii in tree order)
  items_.resize(n);
  for (int k = 0; k < n; k++) {
    const int j = index[k];
    items_[k] = {{x[j][0], x[j][1], x[j][2]}, radius[j], j};
  }
  nodes_.reserve(4 * (n / LEAF_SIZE + 1));
  nodes_.emplace_back();
  depth_ = 0;
  make_node(0, 0, n, 0);
  int top = 0;
  for (int k = 0; k < n; k++) top = std::max(top, items_[k].index + 1);
  slot_.assign(top, -1);
  for (int k = 0; k < n; k++) {
    perm_[k] = items_[k].index;
    slot_[perm_[k]] = k;
  }
}

// (children are stored after their parent: one backward sweep sees them first)
void NeighbourTree::update_radii(const double *radius)
{
  const int n = static_cast<int>(perm_.size());
  for (int k = 0; k < n; k++) items_[k].radius = radius[perm_[k]];
  for (int id = static_cast<int>(nodes_.size()) - 1; id >= 0; id--) {
    Node &node = nodes_[id];
    if (node.left < 0) {
      node.rmax = 0.0;
      for (int k = node.begin; k < node.end; k++) node.rmax = std::max(node.rmax, items_[k].radius);
    } else
      node.rmax = std::max(nodes_[node.left].rmax, nodes_[node.left + 1].rmax);
  }
}

// node id over items_[begin..end): split across its box's longest side, the two children
// stored side by side
void NeighbourTree::make_node(int id, int begin, int end, int depth)
{
  depth_ = std::max(depth_, depth);
  Node node;
  node.begin = begin;
  node.end = end;
  node.left = -1;
  node.rmax = 0.0;
  for (int d = 0; d < 3; d++) {
    node.lo[d] = items_[begin].x[d];
    node.hi[d] = node.lo[d];
  }
  for (int k = begin; k < end; k++) {
    const Item &item = items_[k];
    for (int d = 0; d < 3; d++) {
      node.lo[d] = std::min(node.lo[d], item.x[d]);
      node.hi[d] = std::max(node.hi[d], item.x[d]);
    }
    node.rmax = std::max(node.rmax, item.radius);
  }
  if (end - begin > LEAF_SIZE) {
    int axis = 0;
    for (int d = 1; d < 3; d++)
      if (node.hi[d] - node.lo[d] > node.hi[axis] - node.lo[axis]) axis = d;
    // at the middle of the box (branch-free: the comparisons are unpredictable); at the median
    // (ties by point index) if that leaves a side empty, and below SPATIAL_DEPTH, so that a
    // tight cluster cannot make the tree deeper than SPATIAL_DEPTH + log2(n / LEAF_SIZE)
    const double split = 0.5 * (node.lo[axis] + node.hi[axis]);
    int mid = begin;
    if (depth < SPATIAL_DEPTH)
      for (int k = begin; k < end; k++) {
        const bool left = items_[k].x[axis] < split;
        std::swap(items_[mid], items_[k]);
        mid += left;
      }
    if (mid == begin || mid == end) {
      mid = begin + (end - begin) / 2;
      std::nth_element(items_.begin() + begin, items_.begin() + mid, items_.begin() + end,
                       [axis](const Item &a, const Item &b) {
                         return a.x[axis] < b.x[axis] ||
                             (a.x[axis] == b.x[axis] && a.index < b.index);
                       });
    }
    node.left = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    nodes_.emplace_back();
    make_node(node.left, begin, mid, depth + 1);
    make_node(node.left + 1, mid, end, depth + 1);
  } else
    leaves_.push_back(id);
  nodes_[id] = node;
}

void NeighbourTree::sort_by_index(std::vector<unsigned long long> &keys,
                                  std::vector<unsigned long long> &scratch, std::vector<int> &count)
{
  unsigned top = 0;
  for (unsigned long long key : keys) top = std::max(top, static_cast<unsigned>(key >> 32));
  int bits = 0;
  while (bits < 32 && (top >> bits) != 0) bits++;
  const int passes = (bits + 10) / 11;
  if (passes == 0) return;
  const int digit = (bits + passes - 1) / passes;
  const unsigned long long mask = (1ULL << digit) - 1ULL;
  scratch.resize(keys.size());
  count.resize(std::size_t(1) << digit);
  for (int pass = 0; pass < passes; pass++) {
    const int shift = 32 + pass * digit;
    std::fill(count.begin(), count.end(), 0);
    for (unsigned long long key : keys) count[(key >> shift) & mask]++;
    int offset = 0;
    for (int &c : count) {
      const int here = c;
      c = offset;
      offset += here;
    }
    for (unsigned long long key : keys) scratch[count[(key >> shift) & mask]++] = key;
    keys.swap(scratch);
  }
}

}    // namespace SPHAstro
