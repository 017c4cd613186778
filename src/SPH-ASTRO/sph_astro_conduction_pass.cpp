/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Physical heat conduction (keyword conduction KAPPA; sph_astro_conduction.h), a pass of its
// own after the force pass, run only when kappa > 0:
//   du_i/dt += sum_j m_j 2 kappa (u_i - u_j) / (rho_i rho_j) (dW/dr)_ij / r_ij
// (Brookshaw 1985, Proc. ASA 6, 207; Cleary & Monaghan 1999, J. Comput. Phys. 148, 227) with
// (dW/dr)_ij at h_ij, or the mean of dW/dr at h_i and h_j (grad-h terms or the averaged
// kernel): symmetric in i and j, so each pair conserves sum m u exactly. XSPH (keyword xsph of
// fix sph/astro; Monaghan 1989): the drift correction over a full list.

#include "sph_astro_passes.h"

namespace SPHAstro {
namespace {

  struct ConductionAdapter {
    static constexpr KernelUse use = KernelUse::GRADIENT;
    const Particles &p;
    const double *rho, *u;
    double *conduct;
    double kappa;
    struct Own {
      double m, q;
    };
    void begin(int i, Own &own) const
    {
      own.m = p.mass_of(i);
      own.q = 0.0;
    }
    void pair(int i, int j, double, double, double, const PairGradient &g, Own &own,
              bool update_j) const
    {
      const double q = iact_conduction(kappa, u[i], u[j], rho[i], rho[j], g.dwi);
      own.q += p.mass_of(j) * q;
      if (update_j) conduct[j] -= own.m * q;
    }
    void end(int i, Own &own) const { conduct[i] += own.q; }
  };

  // sum_j m_j / rho_ij (v_j - v_i) W_ij to i, m_i / rho_ij (v_i - v_j) W_ij to j
  struct XsphAdapter {
    static constexpr KernelUse use = KernelUse::VALUE;
    const Particles &p;
    const double *rho;
    double **v;
    double **out;
    struct Own {
      double m, s[3];
    };
    void begin(int i, Own &own) const
    {
      own.m = p.mass_of(i);
      own.s[0] = own.s[1] = own.s[2] = 0.0;
    }
    void pair(int i, int j, double w, Own &own, bool update_j) const
    {
      const double fac_i = iact_xsph(p.mass_of(j), rho[i], rho[j], w);
      const double fac_j = iact_xsph(own.m, rho[i], rho[j], w);
      for (int d = 0; d < 3; d++) {
        const double dv = v[j][d] - v[i][d];
        own.s[d] += fac_i * dv;
        if (update_j) out[j][d] -= fac_j * dv;
      }
    }
    void end(int i, Own &own) const
    {
      for (int d = 0; d < 3; d++) out[i][d] += own.s[d];
    }
  };

}    // namespace

void conduction_pass(const PassContext &ctx, double kappa, bool two_h)
{
  double *conduct = ctx.f->conduct;
  const int nzero = ctx.nzero();
  for (int i = 0; i < nzero; i++) conduct[i] = 0.0;
  with_variant(ctx.kernel, ctx.dim, two_h, [&](auto v) {
    using V = decltype(v);
    ConductionAdapter act{ctx.p, ctx.rho, ctx.uest, conduct, kappa};
    pair_loop<typename V::kernel, V::dim, V::two_h>(ctx.half, ctx.p, ctx.newton, true, act);
  });
}

void xsph_pass(const PassContext &ctx, double **out)
{
  const int nzero = ctx.nzero();
  for (int i = 0; i < nzero; i++) out[i][0] = out[i][1] = out[i][2] = 0.0;
  with_variant(ctx.kernel, ctx.dim, false, [&](auto v) {
    using V = decltype(v);
    XsphAdapter act{ctx.p, ctx.rho, ctx.vest, out};
    pair_loop<typename V::kernel, V::dim, V::two_h>(ctx.half, ctx.p, ctx.newton, false, act);
  });
}

}    // namespace SPHAstro
