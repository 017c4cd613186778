/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO: the dissipative terms of one particle pair
------------------------------------------------------------------------- */

// Plain functions of the pair's numbers, shared by the pair loops (fixed/dh-dt h with the
// mean h_ij, and variable h with grad-h terms) and usable in unit tests without LAMMPS.

#ifndef LMP_SPH_ASTRO_PAIR_TERMS_H
#define LMP_SPH_ASTRO_PAIR_TERMS_H

#include <cmath>

namespace SPHAstro {

// Classic artificial viscosity (Monaghan 1992; seed 000 "standard formulation"):
//   Pi_ij = (-alpha c_ij mu_ij + beta mu_ij^2) / rho_ij  for v_ij . r_ij < 0, else 0
//   mu_ij = h_ij v_ij . r_ij / (r_ij^2 + eps h_ij^2), c_ij, rho_ij the pair means
// With the Balsara (1995) shear limiter mu_ij is multiplied by shear = (f_i + f_j)/2 (seed 000).
inline double viscosity_classic(double vdotr, double r2, double hij, double alpha, double beta,
                                double eps, double cbar, double rhobar, double shear = 1.0)
{
  if (vdotr >= 0.0) return 0.0;
  const double mu = shear * hij * vdotr / (r2 + eps * hij * hij);
  return (-alpha * cbar * mu + beta * mu * mu) / rhobar;
}

// Balsara factor f_i = |div v| / (|div v| + |curl v| + 0.0001 c / h)   (seed 000, "Balsara
// viscosity"): 1 in pure compression, 0 in pure shear
inline double balsara_factor(double divv, double curlv, double cs, double h)
{
  const double d = std::fabs(divv);
  const double denom = d + std::fabs(curlv) + 1e-4 * cs / h;
  return denom > 0.0 ? d / denom : 1.0;
}

// Artificial conductivity (Price 2008, J. Comput. Phys. 227, 10040, eqs. 28 and 30):
//   du_i/dt += sum_j m_j alpha_u v_sig (u_i - u_j) / rho_ij  (dW/dr)_ij
//   v_sig = sqrt(|P_i - P_j| / rho_ij)
// returns alpha_u v_sig (u_i - u_j) / rho_ij; multiplied by m_j dW/dr for i, by -m_i dW/dr
// for j, so that sum_i m_i du_i/dt is zero pair by pair.
inline double conductivity_flux(double alpha_u, double ui, double uj, double Pi, double Pj,
                                double rhobar)
{
  const double vsig = std::sqrt(std::fabs(Pi - Pj) / rhobar);
  return alpha_u * vsig * (ui - uj) / rhobar;
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

}    // namespace SPHAstro

#endif
