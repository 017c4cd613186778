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
  perm_.assign(index, index + n);
  nodes_.clear();
  leaves_.clear();
  slot_.clear();
  if (n == 0) return;
  nodes_.reserve(4 * (n / LEAF_SIZE + 1));
  nodes_.emplace_back();
  make_node(x, radius, 0, 0, n);
  pos_.resize(3 * static_cast<std::size_t>(n));
  rad_.resize(n);
  int top = 0;
  for (int k = 0; k < n; k++) top = std::max(top, perm_[k] + 1);
  slot_.assign(top, -1);
  for (int k = 0; k < n; k++) {
    const int j = perm_[k];
    for (int d = 0; d < 3; d++) pos_[3 * k + d] = x[j][d];
    rad_[k] = radius[j];
    slot_[j] = k;
  }
}

// (children are stored after their parent: one backward sweep sees them first)
void NeighbourTree::update_radii(const double *radius)
{
  const int n = static_cast<int>(perm_.size());
  for (int k = 0; k < n; k++) rad_[k] = radius[perm_[k]];
  for (int id = static_cast<int>(nodes_.size()) - 1; id >= 0; id--) {
    Node &node = nodes_[id];
    if (node.left < 0) {
      node.rmax = 0.0;
      for (int k = node.begin; k < node.end; k++) node.rmax = std::max(node.rmax, rad_[k]);
    } else
      node.rmax = std::max(nodes_[node.left].rmax, nodes_[node.left + 1].rmax);
  }
}

// node id over perm_[begin..end): split at the median of its box's longest side, the two
// children stored side by side (depth ~log2(n / LEAF_SIZE), well inside the query stack)
void NeighbourTree::make_node(double **x, const double *radius, int id, int begin, int end)
{
  Node node;
  node.begin = begin;
  node.end = end;
  node.left = -1;
  node.rmax = 0.0;
  for (int d = 0; d < 3; d++) {
    node.lo[d] = x[perm_[begin]][d];
    node.hi[d] = node.lo[d];
  }
  for (int k = begin; k < end; k++) {
    const int j = perm_[k];
    for (int d = 0; d < 3; d++) {
      node.lo[d] = std::min(node.lo[d], x[j][d]);
      node.hi[d] = std::max(node.hi[d], x[j][d]);
    }
    node.rmax = std::max(node.rmax, radius[j]);
  }
  if (end - begin > LEAF_SIZE) {
    int axis = 0;
    for (int d = 1; d < 3; d++)
      if (node.hi[d] - node.lo[d] > node.hi[axis] - node.lo[axis]) axis = d;
    const int mid = begin + (end - begin) / 2;
    std::nth_element(perm_.begin() + begin, perm_.begin() + mid, perm_.begin() + end,
                     [x, axis](int a, int b) {
                       return x[a][axis] < x[b][axis] || (x[a][axis] == x[b][axis] && a < b);
                     });
    node.left = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    nodes_.emplace_back();
    make_node(x, radius, node.left, begin, mid);
    make_node(x, radius, node.left + 1, mid, end);
  } else
    leaves_.push_back(id);
  nodes_[id] = node;
}

}    // namespace SPHAstro
