/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Per-particle thermodynamics of pair sph/astro (sph_astro_passes.h): the equation of state
// with its checks, the density of the pressure-energy formulation, and du/dt (dA/dt) from the
// force pass's sums.

#include "sph_astro_passes.h"

#include "error.h"

#include <cmath>

using namespace LAMMPS_NS;

namespace SPHAstro {

// P and c_s of the owned atoms from the density of this evaluation and u_est. Thermal entropy
// (Springel & Hernquist 2002): P = A rho^gamma, u_est = A_est rho^(gamma-1)/(gamma-1), and A
// from u when init_entropy. Stops with the atom ID on a non-positive or non-finite density, an
// h beyond its list's cap or a negative or non-finite u.
void equation_of_state(const PassContext &ctx, const EOS &eos, double h_cap,
                       bool density_continuity, const EntropyArrays *entropy, bool init_entropy)
{
  const int nlocal = ctx.p.nlocal;
  const double *rho = ctx.rho;
  const double *h = ctx.p.h;
  double *uest = ctx.uest;
  Fields &f = *ctx.f;
  if (entropy) {
    const double g1 = eos.gamma - 1.0;
    for (int i = 0; i < nlocal; i++) {
      if (init_entropy)
        entropy->Aest[i] = entropy->A[i] = g1 * entropy->u[i] * std::pow(rho[i], -g1);
      uest[i] = entropy->Aest[i] * std::pow(rho[i], g1) / g1;
    }
  }
  for (int i = 0; i < nlocal; i++) {
    if (!ctx.is_sph(i)) {    // (a sink or star: no gas state)
      f.pressure[i] = f.soundspeed[i] = 0.0;
      continue;
    }
    if (!(rho[i] > 0.0) || !std::isfinite(rho[i]))
      ctx.error->one(FLERR, "pair_style sph/astro: atom {} has density {} ({}position not finite?)",
                     ctx.tag[i], rho[i],
                     density_continuity ? "density continuity: too large a timestep? " : "");
    if (h[i] > h_cap)
      ctx.error->one(FLERR,
                     "pair_style sph/astro: atom {} has h = {} larger than the h = {} the ghost "
                     "atoms serve (LAMMPS' ghost cutoff); h was changed during a run (fix "
                     "sph/astro/h keeps h below that cap and widens the ghost cutoff as h grows)",
                     ctx.tag[i], h[i], h_cap);
    const double u = uest[i];
    if (eos.uses_energy() && (!(u >= 0.0) || !std::isfinite(u)))
      ctx.error->one(FLERR,
                     "pair_style sph/astro: atom {} has specific internal energy u = {}; u must "
                     "be finite and >= 0",
                     ctx.tag[i], u);
    eos.pressure_soundspeed(rho[i], u, f.pressure[i], f.soundspeed[i]);
  }
}

// formulation pressure-energy: rho_i = (sum_j m_j u_j W_ij) / u_i, the density that makes the
// ideal-gas pressure (gamma-1) rho_i u_i equal the smoothed one (Saitoh & Makino 2013, the
// volume element m_i u_i / sum_j m_j u_j W_ij), into rho_sum
void pressure_energy_density(const PassContext &ctx, const double *energy_sum)
{
  const double *uest = ctx.uest;
  for (int i = 0; i < ctx.p.nlocal; i++) {
    if (!(uest[i] > 0.0) || !std::isfinite(uest[i]))
      ctx.error->one(FLERR,
                     "pair_style sph/astro formulation pressure-energy: atom {} has specific "
                     "internal energy u = {}; this formulation needs u > 0 (rho = P/((gamma-1) u))",
                     ctx.tag[i], uest[i]);
    ctx.rho_sum[i] = energy_sum[i] / uest[i];
  }
}

// du_i/dt so far holds the dissipative heating (viscosity, conductivity); add the P dV work
// P_i/(Omega_i rho_i^2) sum_j m_j v_ij . grad W (Monaghan 1992, eq. 3.5; Price 2012, eq. 107;
// omega: the grad-h factor). Thermal entropy: dA_i/dt = (gamma-1)/rho_i^(gamma-1) x heating
// (Springel & Hernquist 2002). pdv_done: the P dV work is in du/dt already (pressure geometric).
void thermal_rates(const PassContext &ctx, const EOS &eos, bool omega, bool pdv_done, double *dAdt)
{
  const Fields &f = *ctx.f;
  const int nlocal = ctx.p.nlocal;
  const double *rho = ctx.rho;
  double *dudt = ctx.dudt;
  if (dAdt) {
    const double g1 = eos.gamma - 1.0;
    for (int i = 0; i < nlocal; i++) dAdt[i] = g1 * std::pow(rho[i], -g1) * dudt[i];
  }
  if (pdv_done) return;
  for (int i = 0; i < nlocal; i++)
    dudt[i] += f.pressure[i] / ((omega ? f.omega[i] : 1.0) * rho[i] * rho[i]) * f.vdotgradw[i];
}

}    // namespace SPHAstro
