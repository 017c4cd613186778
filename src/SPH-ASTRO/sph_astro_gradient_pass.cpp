/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Velocity gradients of pair sph/astro (sph_astro_passes.h), from the predicted velocities:
//   div v_i = -1/(Omega_i rho_i) sum_j m_j v_ij . grad_i W_ij
//   curl v_i = 1/(Omega_i rho_i) sum_j m_j v_ij x grad_i W_ij   (Monaghan 1992, eqs. 4.1-4.3;
//                                                                Omega = 1 without grad-h)
//   Balsara (1995, J. Comput. Phys. 121, 357): f_i = |div v| / (|div v| + |curl v| + 1e-4 c/h)
// for the Balsara limiter and the Cullen & Dehnen (2010) switch, and the linearly exact grad v
// = G M^-1 of the reconstruction (sph_astro_reconstruction.h). With grad-h terms the sums are
// taken in the h-rho iteration's last evaluation (sph_astro_density_pass.cpp); otherwise in
// this half-list pass with W(h_ij) or the averaged kernel.

#include "sph_astro_passes.h"

#include <cmath>

namespace SPHAstro {
namespace {

  // the sums of i and j: both take the same sign (v_ij . grad_i W and v_ij x grad_i W are
  // even under i <-> j, as are M and G)
  struct VelocitySumAdapter {
    static constexpr KernelUse use = KernelUse::GRADIENT;
    const Particles &p;
    const double *vest;    // (from its first row: contiguous, as in pair_loop)
    double **sums;
    bool gradient;
    int nsums;
    struct Own {
      double m;
      double acc[VGRAD_SUMS];
    };
    void begin(int i, Own &own) const
    {
      own.m = p.mass_of(i);
      for (int k = 0; k < nsums; k++) own.acc[k] = 0.0;
    }
    void pair(int i, int j, double dx, double dy, double dz, const PairGradient &g, Own &own,
              bool update_j) const
    {
      const double mj = p.mass_of(j);
      const double dvx = vest[3 * i] - vest[3 * j], dvy = vest[3 * i + 1] - vest[3 * j + 1],
                   dvz = vest[3 * i + 2] - vest[3 * j + 2];
      if (gradient) {
        velocity_gradient_add(own.acc, mj * g.dwi, dvx, dvy, dvz, dx, dy, dz);
        if (update_j) velocity_gradient_add(sums[j], own.m * g.dwi, dvx, dvy, dvz, dx, dy, dz);
        return;
      }
      double c[4];
      iact_velocity_curl(dvx, dvy, dvz, dx, dy, dz, g.dwi, c);
      for (int k = 0; k < 4; k++) own.acc[k] += mj * c[k];
      if (update_j)
        for (int k = 0; k < 4; k++) sums[j][k] += own.m * c[k];
    }
    void end(int i, Own &own) const
    {
      for (int k = 0; k < nsums; k++) sums[i][k] += own.acc[k];
    }
  };

}    // namespace

void velocity_sums(const PassContext &ctx, bool two_h, VelocitySums which)
{
  const bool gradient = which == VelocitySums::GRADIENT;
  const int nsums = gradient ? VGRAD_SUMS : 4;
  double **sums = gradient ? ctx.f->vgsum : ctx.f->dcurl;
  const int nzero = ctx.nzero();
  for (int i = 0; i < nzero; i++)
    for (int k = 0; k < nsums; k++) sums[i][k] = 0.0;
  if (ctx.half.inum == 0) return;
  const double *vest = ctx.vest[0];
  with_variant(ctx.kernel, ctx.dim, two_h, [&](auto v) {
    using V = decltype(v);
    VelocitySumAdapter act{ctx.p, vest, sums, gradient, nsums};
    pair_loop<typename V::kernel, V::dim, V::two_h>(ctx.half, ctx.p, ctx.newton, true, act);
  });
}

void finish_curl(const PassContext &ctx, bool omega, bool balsara)
{
  const Fields &f = *ctx.f;
  for (int i = 0; i < ctx.p.nlocal; i++) {
    if (!ctx.p.gas(i)) continue;
    const double norm = 1.0 / ((omega ? f.omega[i] : 1.0) * ctx.rho[i]);
    const double divv = -f.dcurl[i][0] * norm;
    const double curlv = norm *
        std::sqrt(f.dcurl[i][1] * f.dcurl[i][1] + f.dcurl[i][2] * f.dcurl[i][2] +
                  f.dcurl[i][3] * f.dcurl[i][3]);
    f.curlv[i] = curlv;
    if (balsara) f.balsara[i] = balsara_factor(divv, curlv, f.soundspeed[i], ctx.p.h[i]);
  }
}

void finish_velocity_gradient(const PassContext &ctx, double trigger, bool curl)
{
  const Fields &f = *ctx.f;
  const int dim = ctx.dim;
  for (int i = 0; i < ctx.p.nlocal; i++) {
    if (!ctx.p.gas(i)) continue;
    const double *g = f.vgsum[i];
    if (dim == 2)    // 0 where M is singular
      velocity_gradient_symmetric<2>(g, f.vgrad[i]);
    else
      velocity_gradient_symmetric<3>(g, f.vgrad[i]);
    const double volume = ctx.p.mass_of(i) / ctx.rho[i];
    f.vgrad[i][6] = trigger * (dim == 2 ? std::sqrt(volume) : std::cbrt(volume));
    if (curl) {    // G[3 a + k] = sum_j w_j v_ij,a r_ij,k at sums index 6 + 3 a + k
      f.dcurl[i][0] = g[6] + g[10] + g[14];
      f.dcurl[i][1] = g[11] - g[13];
      f.dcurl[i][2] = g[12] - g[8];
      f.dcurl[i][3] = g[7] - g[9];
    }
  }
}

}    // namespace SPHAstro
