/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The one neighbour loop of the pair passes. pair_loop() walks a neighbour list (half or
// full), takes the positions, tests the kernel support(s) of the pair, evaluates the pair's
// kernel (value or gradient, sph_astro_iact.h) and hands it to an interaction adapter, which
// gathers the particles' numbers, calls the interaction function and accumulates for i and,
// where update_j (newton on, or j owned), for j. NearEntries is the gather form over one row
// of a full list at the h_i of the h-rho iteration. with_variant() selects the compiled
// variant: kernel x dimension x {mean h, two h}; every other option is a run-time value.
//
// An adapter ACT provides
//   static constexpr KernelUse use;   what the pair needs of the kernel
//   struct Own;                      i's loaded numbers and accumulators
//   void begin(int i, Own &);        void end(int i, Own &);
//   void pair(int i, int j, double w, Own &, bool update_j)                        (VALUE)
//   void pair(int i, int j, double dx, double dy, double dz, const PairGradient &,
//             Own &, bool update_j)                                                 (GRADIENT)
//   void pair(int i, int j, Own &, bool update_j)                                   (SUPPORT)

#ifndef LMP_SPH_ASTRO_PAIR_LOOP_H
#define LMP_SPH_ASTRO_PAIR_LOOP_H

#include "lmptype.h"
#include "sph_astro_iact.h"
#include "sph_astro_neigh_view.h"

#include <vector>

namespace SPHAstro {

// the atom arrays every pass reads
struct Particles {
  double **x;
  const double *h;
  const int *type;
  const double *rmass;
  const double *mass;
  int nlocal, nall;
  // per type: 1 if SPH gas (the types of pair sph/astro's pair_coeff); null: every type. Atoms
  // of other types (point masses under other fixes and pair styles) are in no list and get no
  // SPH state (their P, c_s, div v, du/dt stay 0)
  const int *sph_type = nullptr;
  double mass_of(int i) const { return rmass ? rmass[i] : mass[type[i]]; }
  bool gas(int i) const { return !sph_type || sph_type[type[i]]; }
};

enum class KernelUse { SUPPORT, VALUE, GRADIENT };

// pair inside the support(s): r < R h_ij (mean h) or r < R max(h_i, h_j) (two h)
template <bool TWO_H>
inline bool within_support(double R2, const KernelSide &ki, double hj, double r2)
{
  if (TWO_H) return r2 < ki.support2 || r2 < R2 * hj * hj;
  const double hij = 0.5 * (ki.h + hj);
  return r2 < R2 * hij * hij;
}

// average: the averaged kernel (two h only): both gradients replaced by their mean
template <class KERNEL, int DIM, bool TWO_H, class ACT>
void pair_loop(const NeighView &nl, const Particles &p, bool newton, bool average, ACT &act)
{
  if (nl.inum == 0) return;
  const PairKernel<KERNEL, DIM> kern;
  // (x from its first row: LAMMPS' memory->create makes it contiguous, and a partner's
  // position is then one load, not its row pointer and then the row)
  const double *x = p.x[0];
  const double *h = p.h;
  const int nlocal = p.nlocal;
  for (int ii = 0; ii < nl.inum; ii++) {
    const int i = nl.ilist[ii];
    const double xi = x[3 * i], yi = x[3 * i + 1], zi = x[3 * i + 2];
    const KernelSide ki(h[i], kern.R2);
    typename ACT::Own own;
    act.begin(i, own);
    const int *jlist = nl.firstneigh[i];
    const int jnum = nl.numneigh[i];
    for (int jj = 0; jj < jnum; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      const double dx = xi - x[3 * j], dy = yi - x[3 * j + 1], dz = zi - x[3 * j + 2];
      const double r2 = dx * dx + dy * dy + dz * dz;
      const bool update_j = newton || j < nlocal;
      if constexpr (ACT::use == KernelUse::VALUE) {
        double w;
        if (!pair_kernel_value<KERNEL, DIM, TWO_H>(kern, ki, h[j], r2, w)) continue;
        act.pair(i, j, w, own, update_j);
      } else if constexpr (ACT::use == KernelUse::GRADIENT) {
        PairGradient g;
        if (!pair_kernel_gradient<KERNEL, DIM, TWO_H>(kern, ki, h[j], r2, average, g)) continue;
        act.pair(i, j, dx, dy, dz, g, own, update_j);
      } else {
        if (!within_support<TWO_H>(kern.R2, ki, h[j], r2)) continue;
        act.pair(i, j, own, update_j);
      }
    }
    act.end(i, own);
  }
}

// the entries of one row of a full list within a distance of atom i, with their separations,
// in row order (the h-rho iteration: its h moves by a few per cent from its first guess, and
// the sums at each h it tries run over these entries instead of the whole row: the same
// terms in the same order, without the row's gathers of x_j). gather() keeps them
// branch-free: each entry is written at slot n, and n advances where it is kept; each()
// hands those with r_ij^2 < support2 to row(j, dx, dy, dz, r2)
class NearEntries {
 public:
  void gather(double **xrows, int i, const int *jlist, int jnum, double near2)
  {
    const double *x = xrows[0];    // (contiguous, as in pair_loop)
    if (static_cast<int>(j_.size()) < jnum) {
      j_.resize(jnum);
      dx_.resize(jnum);
      dy_.resize(jnum);
      dz_.resize(jnum);
      r2_.resize(jnum);
    }
    // (i's position copied: the stores below cannot alias it)
    const double xi = x[3 * i], yi = x[3 * i + 1], zi = x[3 * i + 2];
    int n = 0;
    for (int jj = 0; jj < jnum; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      const double dx = xi - x[3 * j], dy = yi - x[3 * j + 1], dz = zi - x[3 * j + 2];
      const double r2 = dx * dx + dy * dy + dz * dz;
      j_[n] = j;
      dx_[n] = dx;
      dy_[n] = dy;
      dz_[n] = dz;
      r2_[n] = r2;
      n += r2 < near2;
    }
    n_ = n;
  }
  template <class ROW> void each(double support2, ROW &&row) const
  {
    for (int k = 0; k < n_; k++)
      if (r2_[k] < support2) row(j_[k], dx_[k], dy_[k], dz_[k], r2_[k]);
  }

 private:
  std::vector<int> j_;
  std::vector<double> dx_, dy_, dz_, r2_;
  int n_ = 0;
};

// a compiled variant of the passes: kernel, dimension, mean h or two h
template <class KERNEL, int DIM, bool TWO_H> struct Variant {
  using kernel = KERNEL;
  static constexpr int dim = DIM;
  static constexpr bool two_h = TWO_H;
};

template <class KERNEL, class F> inline void with_dimension(int dim, bool two_h, F &&f)
{
  if (dim == 2) {
    if (two_h)
      f(Variant<KERNEL, 2, true>());
    else
      f(Variant<KERNEL, 2, false>());
  } else {
    if (two_h)
      f(Variant<KERNEL, 3, true>());
    else
      f(Variant<KERNEL, 3, false>());
  }
}

// f(Variant<...>()) for the run-time kernel, dimension (2 or 3) and kernel form
template <class F> inline void with_variant(KernelType kernel, int dim, bool two_h, F &&f)
{
  switch (kernel) {
    case KernelType::CUBIC:
      with_dimension<KernelCubic>(dim, two_h, f);
      break;
    case KernelType::QUINTIC:
      with_dimension<KernelQuintic>(dim, two_h, f);
      break;
    case KernelType::WENDLAND_C2:
      with_dimension<KernelWendlandC2>(dim, two_h, f);
      break;
    case KernelType::WENDLAND_C4:
      with_dimension<KernelWendlandC4>(dim, two_h, f);
      break;
    case KernelType::GAUSSIAN:
      with_dimension<KernelGaussian>(dim, two_h, f);
      break;
  }
}

}    // namespace SPHAstro

#endif
