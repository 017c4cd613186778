/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Force pass of pair sph/astro (sph_astro_passes.h): accelerations, dissipative heating,
// sum_j m_j v_ij . grad_i W_ij (for P dV and div v), the signal velocities and the
// conductivity's diffusion rates, over the half list, with iact_force() (sph_astro_iact.h)
// for each pair. finish_force() then gives
//   div v_i = -1/(Omega_i rho_i) sum_j m_j v_ij . grad_i W_ij      (Omega = 1 without grad-h)
// with pressure-energy the sum carries the weights m_j (e_j - C_i) and is divided by e_i
// (Hopkins 2013, eq. 18), so that P_i/rho_i^2 times it is the P dV work in every formulation.

#include "sph_astro_passes.h"

#include "pair.h"

#include <type_traits>

namespace SPHAstro {
namespace {

  // VISC, LEVEL: the variant of iact_force (sph_astro_iact.h) this scene needs
  template <int VISC, int LEVEL> struct ForceAdapter {
    static constexpr KernelUse use = KernelUse::GRADIENT;
    const PassContext &ctx;
    const ForceSettings s;    // a copy: no store to a double array can change it
    const Fields &f;
    // (f and v_est from their first rows: LAMMPS' per-atom arrays are contiguous, and a
    // partner's values are then one load, not its row pointer and then the row)
    double *force;
    const double *vest;
    double *dudt;
    struct Own {
      ForceParticle pi;
      double fx, fy, fz, vgw, heat, vsig, crate;
      int recorded;    // the evaluated pairs recorded before i's row
    };
    // per-particle factors of the pressure term (ForceParticle); null: 1 (b, w) or 0 (C)
    const double *prho, *b, *w, *C;
    [[gnu::always_inline]] void load(int i, ForceParticle &q) const
    {
      q.m = ctx.p.mass_of(i);
      q.rho = ctx.rho[i];
      q.P = f.pressure[i];
      q.c = f.soundspeed[i];
      q.h = ctx.p.h[i];
      q.prho = prho[i];
      if (LEVEL == FORCE_ALL) {
        q.b = b ? b[i] : 1.0;
        q.w = w ? w[i] : 1.0;
        q.C = C ? C[i] : 0.0;
        q.shear = s.balsara ? f.balsara[i] : 1.0;
        q.vgrad = s.reconstruct ? f.vgrad[i] : nullptr;
      } else {
        q.b = q.w = 1.0;
        q.C = 0.0;
        q.shear = 1.0;
        q.vgrad = nullptr;
      }
      if (LEVEL >= FORCE_COMMON) {
        q.alpha = s.alpha_per_particle ? ctx.alpha[i] : s.alpha;
        q.u = s.alpha_u > 0.0 ? ctx.uest[i] : 0.0;
      } else {
        q.alpha = s.alpha;
        q.u = 0.0;
      }
      q.vx = vest[3 * i];
      q.vy = vest[3 * i + 1];
      q.vz = vest[3 * i + 2];
    }
    void begin(int i, Own &own) const
    {
      load(i, own.pi);
      own.fx = own.fy = own.fz = own.vgw = own.heat = own.vsig = own.crate = 0.0;
      own.recorded = ctx.pairs ? static_cast<int>(ctx.pairs->partner.size()) : 0;
    }
    [[gnu::always_inline]] void pair(int i, int j, double dx, double dy, double dz,
                                     const PairGradient &g, Own &own, bool update_j) const
    {
      ForceParticle pj;
      load(j, pj);
      ForceContribution c;
      iact_force<VISC, LEVEL>(s, own.pi, pj, dx, dy, dz, g, c);
      own.fx += dx * c.fpair;
      own.fy += dy * c.fpair;
      own.fz += dz * c.fpair;
      own.vgw += c.vgw_i;
      own.heat += c.heat_i;
      own.crate += c.crate_i;
      if (c.vsig > own.vsig) own.vsig = c.vsig;
      if (update_j) {
        force[3 * j] -= dx * c.fpair;
        force[3 * j + 1] -= dy * c.fpair;
        force[3 * j + 2] -= dz * c.fpair;
        f.vdotgradw[j] += c.vgw_j;
        if (s.energy) dudt[j] += c.heat_j;
        if (s.track_signal && c.vsig > f.vsigmax[j]) f.vsigmax[j] = c.vsig;
        if (LEVEL >= FORCE_COMMON && s.alpha_u > 0.0) f.condrate[j] += c.crate_j;
      }
      if (ctx.pairs) {
        if (ctx.pairs->heats) {
          // the pair's du/dt terms: the P dV work (in heat with the geometric form) and heat
          const bool pdv = s.pressure != PressureForm::GEOMETRIC;
          ctx.pairs->add(j, update_j, c.fpair, c.heat_i + (pdv ? own.pi.prho * c.vgw_i : 0.0),
                         c.heat_j + (pdv ? pj.prho * c.vgw_j : 0.0));
        } else {
          ctx.pairs->add(j, update_j, c.fpair, 0.0, 0.0);
        }
      }
      if (ctx.tally)
        ctx.tally->ev_tally(i, j, ctx.p.nlocal, ctx.newton, 0.0, 0.0, c.fpair, dx, dy, dz);
    }
    void end(int i, Own &own) const
    {
      force[3 * i] += own.fx;
      force[3 * i + 1] += own.fy;
      force[3 * i + 2] += own.fz;
      f.vdotgradw[i] += own.vgw;
      if (s.energy) dudt[i] += own.heat;
      if (s.track_signal && own.vsig > f.vsigmax[i]) f.vsigmax[i] = own.vsig;
      if (LEVEL >= FORCE_COMMON && s.alpha_u > 0.0) f.condrate[i] += own.crate;
      if (ctx.pairs) ctx.pairs->end_row(i, own.recorded);
    }
  };

}    // namespace

ForceSettings force_settings(const PairOptions &o, bool gradh, bool per_particle_alpha)
{
  ForceSettings s;
  s.pressure = o.pressure_energy ? PressureForm::PRESSURE_ENERGY
      : o.pressure_geometric     ? PressureForm::GEOMETRIC
                                 : PressureForm::STANDARD;
  s.viscosity = o.has_viscosity();
  s.signal = o.signal_viscosity();
  s.track_signal = o.tracks_signal();
  s.signal_beta = o.signal_beta();
  s.reconstruct = o.reconstruction();
  s.balsara = o.balsara;
  s.alpha_per_particle = per_particle_alpha;
  s.alpha = o.alpha;
  s.beta = o.beta;
  s.beta_factor = o.beta_factor();
  s.epsilon = o.epsilon;
  s.gate = o.recon_gate;
  s.energy = o.eos.uses_energy();    // only the ideal gas evolves u (and has conductivity)
  s.alpha_u = o.artificial_conductivity() ? o.conductivity : 0.0;
  s.gradh = gradh;
  return s;
}

void force_pass(const PassContext &ctx, const ForceSettings &s, bool two_h, bool average)
{
  Fields &f = *ctx.f;
  const bool signal = s.viscosity && s.signal;
  const int nzero = ctx.nzero();
  const int nlocal = ctx.p.nlocal;
  const char *ghosts = ctx.ghosts_in_pairs;
  for (int i = 0; i < nzero; i++) {
    if (ghosts && i >= nlocal && !ghosts[i]) continue;
    f.vdotgradw[i] = 0.0;
    if (s.energy) ctx.dudt[i] = 0.0;
    if (s.track_signal) f.vsigmax[i] = 2.0 * f.soundspeed[i];    // the pair with itself
    if (s.alpha_u > 0.0) f.condrate[i] = 0.0;
  }
  ForceSettings settings = s;
  settings.signal = signal;
  // the pressure term's factors of owned and ghost atoms (ForceParticle)
  const int nall = ctx.p.nall;
  const bool pe = s.pressure == PressureForm::PRESSURE_ENERGY;
  const bool geo = s.pressure == PressureForm::GEOMETRIC;
  for (int i = 0; i < nall; i++) {
    if (ghosts && i >= nlocal && !ghosts[i]) continue;
    const double rho = ctx.rho[i];
    f.prho[i] = geo ? f.pressure_factor[i]
        : pe        ? f.pressure_factor[i] / f.pressure[i]
                    : f.pressure[i] / ((s.gradh ? f.omega[i] : 1.0) * rho * rho);
  }
  const double *b = (pe || geo) ? f.pressure_factor : nullptr;
  const double *w = pe ? f.pressure_factor : nullptr;
  const double *C = (pe && s.gradh) ? f.pe_gradh : nullptr;
  // templates where they pay (doc/performance.md): the viscosity form, and which of the
  // switch's alpha, conductivity, Balsara, reconstruction and the other pressure forms may act
  const int visc = !s.viscosity ? VISC_NONE : signal ? VISC_SIGNAL : VISC_CLASSIC;
  const int level = (s.balsara || s.reconstruct || s.pressure != PressureForm::STANDARD) ? FORCE_ALL
      : (s.alpha_per_particle || s.alpha_u > 0.0) ? FORCE_COMMON
                                                  : FORCE_PLAIN;
  if (ctx.pairs) {    // at most one record per list entry
    std::size_t entries = 0;
    for (int ii = 0; ii < ctx.half.inum; ii++) entries += ctx.half.numneigh[ctx.half.ilist[ii]];
    ctx.pairs->reserve(ctx.half.inum, entries);
  }
  if (ctx.half.inum == 0) return;
  double *force = ctx.force[0];
  const double *vest = ctx.vest[0];
  with_variant(ctx.kernel, ctx.dim, two_h, [&](auto v) {
    using V = decltype(v);
    auto run = [&](auto adapter) {
      pair_loop<typename V::kernel, V::dim, V::two_h>(ctx.half, ctx.p, ctx.newton, average,
                                                      adapter);
    };
    auto adapter = [&](auto visc_tag, auto level_tag) {
      constexpr int VISC = decltype(visc_tag)::value, LEVEL = decltype(level_tag)::value;
      run(ForceAdapter<VISC, LEVEL>{ctx, settings, f, force, vest, ctx.dudt, f.prho, b, w, C});
    };
    using Plain = std::integral_constant<int, FORCE_PLAIN>;
    using Common = std::integral_constant<int, FORCE_COMMON>;
    if (level == FORCE_ALL)
      adapter(std::integral_constant<int, VISC_RUNTIME>(),
              std::integral_constant<int, FORCE_ALL>());
    else if (visc == VISC_NONE)
      level == FORCE_PLAIN ? adapter(std::integral_constant<int, VISC_NONE>(), Plain())
                           : adapter(std::integral_constant<int, VISC_NONE>(), Common());
    else if (visc == VISC_CLASSIC)
      level == FORCE_PLAIN ? adapter(std::integral_constant<int, VISC_CLASSIC>(), Plain())
                           : adapter(std::integral_constant<int, VISC_CLASSIC>(), Common());
    else
      level == FORCE_PLAIN ? adapter(std::integral_constant<int, VISC_SIGNAL>(), Plain())
                           : adapter(std::integral_constant<int, VISC_SIGNAL>(), Common());
  });
}

void finish_force(const PassContext &ctx, const ForceSettings &s)
{
  Fields &f = *ctx.f;
  const int nlocal = ctx.p.nlocal;
  const bool pe = s.pressure == PressureForm::PRESSURE_ENERGY;
  if (pe)
    for (int i = 0; i < nlocal; i++)
      if (ctx.p.gas(i)) f.vdotgradw[i] /= f.pressure_factor[i];
  // (the pressure-energy grad-h terms are in C, not in Omega)
  const bool omega = s.gradh && !pe;
  for (int i = 0; i < nlocal; i++)
    f.divv[i] = ctx.p.gas(i) ? -f.vdotgradw[i] / ((omega ? f.omega[i] : 1.0) * ctx.rho[i]) : 0.0;
}

}    // namespace SPHAstro
