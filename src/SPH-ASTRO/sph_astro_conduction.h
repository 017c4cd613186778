/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: physical heat conduction, one particle pair
------------------------------------------------------------------------- */

// Heat conduction with a constant conductivity, written directly for the specific internal
// energy u. For the ideal gas u = c_v T with constant c_v, so the heat equation
//   rho c_v dT/dt = div(k grad T)               (Cleary & Monaghan 1999, J. Comput. Phys. 148, 227)
// reads rho du/dt = div(kappa grad u) with kappa = k / c_v, the conductivity the keyword
// `conduction KAPPA` of pair sph/astro takes (units mass / (length time)). The diffusivity of
// u and of T is D = kappa / rho. No mean molecular weight or gas constant is needed.
//
// Second derivative from the first derivative of the kernel (Brookshaw 1985, Proc. ASA 6, 207;
// Cleary & Monaghan 1999, J. Comput. Phys. 148, 227):
//   du_i/dt += sum_j m_j (kappa_i + kappa_j) (u_i - u_j) / (rho_i rho_j)
//                    (r_ij . grad_i W_ij) / r_ij^2
// With kappa_i = kappa_j = kappa this is (kappa / rho_i) x Brookshaw's Laplacian,
//   lap u_i = 2 sum_j m_j / rho_j (u_i - u_j) (r_ij . grad_i W_ij) / r_ij^2.
// r_ij . grad_i W_ij / r_ij^2 = (dW/dr) / r is symmetric in i, j and negative, so heat flows
// from hot to cold and m_i du_i + m_j du_j = 0 pair by pair: sum_i m_i du_i/dt = 0.
//
// Explicit stability (timestep of fix sph/astro, keyword `conduction C`):
//   dt < C rho_i h_i^2 / kappa   (= C h^2 / D; the form of Cleary & Monaghan 1999 with
//                                 c_v folded into kappa)

#ifndef LMP_SPH_ASTRO_CONDUCTION_H
#define LMP_SPH_ASTRO_CONDUCTION_H

namespace SPHAstro {

// (kappa_i + kappa_j)(u_i - u_j) / (rho_i rho_j) x (dW/dr)/r; du_i/dt gains m_j times it,
// du_j/dt loses m_i times it
inline double conduction_pair(double kappa_i, double kappa_j, double ui, double uj, double rhoi,
                              double rhoj, double dwdr_over_r)
{
  return (kappa_i + kappa_j) * (ui - uj) / (rhoi * rhoj) * dwdr_over_r;
}

// the largest stable step of the explicit conduction update at one particle
inline double conduction_timestep(double factor, double rho, double h, double kappa)
{
  return factor * rho * h * h / kappa;
}

}    // namespace SPHAstro

#endif
