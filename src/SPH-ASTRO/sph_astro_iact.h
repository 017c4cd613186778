/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The interaction of one particle pair, on plain numbers (no LAMMPS), in the manner of
// SWIFT's hydro_iact.h (runner_iact_density, runner_iact_force): each function takes what it
// needs of particles i and j and returns the contributions to both. The pair loops
// (sph_astro_pair_loop.h) gather the numbers and scatter the results; the unit tests call
// these functions directly.
//
// Kernel of a pair, r_ij = x_i - x_j, R the kernel radius (support R h):
//   mean h      W_ij = W(r_ij, h_ij), h_ij = (h_i + h_j)/2, for every term (Monaghan 1992)
//   two h       W(r_ij, h_i) and W(r_ij, h_j): with grad-h terms (Springel & Hernquist 2002;
//               Price 2012, J. Comput. Phys. 231, 759, eqs. 101-107) each pressure term takes
//               its own, the dissipative terms the mean of the two; with the averaged kernel
//               (keyword symmetrise kernel, Hernquist & Katz 1989, ApJS 70, 419) both are
//               replaced by their mean in every term.

#ifndef LMP_SPH_ASTRO_IACT_H
#define LMP_SPH_ASTRO_IACT_H

#include "sph_astro_conduction.h"
#include "sph_astro_kernel.h"
#include "sph_astro_pair_terms.h"
#include "sph_astro_reconstruction.h"

#include <cmath>

namespace SPHAstro {

/* ----------------------------------------------------------------------
   kernels of a pair
------------------------------------------------------------------------- */

// W(r, h) = sigma / h^d w(r/h) and (dW/dr)/r for one kernel and dimension
template <class KERNEL, int DIM> struct PairKernel {
  using K = Kernel<KERNEL, DIM>;
  const double sigma = K::sigma();
  static constexpr double R2 = K::radius * K::radius;

  double W(double r, double hinv) const
  {
    return sigma * inv_h_pow_dim<DIM>(hinv) * K::w(r * hinv);
  }
  double dW_over_r(double r, double rinv, double hinv) const
  {
    return sigma * inv_h_pow_dim<DIM>(hinv) * hinv * K::dw(r * hinv) * rinv;
  }
};

// particle i's part of its pairs' kernels, taken once per i
struct KernelSide {
  double h, hinv, support2;    // support2 = (R h)^2
  KernelSide(double hi, double R2) : h(hi), hinv(1.0 / hi), support2(R2 * hi * hi) {}
};

// W of a pair (density): false outside the support(s). Mean h: W(r, h_ij); two h: the mean
// of W(r, h_i) and W(r, h_j) (the averaged kernel; grad-h densities take W(h_i) in a pass of
// their own)
template <class KERNEL, int DIM, bool TWO_H>
inline bool pair_kernel_value(const PairKernel<KERNEL, DIM> &kern, const KernelSide &ki, double hj,
                              double r2, double &w)
{
  if (TWO_H) {
    const double support2j = kern.R2 * hj * hj;
    if (r2 >= ki.support2 && r2 >= support2j) return false;
    const double r = std::sqrt(r2);
    const double wi = r2 < ki.support2 ? kern.W(r, ki.hinv) : 0.0;
    const double wj = r2 < support2j ? kern.W(r, 1.0 / hj) : 0.0;
    w = 0.5 * (wi + wj);
    return true;
  }
  const double hij = 0.5 * (ki.h + hj);
  if (r2 >= kern.R2 * hij * hij) return false;
  w = kern.W(std::sqrt(r2), 1.0 / hij);
  return true;
}

// the kernel gradients of a pair, grad_i W = r_ij x dW/dr / r: dwi with h_i, dwj with h_j
// (equal with the mean h or the averaged kernel); false outside the support(s) and for r = 0
struct PairGradient {
  double r2, r, dwi, dwj;
  double mean() const { return 0.5 * (dwi + dwj); }
};

template <class KERNEL, int DIM, bool TWO_H>
inline bool pair_kernel_gradient(const PairKernel<KERNEL, DIM> &kern, const KernelSide &ki,
                                 double hj, double r2, bool average, PairGradient &g)
{
  if (r2 == 0.0) return false;
  g.r2 = r2;
  if (TWO_H) {
    const double support2j = kern.R2 * hj * hj;
    if (r2 >= ki.support2 && r2 >= support2j) return false;
    g.r = std::sqrt(r2);
    const double rinv = 1.0 / g.r;
    g.dwi = r2 < ki.support2 ? kern.dW_over_r(g.r, rinv, ki.hinv) : 0.0;
    g.dwj = r2 < support2j ? kern.dW_over_r(g.r, rinv, 1.0 / hj) : 0.0;
    if (average) g.dwi = g.dwj = g.mean();
    return true;
  }
  const double hij = 0.5 * (ki.h + hj);
  if (r2 >= kern.R2 * hij * hij) return false;
  g.r = std::sqrt(r2);
  g.dwi = g.dwj = kern.dW_over_r(g.r, 1.0 / g.r, 1.0 / hij);
  return true;
}

/* ----------------------------------------------------------------------
   density
------------------------------------------------------------------------- */

// rho_i = sum_j m_j W_ij (Monaghan 1992, eq. 2.7; with formulation pressure-energy the
// weights are m_j u_j: Hopkins 2013, MNRAS 428, 2840, eq. 13): the contribution to i is
// m_j W_ij, to j m_i W_ij
struct DensityContribution {
  double to_i, to_j;
};
inline DensityContribution iact_density(double weight_i, double weight_j, double w)
{
  return {weight_j * w, weight_i * w};
}

// One neighbour's terms of the h-rho iteration at h_i (gather: only i's sums), with
// q = r / h_i, w = w(q), dw = w'(q): m_j w and -m_j (d w + q w') (the sum of dW/dh without
// its factor sigma / h^(d+1); Price 2012, eq. 34)
struct GradhSums {
  double w = 0.0, dwdh = 0.0;
  void add(double weight, double w_q, double dw_q, double q, int dim)
  {
    w += weight * w_q;
    dwdh -= weight * (dim * w_q + q * dw_q);
  }
};

// velocity sums for div v and curl v (Monaghan 1992, eqs. 4.1-4.3): v_ij . grad_i W and
// v_ij x grad_i W, grad_i W = r_ij dw; the same for j (both products are even in i <-> j)
inline void iact_velocity_curl(double dvx, double dvy, double dvz, double dx, double dy, double dz,
                               double dw, double out[4])
{
  out[0] = (dvx * dx + dvy * dy + dvz * dz) * dw;
  out[1] = (dvy * dz - dvz * dy) * dw;
  out[2] = (dvz * dx - dvx * dz) * dw;
  out[3] = (dvx * dy - dvy * dx) * dw;
}

/* ----------------------------------------------------------------------
   force, heating, conductivity
------------------------------------------------------------------------- */

enum class PressureForm { STANDARD, GEOMETRIC, PRESSURE_ENERGY };

// loop-invariant settings of the force interaction
struct ForceSettings {
  PressureForm pressure = PressureForm::STANDARD;
  bool viscosity = true;              // artificial viscosity on
  bool signal = false;                // signal-velocity form (else classic)
  bool track_signal = false;          // max_j v_sig,ij wanted (signal form or the Courant's)
  double signal_beta = 3.0;           // beta of v_sig = c_i + c_j - beta w_ij
  bool reconstruct = false;           // on velocities reconstructed to the pair midpoint
  bool balsara = false;               // shear limiter factors in ForceParticle::shear
  bool alpha_per_particle = false;    // a switch sets alpha; beta = beta_factor x alpha
  double alpha = 1.0, beta = 2.0, beta_factor = 2.0, epsilon = 0.01;
  int gate = 16;           // smoothness gate exponent of the reconstruction
  bool energy = true;      // du/dt wanted (eos ideal)
  double alpha_u = 0.0;    // artificial conductivity (0: off)
  // grad-h factors: the standard pressure term's P/(Omega rho^2), C in pressure-energy
  bool gradh = false;
};

// what the force interaction reads of one particle. The pressure term of every form is
//   prho_i (b_j - C_i) dW_i + prho_j (b_i - C_j) dW_j
// and the weighted velocity divergence sum_j m_j (w_j - C_i) v_ij . grad_i W, with
//   STANDARD         prho = P/(Omega rho^2), b = 1, w = 1, C = 0
//   GEOMETRIC        prho = b = g = sqrt(P)/rho, w = 1, C = 0 (one kernel gradient)
//   PRESSURE_ENERGY  prho = e/P, b = w = e = (gamma-1) u, C the grad-h term (0 without)
struct ForceParticle {
  double m, rho, P, c, h;
  double prho, b, w, C;
  double alpha;           // viscosity alpha of the particle (switch) or the constant
  double shear;           // Balsara factor (1 without the limiter)
  double u;               // predicted u (conductivity)
  const double *vgrad;    // reconstruction: symmetric grad v and spacing
  double vx, vy, vz;      // predicted velocity
};

// contributions of one pair: the force on i is r_ij fpair (on j its opposite)
struct ForceContribution {
  double fpair;
  double vgw_i, vgw_j;      // sum_j m_j v_ij . grad_i W (pressure-energy: weights m_j (e_j - C_i))
  double heat_i, heat_j;    // dissipative heating (and the geometric P dV work)
  double vsig;              // signal velocity of the pair (when tracked, else 0)
  double crate_i, crate_j;    // conductivity diffusion rates m_j k, m_i k
};

// Momentum and energy equations of one pair (Monaghan 1992, eqs. 3.1 and 3.5; Price 2012,
// eqs. 105 and 107 with grad-h factors), r_ij = (dx, dy, dz), g the kernel gradients:
//   dv_i/dt += -m_j (P_i/(Omega_i rho_i^2) dW_i + P_j/(Omega_j rho_j^2) dW_j + Pi_ij dWbar) r_ij
//   du_i/dt += 1/2 m_j Pi_ij v_ij . r_ij dWbar    (+ P dV, summed through vgw_i)
// pressure geometric: 2 g_i g_j dW replaces the pressure term, its P dV work g_i g_j m_j v_ij .
// grad W goes to both; pressure-energy (Hopkins 2013, eqs. 16-18):
//   e_i (e_j - C_i)/P_i dW_i + e_j (e_i - C_j)/P_j dW_j.
// Viscosity Pi_ij: classic (Monaghan 1992, eq. 4.2) or signal (Monaghan 1997), with the
// Balsara factor or on reconstructed velocities (sph_astro_reconstruction.h: only pairs that
// approach both truly and reconstructed, and the heating keeps the true v_ij, so it is >= 0).
// Artificial conductivity (Price 2008, eq. 28): du_i/dt += -m_j k_ij (u_i - u_j) |dWbar| r,
// k_ij = alpha_u sqrt(|P_i - P_j|/rho_ij)/rho_ij. Every term is antisymmetric in force or
// heat flux, so momentum and energy are conserved pair by pair.
//
// The template arguments fix, where the caller knows them, what ForceSettings says at run time:
// VISC the viscosity (VISC_RUNTIME: read s); LEVEL the terms that may be on: FORCE_PLAIN none of
// the below, FORCE_COMMON a switch's alpha and conductivity, FORCE_ALL also the Balsara limiter,
// reconstruction and the other pressure forms (with the standard form below FORCE_ALL,
// b = w = 1 and C = 0). The pair loop compiles the common cases without the others' tests.
enum ViscosityVariant { VISC_NONE = 0, VISC_CLASSIC = 1, VISC_SIGNAL = 2, VISC_RUNTIME = 3 };
enum ForceLevel { FORCE_PLAIN = 0, FORCE_COMMON = 1, FORCE_ALL = 2 };

template <int VISC = VISC_RUNTIME, int LEVEL = FORCE_ALL>
[[gnu::always_inline]] inline void
iact_force(const ForceSettings &s, const ForceParticle &pi, const ForceParticle &pj, double dx,
           double dy, double dz, const PairGradient &g, ForceContribution &out)
{
  const bool viscosity = VISC == VISC_RUNTIME ? s.viscosity : VISC != VISC_NONE;
  const bool signal = VISC == VISC_RUNTIME ? s.signal : VISC == VISC_SIGNAL;
  const bool reconstruct = LEVEL == FORCE_ALL && s.reconstruct;
  const bool balsara = LEVEL == FORCE_ALL && s.balsara;
  const bool per_particle = LEVEL >= FORCE_COMMON && s.alpha_per_particle;
  const bool conductivity = LEVEL >= FORCE_COMMON && s.alpha_u > 0.0;
  const double dwi = g.dwi, dwj = g.dwj, dwbar = g.mean(), r = g.r;
  const double dvx = pi.vx - pj.vx, dvy = pi.vy - pj.vy, dvz = pi.vz - pj.vz;
  const double vdotr = dvx * dx + dvy * dy + dvz * dz;
  const double rhobar = 0.5 * (pi.rho + pj.rho);

  double visc = 0.0;
  out.vsig = 0.0;
  if ((viscosity && signal) || s.track_signal)
    out.vsig = signal_velocity(vdotr / r, pi.c, pj.c, s.signal_beta);
  if (viscosity) {
    double vdotr_visc = vdotr;
    if (reconstruct)
      vdotr_visc = reconstructed_vdotr(
          vdotr, velocity_slope(pi.vgrad, dx, dy, dz), velocity_slope(pj.vgrad, dx, dy, dz), r,
          0.5 * (pi.vgrad[6] + pj.vgrad[6]), pi.h > pj.h ? pi.h : pj.h, s.gate);
    if (vdotr_visc < 0.0 && (!reconstruct || vdotr < 0.0)) {
      const double a = per_particle ? 0.5 * (pi.alpha + pj.alpha) : s.alpha;
      const double shear = balsara ? 0.5 * (pi.shear + pj.shear) : 1.0;
      if (signal)
        visc = viscosity_signal(vdotr_visc, r, a, s.beta, pi.c, pj.c, rhobar, shear);
      else
        visc = viscosity_classic(vdotr_visc, g.r2, 0.5 * (pi.h + pj.h), a,
                                 per_particle ? s.beta_factor * a : s.beta, s.epsilon,
                                 0.5 * (pi.c + pj.c), rhobar, shear);
    }
  }

  const double pterm = pi.prho * (pj.b - pi.C) * dwi + pj.prho * (pi.b - pj.C) * dwj;
  out.fpair = -pi.m * pj.m * (pterm + visc * dwbar);
  out.vgw_i = continuity_rate(pj.m * (pj.w - pi.C), vdotr, dwi);
  out.vgw_j = continuity_rate(pi.m * (pi.w - pj.C), vdotr, dwj);

  out.heat_i = out.heat_j = 0.0;
  out.crate_i = out.crate_j = 0.0;
  if (!s.energy) return;
  if (s.pressure == PressureForm::GEOMETRIC) {
    const double pdv = pi.prho * pj.prho * vdotr * dwi;
    out.heat_i += pj.m * pdv;
    out.heat_j += pi.m * pdv;
  }
  if (viscosity) {    // (no test of visc: a data-dependent branch costs more than the sum)
    const double heat = 0.5 * visc * vdotr * dwbar;
    out.heat_i += pj.m * heat;
    out.heat_j += pi.m * heat;
  }
  if (conductivity) {
    const double crate = -conductivity_coefficient(s.alpha_u, pi.P, pj.P, rhobar) * dwbar * r;
    const double cond = -crate * (pi.u - pj.u);
    out.heat_i += pj.m * cond;
    out.heat_j -= pi.m * cond;
    out.crate_i = pj.m * crate;
    out.crate_j = pi.m * crate;
  }
}

// physical heat conduction of a pair (sph_astro_conduction.h; Brookshaw 1985; Cleary &
// Monaghan 1999): du_i/dt += m_j q, du_j/dt -= m_i q
inline double iact_conduction(double kappa, double ui, double uj, double rhoi, double rhoj,
                              double dw_over_r)
{
  return conduction_pair(kappa, kappa, ui, uj, rhoi, rhoj, dw_over_r);
}

// XSPH (Monaghan 1989, J. Comput. Phys. 82, 1; Monaghan 1992, eq. 4.1): the drift correction
// of i from j, eps m_j / rho_ij (v_j - v_i) W_ij (per unit velocity difference)
inline double iact_xsph(double mj, double rhoi, double rhoj, double w)
{
  return mj * w / (0.5 * (rhoi + rhoj));
}

}    // namespace SPHAstro

#endif
