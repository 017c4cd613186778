/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The gravity tree: structure from Morton keys, moments, walk (sph_astro_gravity_tree.h).

#include "sph_astro_gravity_tree.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace SPHAstro {

void GravityItems::clear()
{
  for (auto *v : {&x, &y, &z, &m, &h, &zo, &moments}) v->clear();
  mp.clear();
  tie.clear();
}

void GravityItems::add_particle(double px, double py, double pz, double pm, double ph, double pzo,
                                int64_t order)
{
  x.push_back(px);
  y.push_back(py);
  z.push_back(pz);
  m.push_back(pm);
  h.push_back(ph);
  zo.push_back(pzo);
  mp.push_back(-1);
  tie.push_back(order);
}

void GravityItems::add_multipole(double px, double py, double pz, double pm, const double *qm,
                                 double pb, int64_t order)
{
  // a node of one point mass (radius 0) is a particle of softening length 0: it is only ever
  // summed far beyond every softening support
  if (!(pb > 0.0)) {
    add_particle(px, py, pz, pm, 0.0, 0.0, order);
    return;
  }
  x.push_back(px);
  y.push_back(py);
  z.push_back(pz);
  m.push_back(pm);
  h.push_back(0.0);
  zo.push_back(0.0);
  mp.push_back(static_cast<int>(moments.size() / 7));
  moments.insert(moments.end(), qm, qm + 6);
  moments.push_back(pb);
  tie.push_back(order);
}

namespace {
  // the 21 bits of v spread to every third bit
  inline uint64_t spread3(uint64_t v)
  {
    v &= 0x1fffffULL;
    v = (v | v << 32) & 0x1f00000000ffffULL;
    v = (v | v << 16) & 0x1f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
  }

  inline int highest_bit(uint64_t v)
  {
    return 63 - __builtin_clzll(v);
  }
}    // namespace

void GravityTree::make_structure(int n, const double *px, const double *py, const double *pz,
                                 const int64_t *tie, const std::vector<char> *is_multipole)
{
  nodes_.clear();
  depth_ = 0;
  perm_.resize(n);
  if (n == 0) return;
  double lo[3] = {px[0], py[0], pz[0]}, hi[3] = {px[0], py[0], pz[0]};
  for (int i = 1; i < n; i++) {
    lo[0] = std::min(lo[0], px[i]);
    hi[0] = std::max(hi[0], px[i]);
    lo[1] = std::min(lo[1], py[i]);
    hi[1] = std::max(hi[1], py[i]);
    lo[2] = std::min(lo[2], pz[i]);
    hi[2] = std::max(hi[2], pz[i]);
  }
  const double side = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  const double cells = static_cast<double>((1 << KEY_BITS) - 1);
  const double scale = side > 0.0 ? cells / side : 0.0;
  keys_.resize(n);
  for (int i = 0; i < n; i++) {
    const double c[3] = {px[i], py[i], pz[i]};
    uint64_t key = 0;
    for (int d = 0; d < 3; d++) {
      double s = (c[d] - lo[d]) * scale;
      s = s >= 0.0 ? std::min(s, cells) : 0.0;    // (a non-finite coordinate: the first cell)
      key |= spread3(static_cast<uint64_t>(s)) << (2 - d);
    }
    keys_[i] = key;
  }
  std::iota(perm_.begin(), perm_.end(), 0);
  std::stable_sort(perm_.begin(), perm_.end(), [&](int a, int b) {
    return keys_[a] != keys_[b] ? keys_[a] < keys_[b] : tie[a] < tie[b];
  });
  // keys and positions in tree order
  std::vector<uint64_t> sorted(n);
  for (int k = 0; k < n; k++) sorted[k] = keys_[perm_[k]];
  keys_.swap(sorted);
  sx_.resize(n);
  sy_.resize(n);
  sz_.resize(n);
  for (int k = 0; k < n; k++) {
    sx_[k] = px[perm_[k]];
    sy_[k] = py[perm_[k]];
    sz_[k] = pz[perm_[k]];
  }
  nodes_.reserve(2 * (n / std::max(leaf_size_, 1) + 1));
  nodes_.emplace_back();
  make_node(0, 0, n, 0);
  // a leaf's particles first, then its multipole items (in key order each)
  if (is_multipole)
    for (const GravityNode &node : nodes_)
      if (node.nchild == 0)
        std::stable_partition(perm_.begin() + node.first, perm_.begin() + node.first + node.count,
                              [&](int i) {
                                return !(*is_multipole)[i];
                              });
  for (GravityNode &node : nodes_)
    if (node.nchild == 0) {
      int np = node.count;
      if (is_multipole) {
        np = 0;
        while (np < node.count && !(*is_multipole)[perm_[node.first + np]]) np++;
      }
      node.nparticles = np;
    }
  nodes_.shrink_to_fit();
  // (the keys and positions of the build serve only the structure)
  std::vector<uint64_t>().swap(keys_);
  std::vector<double>().swap(sx_);
  std::vector<double>().swap(sy_);
  std::vector<double>().swap(sz_);
}

// node index over the sorted keys [first, first + count): a leaf, or children at the highest
// key digit (3 bits: one octree level) in which its keys differ
void GravityTree::make_node(int index, int first, int count, int level)
{
  GravityNode &node = nodes_[index];
  node.first = first;
  node.count = count;
  node.child = -1;
  node.nchild = 0;
  node.nparticles = count;
  depth_ = std::max(depth_, level);
  if (count <= leaf_size_) return;
  const uint64_t differ = keys_[first] ^ keys_[first + count - 1];
  if (differ == 0) {
    split_equal_keys(index, first, count, level);
    return;
  }
  const int shift = 3 * (highest_bit(differ) / 3);
  int starts[9], nchild = 0;
  int k = first;
  while (k < first + count) {
    starts[nchild++] = k;
    const uint64_t digit = (keys_[k] >> shift) & 7u;
    // the end of this digit's run (keys are sorted)
    int lo = k, hi = first + count;
    while (hi - lo > 1) {
      const int mid = (lo + hi) / 2;
      if (((keys_[mid] >> shift) & 7u) == digit)
        lo = mid;
      else
        hi = mid;
    }
    k = hi;
  }
  starts[nchild] = first + count;
  const int child = static_cast<int>(nodes_.size());
  nodes_.resize(nodes_.size() + nchild);
  nodes_[index].child = child;    // (nodes_ may have moved)
  nodes_[index].nchild = nchild;
  for (int c = 0; c < nchild; c++)
    make_node(child + c, starts[c], starts[c + 1] - starts[c], level + 1);
}

// items whose keys are all equal (closer than the key resolution, side / 2^21, which one
// item far from the rest makes coarse): halves at the middle of the longest side of their
// box, in the items' order, until a half fits a leaf or its items coincide
void GravityTree::split_equal_keys(int index, int first, int count, int level)
{
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (int k = first; k < first + count; k++) {
    const double c[3] = {sx_[k], sy_[k], sz_[k]};
    for (int d = 0; d < 3; d++) {
      lo[d] = std::min(lo[d], c[d]);
      hi[d] = std::max(hi[d], c[d]);
    }
  }
  int axis = 0;
  for (int d = 1; d < 3; d++)
    if (hi[d] - lo[d] > hi[axis] - lo[axis]) axis = d;
  const double mid = 0.5 * (lo[axis] + hi[axis]);
  if (!(hi[axis] > lo[axis]) || !(mid > lo[axis])) return;    // coincident: one leaf
  const std::vector<double> &c = axis == 0 ? sx_ : axis == 1 ? sy_ : sz_;
  // stable partition of perm_ and the positions by c < mid
  std::vector<int> below, above;
  for (int k = first; k < first + count; k++) (c[k] < mid ? below : above).push_back(k);
  std::vector<int> order(below);
  order.insert(order.end(), above.begin(), above.end());
  std::vector<int> p(count);
  std::vector<double> qx(count), qy(count), qz(count);
  for (int k = 0; k < count; k++) {
    p[k] = perm_[order[k]];
    qx[k] = sx_[order[k]];
    qy[k] = sy_[order[k]];
    qz[k] = sz_[order[k]];
  }
  for (int k = 0; k < count; k++) {
    perm_[first + k] = p[k];
    sx_[first + k] = qx[k];
    sy_[first + k] = qy[k];
    sz_[first + k] = qz[k];
  }
  const int nbelow = static_cast<int>(below.size());
  const int child = static_cast<int>(nodes_.size());
  nodes_.resize(nodes_.size() + 2);
  nodes_[index].child = child;
  nodes_[index].nchild = 2;
  make_node(child, first, nbelow, level + 1);
  make_node(child + 1, first + nbelow, count - nbelow, level + 1);
}

void GravityTree::build(int n, const double *const *x, const int64_t *tie)
{
  std::vector<double> px(n), py(n), pz(n);
  for (int i = 0; i < n; i++) {
    px[i] = x[i][0];
    py[i] = x[i][1];
    pz[i] = x[i][2];
  }
  make_structure(n, px.data(), py.data(), pz.data(), tie, nullptr);
  x_.assign(n, 0.0);
  y_.assign(n, 0.0);
  z_.assign(n, 0.0);
  m_.assign(n, 0.0);
  h_.assign(n, 0.0);
  zo_.assign(n, 0.0);
  mp_.clear();
  mp_moments_.clear();
}

namespace {
  // v[k] = v[perm[k]] for k < n (count: values per item), through one buffer
  template <class T> void permute(std::vector<T> &v, const std::vector<int> &perm, int count = 1)
  {
    std::vector<T> out(v.size());
    for (size_t k = 0; k < perm.size(); k++)
      for (int c = 0; c < count; c++) out[count * k + c] = v[count * perm[k] + c];
    v.swap(out);
  }
}    // namespace

void GravityTree::build(GravityItems &items)
{
  const int n = items.size();
  std::vector<char> is_multipole(n);
  for (int i = 0; i < n; i++) is_multipole[i] = items.mp[i] >= 0;
  make_structure(n, items.x.data(), items.y.data(), items.z.data(), items.tie.data(),
                 &is_multipole);
  // the items' arrays become the tree's, in tree order
  x_.swap(items.x);
  y_.swap(items.y);
  z_.swap(items.z);
  m_.swap(items.m);
  h_.swap(items.h);
  zo_.swap(items.zo);
  mp_.swap(items.mp);
  mp_moments_.swap(items.moments);    // (indexed through mp_: not permuted)
  for (auto *v : {&x_, &y_, &z_, &m_, &h_, &zo_}) permute(*v, perm_);
  permute(mp_, perm_);
  items = GravityItems();    // (its arrays now hold the tree's old ones: freed)
  moments();
}

// bottom-up (children come after their parent in nodes_): monopole, centre of mass, second
// moment (parallel-axis shift of the children's), b_max (a leaf's from its items, an internal
// node's from its children's spheres), h_max
void GravityTree::moments()
{
  const bool items_with_extent = !mp_.empty();
  for (int k = static_cast<int>(nodes_.size()) - 1; k >= 0; k--) {
    GravityNode &node = nodes_[k];
    double M = 0.0, cx = 0.0, cy = 0.0, cz = 0.0;
    double q[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    double bmax = 0.0, hmax = 0.0;
    if (node.nchild == 0) {
      const int a = node.first, e = node.first + node.count;
      for (int j = a; j < e; j++) {
        M += m_[j];
        cx += m_[j] * x_[j];
        cy += m_[j] * y_[j];
        cz += m_[j] * z_[j];
      }
      if (M > 0.0) {
        cx /= M;
        cy /= M;
        cz /= M;
      } else {    // (massless: the first item's position)
        cx = x_[a];
        cy = y_[a];
        cz = z_[a];
      }
      for (int j = a; j < e; j++) {
        const double dx = x_[j] - cx, dy = y_[j] - cy, dz = z_[j] - cz;
        const double mj = m_[j];
        q[0] += mj * dx * dx;
        q[1] += mj * dy * dy;
        q[2] += mj * dz * dz;
        q[3] += mj * dx * dy;
        q[4] += mj * dx * dz;
        q[5] += mj * dy * dz;
        const int mp = items_with_extent ? mp_[j] : -1;
        const double b = mp >= 0 ? mp_moments_[7 * mp + 6] : 0.0;
        if (mp >= 0)
          for (int c = 0; c < 6; c++) q[c] += mp_moments_[7 * mp + c];
        bmax = std::max(bmax, std::sqrt(dx * dx + dy * dy + dz * dz) + b);
      }
      for (int j = a; j < a + node.nparticles; j++) hmax = std::max(hmax, h_[j]);
    } else {
      const int c0 = node.child, c1 = node.child + node.nchild;
      for (int c = c0; c < c1; c++) {
        const GravityNode &ch = nodes_[c];
        M += ch.m;
        cx += ch.m * ch.x;
        cy += ch.m * ch.y;
        cz += ch.m * ch.z;
        hmax = std::max(hmax, ch.hmax);
      }
      if (M > 0.0) {
        cx /= M;
        cy /= M;
        cz /= M;
      } else {
        cx = nodes_[c0].x;
        cy = nodes_[c0].y;
        cz = nodes_[c0].z;
      }
      for (int c = c0; c < c1; c++) {
        const GravityNode &ch = nodes_[c];
        const double dx = ch.x - cx, dy = ch.y - cy, dz = ch.z - cz;
        q[0] += ch.q[0] + ch.m * dx * dx;
        q[1] += ch.q[1] + ch.m * dy * dy;
        q[2] += ch.q[2] + ch.m * dz * dz;
        q[3] += ch.q[3] + ch.m * dx * dy;
        q[4] += ch.q[4] + ch.m * dx * dz;
        q[5] += ch.q[5] + ch.m * dy * dz;
        bmax = std::max(bmax, std::sqrt(dx * dx + dy * dy + dz * dz) + ch.bmax);
      }
    }
    node.m = M;
    node.x = cx;
    node.y = cy;
    node.z = cz;
    for (int c = 0; c < 6; c++) node.q[c] = q[c];
    node.bmax = bmax;
    node.hmax = hmax;
  }
}

void GravityTree::walk(const TargetBox &box, const OpeningCriterion &crit,
                       std::vector<int> &accepted_nodes, std::vector<int> &leaves) const
{
  if (nodes_.empty()) return;
  std::vector<int> &stack = stack_;
  stack.clear();
  stack.push_back(0);
  const bool cut = std::isfinite(crit.cutoff);
  while (!stack.empty()) {
    const int k = stack.back();
    stack.pop_back();
    const GravityNode &n = nodes_[k];
    if (cut) {    // the node's sphere and the box
      double d2 = 0.0;
      const double c[3] = {n.x, n.y, n.z};
      for (int d = 0; d < 3; d++) {
        const double e = std::max(std::max(box.lo[d] - c[d], c[d] - box.hi[d]), 0.0);
        d2 += e * e;
      }
      if (d2 >= (crit.cutoff + n.bmax) * (crit.cutoff + n.bmax)) continue;
    }
    if (accepted(n, box, crit))
      accepted_nodes.push_back(k);
    else if (n.nchild == 0)
      leaves.push_back(k);
    else
      for (int c = n.child + n.nchild - 1; c >= n.child; c--) stack.push_back(c);
  }
}

void GravityTree::walk(const std::vector<TargetBox> &boxes, const OpeningCriterion &crit,
                       std::vector<int> &accepted_nodes, std::vector<int> &leaves) const
{
  if (nodes_.empty() || boxes.empty()) return;
  std::vector<int> &stack = stack_;
  stack.clear();
  stack.push_back(0);
  while (!stack.empty()) {
    const int k = stack.back();
    stack.pop_back();
    const GravityNode &n = nodes_[k];
    bool all = true;
    for (const TargetBox &box : boxes)
      if (!accepted(n, box, crit)) {
        all = false;
        break;
      }
    if (all)
      accepted_nodes.push_back(k);
    else if (n.nchild == 0)
      leaves.push_back(k);
    else
      for (int c = n.child + n.nchild - 1; c >= n.child; c--) stack.push_back(c);
  }
}

void GravityTree::groups(int group_size, std::vector<int> &out) const
{
  out.clear();
  if (nodes_.empty()) return;
  std::vector<int> &stack = stack_;
  stack.clear();
  stack.push_back(0);
  while (!stack.empty()) {
    const int k = stack.back();
    stack.pop_back();
    const GravityNode &n = nodes_[k];
    if (n.count <= group_size || n.nchild == 0)
      out.push_back(k);
    else
      for (int c = n.child + n.nchild - 1; c >= n.child; c--) stack.push_back(c);
  }
}

double GravityTree::memory_usage() const
{
  return nodes_.capacity() * sizeof(GravityNode) +
      (perm_.capacity() + mp_.capacity()) * sizeof(int) + keys_.capacity() * sizeof(uint64_t) +
      (x_.capacity() + y_.capacity() + z_.capacity() + m_.capacity() + h_.capacity() +
       zo_.capacity() + mp_moments_.capacity()) *
      sizeof(double);
}

}    // namespace SPHAstro
