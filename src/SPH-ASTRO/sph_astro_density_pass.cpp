/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Density passes of pair sph/astro (sph_astro_passes.h):
//   summation  rho_i = sum_j m_j W_ij including m_i W(0, h_i)          (Monaghan 1992, eq. 2.7)
//              W_ij = W(r_ij, h_ij), or (W(r_ij, h_i) + W(r_ij, h_j))/2 with the averaged kernel
//              formulation pressure-energy: weights m_j u_j, P_i/(gamma-1) = sum_j m_j u_j W_ij
//              (Saitoh & Makino 2013, ApJ 768, 44; Hopkins 2013, MNRAS 428, 2840, eq. 13)
//   h-rho      rho_i = sum_j m_j W(r_ij, h_i), h_i = hfact (m_i / rho_i)^(1/d), by Newton-Raphson
//              with bisection; Omega_i = 1 + h_i/(d rho_i) sum_j m_j dW(r_ij, h_i)/dh_i,
//              dW/dh = -sigma/h^(d+1) (d w(q) + q w'(q))  (Springel & Hernquist 2002, MNRAS 333,
//              649; Price 2012, J. Comput. Phys. 231, 759, eqs. 31-34). The last evaluation also
//              sums the velocity sums (curl or grad v) at the h it keeps, and with
//              pressure-energy sum_j m_j u_j W(h_i) and the grad-h term
//              C_i = h_i (dP_i/dh_i) / (d rho_i Omega_i) (0 where h does not follow rho).
//              With adaptive gravitational softening (pair sph/astro/gravity) it also sums
//              S_i = sum_{j != i} m_j dphi(r_ij, h_i)/dh_i, the sum of zeta_i (Price & Monaghan
//              2007, MNRAS 374, 1347, eq. 26), over the same neighbours.

#include "sph_astro_passes.h"

#include "sph_astro_gravity_kernel.h"

#include "error.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

using namespace LAMMPS_NS;

namespace SPHAstro {
namespace {

  // summation over the half list: m_j W_ij to i, m_i W_ij to j (PE: weights m u)
  template <bool PE> struct DensityAdapter {
    static constexpr KernelUse use = KernelUse::VALUE;
    const Particles &p;
    const double *u;    // weights m u (pressure-energy), else null
    double *rho, *nneigh;
    double w0;    // sigma w(0) / h^d without the 1/h^d
    int dim;
    struct Own {
      double weight, rho, n;
    };
    double weight(int i) const { return PE ? p.mass_of(i) * u[i] : p.mass_of(i); }
    void begin(int i, Own &own) const
    {
      own.weight = weight(i);
      const double hinv = 1.0 / p.h[i];
      own.rho = own.weight * w0 * (dim == 2 ? hinv * hinv : hinv * hinv * hinv);
      own.n = 0.0;
    }
    void pair(int, int j, double w, Own &own, bool update_j) const
    {
      const DensityContribution c = iact_density(own.weight, weight(j), w);
      own.rho += c.to_i;
      own.n += 1.0;
      if (update_j) {
        rho[j] += c.to_j;
        nneigh[j] += 1.0;
      }
    }
    void end(int i, Own &own) const
    {
      rho[i] += own.rho;
      nneigh[i] += own.n;
    }
  };

  struct CountAdapter {
    static constexpr KernelUse use = KernelUse::SUPPORT;
    double *nneigh;
    struct Own {
      double n;
    };
    void begin(int, Own &own) const { own.n = 0.0; }
    void pair(int, int j, Own &own, bool update_j) const
    {
      own.n += 1.0;
      if (update_j) nneigh[j] += 1.0;
    }
    void end(int i, Own &own) const { nneigh[i] += own.n; }
  };

  // S_i = sum_{j != i} m_j dphi(r_ij, h_i)/dh_i over the entries within the support
  // support2 = (R h_i)^2, dphi/dh = -[fpot(q) + q fforce(q)] / h^2 (sph_astro_gravity_kernel.h)
  template <class KERNEL>
  double dphidh_sum(const NearEntries &near, const Particles &p, int i, double hinv,
                    double support2, const SoftenedKernel &soft)
  {
    double sum = 0.0;
    near.each(support2, [&](int j, double, double, double, double r2) {
      if (j == i) return;
      const double q = std::sqrt(r2) * hinv;
      double fpot, fforce;
      if constexpr (std::is_same_v<KERNEL, KernelCubic>)
        SoftenedCubic::eval(q, fpot, fforce);
      else
        soft.eval(q, fpot, fforce);
      sum -= p.mass_of(j) * (fpot + q * fforce);
    });
    return sum * hinv * hinv;
  }

  // the entries kept for an h iteration: those within NEAR_MARGIN x the h it first tries (and
  // again for an h that goes past that)
  constexpr double NEAR_MARGIN = 1.1;

  // SUMS (VelocitySums) and PE compiled in: this loop runs several times per particle
  template <class KERNEL, int DIM, int SUMS, bool PE>
  void gradh_loop(const PassContext &ctx, const GradhSettings &s, GradhStatistics &stats)
  {
    using K = Kernel<KERNEL, DIM>;
    const Particles &p = ctx.p;
    Fields &f = *ctx.f;
    double **x = p.x;
    double *h = const_cast<double *>(p.h);
    const double *uest = ctx.uest;
    constexpr bool curl = SUMS == static_cast<int>(VelocitySums::CURL);
    constexpr bool gradient = SUMS == static_cast<int>(VelocitySums::GRADIENT);
    // (v_est from its first row: contiguous, one load per partner, as in pair_loop)
    const double *vest = ((curl || gradient) && p.nall > 0) ? ctx.vest[0] : nullptr;
    constexpr bool pe = PE;
    const double sigma = K::sigma();
    const double R2 = K::radius * K::radius;
    const double w0 = K::w(0.0);
    const double hfact_d = std::pow(s.hfact, DIM);
    const double gm1 = s.gamma - 1.0;
    const NeighView &nl = s.full;
    NearEntries near;

    for (int ii = 0; ii < nl.inum; ii++) {
      const int i = nl.ilist[ii];
      const double mi = p.mass_of(i);
      const double cap = s.h_cap;
      const int *jlist = nl.firstneigh[i];
      int jnum = nl.numneigh[i];
      double hlist = s.hlist[i];    // the largest h jlist serves

      double hi = h[i] < cap ? h[i] : cap;
      double hlo = 0.0, hhi = INFINITY;    // f(h) = rho(h) - rho_target(h) rises with h
      double h_evaluated = hi;             // rho, Omega and the sums belong to this h
      double rhoi = 0.0, dsum = 0.0, ni = 0.0, esum = 0.0, desum = 0.0;
      double curl_sum[4] = {0.0, 0.0, 0.0, 0.0};
      double grad_sum[VGRAD_SUMS] = {};
      bool converged = false, at_cap = false;
      double h_near = -1.0;    // near holds the row's entries within R h_near
      int it = 0;
      while (it < s.max_iterations) {
        it++;
        if (hi > hlist) {
          jlist = s.wide->row(i, hi, hlist, jnum);
          h_near = -1.0;
        }
        if (!(hi <= h_near)) {
          h_near = std::min(hlist, NEAR_MARGIN * hi);
          near.gather(x, i, jlist, jnum, R2 * h_near * h_near);
        }
        const double hinv = 1.0 / hi;
        const double norm = sigma * inv_h_pow_dim<DIM>(hinv);
        GradhSums mass, energy;
        mass.add(mi, w0, 0.0, 0.0, DIM);    // self term
        if constexpr (pe) energy.add(mi * uest[i], w0, 0.0, 0.0, DIM);
        double vsum[4] = {0.0, 0.0, 0.0, 0.0};
        double gsum[VGRAD_SUMS] = {};
        ni = 0.0;
        near.each(R2 * hi * hi, [&](int j, double dx, double dy, double dz, double r2) {
          const double r = std::sqrt(r2);
          const double q = r * hinv;
          const double mj = p.mass_of(j);
          const double w = K::w(q), dw = K::dw(q);
          mass.add(mj, w, dw, q, DIM);
          if constexpr (pe) energy.add(mj * uest[j], w, dw, q, DIM);
          ni += 1.0;
          if constexpr (curl || gradient) {
            if (r2 == 0.0) return;
            const double dvx = vest[3 * i] - vest[3 * j], dvy = vest[3 * i + 1] - vest[3 * j + 1],
                         dvz = vest[3 * i + 2] - vest[3 * j + 2];
            if (curl) {
              double c[4];
              iact_velocity_curl(dvx, dvy, dvz, dx, dy, dz, mj * dw / r, c);
              for (int k = 0; k < 4; k++) vsum[k] += c[k];
            } else
              velocity_gradient_add(gsum, mj * dw / r, dvx, dvy, dvz, dx, dy, dz);
          }
        });
        if (curl)    // grad_i W = sigma h^-(d+1) w'(q) r_ij / r
          for (int k = 0; k < 4; k++) curl_sum[k] = norm * hinv * vsum[k];
        if (gradient)
          for (int k = 0; k < VGRAD_SUMS; k++) grad_sum[k] = norm * hinv * gsum[k];
        rhoi = norm * mass.w;
        dsum = norm * hinv * mass.dwdh;    // sum_j m_j dW/dh
        if (pe) {
          esum = norm * energy.w;
          desum = norm * hinv * energy.dwdh;
        }
        h_evaluated = hi;
        const double rho_target = mi * hfact_d * inv_h_pow_dim<DIM>(hinv);
        const double fval = rhoi - rho_target;
        const double fprime = dsum + DIM * rho_target * hinv;
        if (fval < 0.0)
          hlo = hi;
        else
          hhi = hi;
        double hnew = hi - fval / fprime;
        // a Newton step below the tolerance is convergence, even where round-off puts it on
        // the bracket's edge (hnew == hlo), which would send the iteration to 2 h
        if (fprime > 0.0 && std::fabs(hnew - hi) < s.tolerance * hi && hi < cap) {
          converged = true;
          break;
        }
        if (!(fprime > 0.0) || !(hnew > hlo) || !(hnew < hhi))
          hnew = std::isfinite(hhi) ? 0.5 * (hlo + hhi) : 2.0 * hi;    // bisection fallback
        if (hnew >= cap && hi >= cap) {    // wants to grow past the cap: stay there
          at_cap = true;
          converged = true;
          break;
        }
        if (hnew > cap) hnew = cap;
        if (std::fabs(hnew - hi) < s.tolerance * hi) {
          converged = true;
          break;
        }
        hi = hnew;
      }
      if (!converged) {
        stats.failures++;
        if (!stats.first_failure || ctx.tag[i] < stats.first_failure)
          stats.first_failure = ctx.tag[i];
      }
      if (at_cap) {
        stats.capped++;
        if (!stats.first_capped || ctx.tag[i] < stats.first_capped) stats.first_capped = ctx.tag[i];
      }
      hi = h_evaluated;
      stats.iterations_sum += it;
      if (it > stats.iterations_max) stats.iterations_max = it;
      if (!(rhoi > 0.0) || !std::isfinite(rhoi) || !std::isfinite(hi))
        ctx.error->one(FLERR, "pair_style sph/astro: atom {} has density {} at h = {}", ctx.tag[i],
                       rhoi, hi);
      h[i] = hi;
      ctx.rho_sum[i] = rhoi;
      f.nneigh[i] = ni;
      if (curl)
        for (int k = 0; k < 4; k++) f.dcurl[i][k] = curl_sum[k];
      if (gradient)
        for (int k = 0; k < VGRAD_SUMS; k++) f.vgsum[i][k] = grad_sum[k];
      // h held at the cap does not follow rho: Omega = 1
      f.omega[i] = at_cap ? 1.0 : 1.0 + hi / (DIM * rhoi) * dsum;
      bool follows_rho = !at_cap;
      if (!(f.omega[i] > 0.0)) {
        f.omega[i] = 1.0;
        follows_rho = false;
      }
      if (pe) {    // P_i / (gamma-1) and C_i = h_i dP_i/dh_i / (d rho_i Omega_i)
        f.energy_sum[i] = esum;
        f.pe_gradh[i] = follows_rho ? gm1 * hi * desum / (DIM * rhoi * f.omega[i]) : 0.0;
      }
      // (near holds the entries within R h_near >= R h_i of the last evaluation)
      if constexpr (DIM == 3)
        if (s.dphidh_sum)
          s.dphidh_sum[i] = dphidh_sum<KERNEL>(near, p, i, 1.0 / hi, R2 * hi * hi, *s.softened);
    }
    stats.particles = nl.inum;
  }

}    // namespace

void density_summation(const PassContext &ctx, bool two_h, bool weight_u)
{
  const int nzero = ctx.nzero();
  for (int i = 0; i < nzero; i++) {
    ctx.rho_sum[i] = 0.0;
    ctx.f->nneigh[i] = 0.0;
  }
  with_variant(ctx.kernel, ctx.dim, two_h, [&](auto v) {
    using V = decltype(v);
    using K = Kernel<typename V::kernel, V::dim>;
    const double w0 = K::sigma() * K::w(0.0);
    if (weight_u) {
      DensityAdapter<true> act{ctx.p, ctx.uest, ctx.rho_sum, ctx.f->nneigh, w0, V::dim};
      pair_loop<typename V::kernel, V::dim, V::two_h>(ctx.half, ctx.p, ctx.newton, false, act);
    } else {
      DensityAdapter<false> act{ctx.p, nullptr, ctx.rho_sum, ctx.f->nneigh, w0, V::dim};
      pair_loop<typename V::kernel, V::dim, V::two_h>(ctx.half, ctx.p, ctx.newton, false, act);
    }
  });
}

void count_neighbours(const PassContext &ctx, bool two_h)
{
  const int nzero = ctx.nzero();
  for (int i = 0; i < nzero; i++) ctx.f->nneigh[i] = 0.0;
  // the support test needs only the kernel radius, the same in 2D and 3D
  with_variant(ctx.kernel, 3, two_h, [&](auto v) {
    using V = decltype(v);
    CountAdapter act{ctx.f->nneigh};
    pair_loop<typename V::kernel, V::dim, V::two_h>(ctx.half, ctx.p, ctx.newton, false, act);
  });
}

void density_gradh(const PassContext &ctx, const GradhSettings &s, GradhStatistics &stats)
{
  stats = GradhStatistics();
  with_variant(ctx.kernel, ctx.dim, false, [&](auto v) {
    using K = typename decltype(v)::kernel;
    constexpr int D = decltype(v)::dim;
    constexpr int NONE = static_cast<int>(VelocitySums::NONE);
    constexpr int CURL = static_cast<int>(VelocitySums::CURL);
    constexpr int GRADIENT = static_cast<int>(VelocitySums::GRADIENT);
    const bool pe = s.pressure_energy;
    switch (s.sums) {
      case VelocitySums::NONE:
        pe ? gradh_loop<K, D, NONE, true>(ctx, s, stats)
           : gradh_loop<K, D, NONE, false>(ctx, s, stats);
        break;
      case VelocitySums::CURL:
        pe ? gradh_loop<K, D, CURL, true>(ctx, s, stats)
           : gradh_loop<K, D, CURL, false>(ctx, s, stats);
        break;
      case VelocitySums::GRADIENT:
        pe ? gradh_loop<K, D, GRADIENT, true>(ctx, s, stats)
           : gradh_loop<K, D, GRADIENT, false>(ctx, s, stats);
        break;
    }
  });
}

}    // namespace SPHAstro
