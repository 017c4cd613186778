/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The dissipative and pressure terms of one particle pair, and the viscosity switches

// Plain functions of the pair's numbers, shared by the pair loops (fixed/dh-dt h with the
// mean h_ij, and variable h with grad-h terms) and usable in unit tests without LAMMPS.

#ifndef LMP_SPH_ASTRO_PAIR_TERMS_H
#define LMP_SPH_ASTRO_PAIR_TERMS_H

#include <cmath>

namespace SPHAstro {

// Geometric-mean pressure term (an alternative symmetrisation of the pressure force):
//   1/2 (P_i/rho_i^2 + P_j/rho_j^2)  ->  sqrt(P_i P_j)/(rho_i rho_j)
// so the pair term of the momentum equation is 2 sqrt(P_i P_j)/(rho_i rho_j) = 2 g_i g_j with
// g = sqrt(P)/rho per particle (iact_force, sph_astro_iact.h); the energy equation in the same form (as Monaghan 1992 pairs
// the energy equation with the force) gives both partners the P dV work
//   du_i/dt = sum_j m_j g_i g_j v_ij . grad_i W_ij,
// so m_i du_i + m_j du_j = -(work of the pair force): the total energy is conserved.
inline double pressure_geometric_factor(double P, double rho)
{
  return std::sqrt(P) / rho;
}

// Continuity equation in the form that vanishes for uniform motion (Monaghan 1992, eq. 2.12):
// drho_i/dt = sum_j m_j v_ij . grad_i W_ij, with grad_i W_ij = r_ij (dW/dr)/r; the pair's
// contribution for particle i, vdotr = v_ij . r_ij, dwdr_r = (dW/dr)/r
inline double continuity_rate(double mj, double vdotr, double dwdr_r)
{
  return mj * vdotr * dwdr_r;
}

// Classic artificial viscosity (Monaghan & Gingold 1983; Monaghan 1992, eq. 4.2):
//   Pi_ij = (-alpha c_ij mu_ij + beta mu_ij^2) / rho_ij  for v_ij . r_ij < 0, else 0
//   mu_ij = h_ij v_ij . r_ij / (r_ij^2 + eps h_ij^2), c_ij, rho_ij the pair means
// With the Balsara (1995) shear limiter mu_ij is multiplied by shear = (f_i + f_j)/2.
inline double viscosity_classic(double vdotr, double r2, double hij, double alpha, double beta,
                                double eps, double cbar, double rhobar, double shear = 1.0)
{
  if (vdotr >= 0.0) return 0.0;
  const double mu = shear * hij * vdotr / (r2 + eps * hij * hij);
  return (-alpha * cbar * mu + beta * mu * mu) / rhobar;
}

// Signal-velocity artificial viscosity (Monaghan 1997, J. Comput. Phys. 136, 298, by analogy
// with Riemann solvers; in this form in Springel 2005, MNRAS 364, 1105, eqs. 14-15):
//   Pi_ij = -(alpha/2) v_sig w_ij / rho_ij   for w_ij = v_ij . r_ij / |r_ij| < 0, else 0
//   v_sig = c_i + c_j - beta w_ij            (beta = 3)
// The quadratic term alpha beta w^2 / 2 scales with alpha by construction, so a per-particle
// alpha needs no separate beta. The Balsara limiter multiplies Pi_ij by shear = (f_i + f_j)/2.
inline double signal_velocity(double w, double ci, double cj, double beta)
{
  return ci + cj - beta * (w < 0.0 ? w : 0.0);
}

inline double viscosity_signal(double vdotr, double r, double alpha, double beta, double ci,
                               double cj, double rhobar, double shear = 1.0)
{
  if (vdotr >= 0.0) return 0.0;
  const double w = vdotr / r;
  return -0.5 * shear * alpha * signal_velocity(w, ci, cj, beta) * w / rhobar;
}

// Balsara factor f_i = |div v| / (|div v| + |curl v| + 0.0001 c / h)   (Balsara 1995,
// J. Comput. Phys. 121, 357): 1 in pure compression, 0 in pure shear
inline double balsara_factor(double divv, double curlv, double cs, double h)
{
  const double d = std::fabs(divv);
  const double denom = d + std::fabs(curlv) + 1e-4 * cs / h;
  return denom > 0.0 ? d / denom : 1.0;
}

// Artificial conductivity (Price 2008, J. Comput. Phys. 227, 10040, eqs. 28 and 30):
//   du_i/dt += sum_j m_j alpha_u v_sig (u_i - u_j) / rho_ij  (dW/dr)_ij
//   v_sig = sqrt(|P_i - P_j| / rho_ij)
// conductivity_coefficient is alpha_u v_sig / rho_ij, the same for i and j: the flux
// coefficient x (u_i - u_j) is multiplied by m_j dW/dr for i and by -m_i dW/dr for j, so that
// sum_i m_i du_i/dt is zero pair by pair; du_i/dt = -sum_j k_ij (u_i - u_j) with
// k_ij = m_j coefficient |dW/dr|_ij >= 0, whose rate sum_j k_ij bounds the explicit step
// (fix sph/astro: dt <= C / sum_j k_ij; Gershgorin: the largest eigenvalue of the diffusion
// is at most 2 max_i sum_j k_ij, and the predictor-corrector u update is stable for
// dt x eigenvalue <= 2, so C <= 1 is stable)
inline double conductivity_coefficient(double alpha_u, double Pi, double Pj, double rhobar)
{
  const double vsig = std::sqrt(std::fabs(Pi - Pj) / rhobar);
  return alpha_u * vsig / rhobar;
}

// Morris & Monaghan (1997) viscosity switch, one step of
//   d alpha/dt = -(alpha - alpha_min) / tau + S (alpha_max - alpha)
//   tau = h / (l c_s),  S = max(-div v, 0)
// solved exactly with div v, c_s and h frozen over dt; stays in [alpha_min, alpha_max].
inline double switch_morris_monaghan(double alpha, double divv, double cs, double h, double dt,
                                     double alpha_min, double alpha_max, double ell)
{
  const double inv_tau = ell * cs / h;
  const double source = divv < 0.0 ? -divv : 0.0;
  const double k = inv_tau + source;
  if (!(k > 0.0)) return alpha;    // cold and not compressed: nothing drives alpha
  const double alpha_eq = (alpha_min * inv_tau + source * alpha_max) / k;
  return alpha_eq + (alpha - alpha_eq) * std::exp(-k * dt);
}

// Cullen & Dehnen (2010, MNRAS 408, 669) viscosity switch in the simplified form of Phantom
// (Price et al. 2018, PASA 35, e031) and SPHENIX (Borrow et al. 2022, MNRAS 511,
// 2367), with d(div v)/dt from the change of div v over the last step:
//   xi_i  = max(-div v_i, 0)^2 / (max(-div v_i, 0)^2 + |curl v_i|^2)   (1 if both vanish)
//   A_i   = xi_i max(-d(div v_i)/dt, 0)                   (shock indicator: growing compression)
//   alpha_loc = min(10 h_i^2 A_i / c_i^2, alpha_max), at least alpha_min
//   alpha_i -> alpha_loc at once if alpha_loc > alpha_i, else it decays towards alpha_loc,
//   d alpha_i/dt = -(alpha_i - alpha_loc) / tau_i, tau_i = h_i / (l c_i), solved exactly
//   at frozen coefficients.
inline double cullen_dehnen_limiter(double divv, double curlv)
{
  const double c = divv < 0.0 ? divv * divv : 0.0;
  const double denom = c + curlv * curlv;
  return denom > 0.0 ? c / denom : 1.0;
}

inline double cullen_dehnen_alpha_loc(double ddivvdt, double xi, double cs, double h,
                                      double alpha_min, double alpha_max)
{
  const double source = 10.0 * h * h * xi * (ddivvdt < 0.0 ? -ddivvdt : 0.0);
  const double c2 = cs * cs;
  if (!(c2 > 0.0)) return source > 0.0 ? alpha_max : alpha_min;
  const double a = source / c2;
  return a > alpha_max ? alpha_max : (a < alpha_min ? alpha_min : a);
}

inline double switch_cullen_dehnen(double alpha, double divv, double ddivvdt, double curlv,
                                   double cs, double h, double dt, double alpha_min,
                                   double alpha_max, double ell)
{
  const double xi = cullen_dehnen_limiter(divv, curlv);
  const double aloc = cullen_dehnen_alpha_loc(ddivvdt, xi, cs, h, alpha_min, alpha_max);
  if (aloc >= alpha) return aloc;
  const double inv_tau = ell * cs / h;
  if (!(inv_tau > 0.0)) return alpha;
  return aloc + (alpha - aloc) * std::exp(-inv_tau * dt);
}

}    // namespace SPHAstro

#endif
