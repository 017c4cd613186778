/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

#include "sph_astro_neighbour_tree.h"

#include <algorithm>

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>
#define SPH_ASTRO_AVX512_SELECT 1
#define SPH_ASTRO_NOINLINE __attribute__((noinline))
#else
#define SPH_ASTRO_NOINLINE
#endif

namespace SPHAstro {

namespace {
  // (not inlined into the AVX-512 version below, whose target would let the compiler fuse its
  // products and sums into FMAs)
  SPH_ASTRO_NOINLINE int select_within_scalar(const double *cx, const double *cy, const double *cz,
                                              const double *cr, const int *index, int nc,
                                              const double *c, double rc, double pad, int *found)
  {
    int n = 0;
    for (int m = 0; m < nc; m++) {
      const double dx = cx[m] - c[0], dy = cy[m] - c[1], dz = cz[m] - c[2];
      const double reach = (rc > cr[m] ? rc : cr[m]) + pad;
      found[n] = index[m];
      n += dx * dx + dy * dy + dz * dz < reach * reach;
    }
    return n;
  }

#ifdef SPH_ASTRO_AVX512_SELECT
  // candidates m .. m + 7 within reach of c (x, y, z; radius r, pad p); the _round_ forms round
  // products and sums one by one, never fused into one FMA, as in the scalar loop
  constexpr int ROUND = _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC;
  __attribute__((target("avx512f"))) inline __mmask8 within8(const double *cx, const double *cy,
                                                             const double *cz, const double *cr,
                                                             int m, __m512d x, __m512d y, __m512d z,
                                                             __m512d r, __m512d p)
  {
    const __m512d dx = _mm512_sub_round_pd(_mm512_loadu_pd(cx + m), x, ROUND);
    const __m512d dy = _mm512_sub_round_pd(_mm512_loadu_pd(cy + m), y, ROUND);
    const __m512d dz = _mm512_sub_round_pd(_mm512_loadu_pd(cz + m), z, ROUND);
    const __m512d d2 =
        _mm512_add_round_pd(_mm512_add_round_pd(_mm512_mul_round_pd(dx, dx, ROUND),
                                                _mm512_mul_round_pd(dy, dy, ROUND), ROUND),
                            _mm512_mul_round_pd(dz, dz, ROUND), ROUND);
    const __m512d reach = _mm512_add_round_pd(_mm512_max_pd(r, _mm512_loadu_pd(cr + m)), p, ROUND);
    return _mm512_cmp_pd_mask(d2, _mm512_mul_round_pd(reach, reach, ROUND), _CMP_LT_OQ);
  }

  __attribute__((target("avx512f"))) int
  select_within_avx512(const double *cx, const double *cy, const double *cz, const double *cr,
                       const int *index, int nc, const double *c, double rc, double pad, int *found)
  {
    const __m512d x = _mm512_set1_pd(c[0]), y = _mm512_set1_pd(c[1]), z = _mm512_set1_pd(c[2]);
    const __m512d r = _mm512_set1_pd(rc), p = _mm512_set1_pd(pad);
    int n = 0, m = 0;
    for (; m + 16 <= nc; m += 16) {
      const unsigned lo = within8(cx, cy, cz, cr, m, x, y, z, r, p);
      const unsigned hi = within8(cx, cy, cz, cr, m + 8, x, y, z, r, p);
      const __mmask16 mask = static_cast<__mmask16>(lo | (hi << 8));
      _mm512_mask_compressstoreu_epi32(found + n, mask, _mm512_loadu_si512(index + m));
      n += __builtin_popcount(mask);
    }
    return n +
        select_within_scalar(cx + m, cy + m, cz + m, cr + m, index + m, nc - m, c, rc, pad,
                             found + n);
  }
#endif

  using SelectWithin = int (*)(const double *, const double *, const double *, const double *,
                               const int *, int, const double *, double, double, int *);
  SelectWithin choose_select_within()
  {
#ifdef SPH_ASTRO_AVX512_SELECT
    __builtin_cpu_init();    // (this runs from a static initializer, maybe before libgcc's)
    if (__builtin_cpu_supports("avx512f")) return select_within_avx512;
#endif
    return select_within_scalar;
  }
  const SelectWithin select_within_chosen = choose_select_within();
}    // namespace

int NeighbourTree::select_within(const double *cx, const double *cy, const double *cz,
                                 const double *cr, const int *index, int nc, const double *c,
                                 double rc, double pad, int *found)
{
  return select_within_chosen(cx, cy, cz, cr, index, nc, c, rc, pad, found);
}

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
