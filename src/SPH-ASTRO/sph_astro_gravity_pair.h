/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The kernel-softened gravity of one pair inside its softening support, shared by direct
// summation (pair sph/astro/gravity) and the tree (kspace tree/sph/astro/gravity), so that the
// two sum the same pair terms:
//   phi_ij = [phi(r, h_i) + phi(r, h_j)] / 2,   dphi_ij/dr likewise
// (Price & Monaghan 2007, MNRAS 374, 1347, sec. 2.2; sph_astro_gravity_kernel.h), and the
// adaptive-softening ("zeta") term of the pair, per G m_i m_j and divided by nothing,
//   dzeta = [zeta_i/Omega_i dW/dr(r, h_i) + zeta_j/Omega_j dW/dr(r, h_j)] / 2
// (Price & Monaghan 2007, sec. 3; the force on i is -G m_i m_j (dphi_ij/dr + dzeta) r_ij/r).

#ifndef LMP_SPH_ASTRO_GRAVITY_PAIR_H
#define LMP_SPH_ASTRO_GRAVITY_PAIR_H

#include "sph_astro_gravity_kernel.h"

namespace SPHAstro {

// phi_ij and dphi_ij/dr for r inside max(R h_i, R h_j) (fpot and fforce of the kernel:
// the closed form of M4 when CUBIC, else soft's)
template <bool CUBIC>
inline void softened_pair_inside(const SoftenedKernel &soft, double r, double hi, double hj,
                                 double &phi, double &dphi)
{
  const double hiinv = 1.0 / hi;
  double pi, fi;
  if (CUBIC)
    SoftenedCubic::eval(r * hiinv, pi, fi);
  else
    soft.eval(r * hiinv, pi, fi);
  phi = pi * hiinv;
  dphi = fi * hiinv * hiinv;
  if (hj != hi) {
    const double hjinv = 1.0 / hj;
    double pj, fj;
    if (CUBIC)
      SoftenedCubic::eval(r * hjinv, pj, fj);
    else
      soft.eval(r * hjinv, pj, fj);
    phi = 0.5 * (phi + pj * hjinv);
    dphi = 0.5 * (dphi + fj * hjinv * hjinv);
  }
}

// the pair's zeta term (r > 0); zoi, zoj: zeta/Omega of the two particles
inline double zeta_pair_term(KernelType kernel, double r, double hi, double hj, double zoi,
                             double zoj)
{
  return 0.5 * (zoi * kernel_dwdr3(kernel, r, hi) + zoj * kernel_dwdr3(kernel, r, hj));
}

}    // namespace SPHAstro

#endif
