/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: kernel-softened Newtonian gravity
------------------------------------------------------------------------- */

// A particle of mass m spread with the SPH kernel W(r,h) of sph_astro_kernel.h (3D) has the
// potential G m phi(r,h) and the radial force per unit mass -G m dphi/dr (Price & Monaghan 2007,
// MNRAS 374, 1347, sec. 2, "kernel softening"):
//
//   dphi/dr = M(<r)/r^2,     M(<r) = 4 pi int_0^r W(r',h) r'^2 dr'   (mass fraction inside r)
//   phi(r)  = -1/r                                 for r >= R h (outside the support R h)
//   phi(r)  = -1/(R h) - int_r^{Rh} dphi/dr' dr'   inside
//
// so that both are Newtonian beyond the support and finite at r = 0. In q = r/h:
//   phi = fpot(q)/h,  dphi/dr = fforce(q)/h^2.
//
// Cubic spline M4 (support 2h): the closed form of Price & Monaghan 2007, appendix A
// (also Hernquist & Katz 1989, ApJS 70, 419):
//   q < 1:   fpot = 2/3 q^2 - 3/10 q^4 + 1/10 q^5 - 7/5
//            fforce = 4/3 q - 6/5 q^3 + 1/2 q^4
//   1<=q<2:  fpot = 4/3 q^2 - q^3 + 3/10 q^4 - 1/30 q^5 - 8/5 + 1/(15 q)
//            fforce = 8/3 q - 3 q^2 + 6/5 q^3 - 1/6 q^4 - 1/(15 q^2)
//   q >= 2:  fpot = -1/q, fforce = 1/q^2
//
// Every kernel of the package is a piecewise polynomial w(q) = sum_n w_n q^n on intervals
// [e_k, e_k+1), so the integrals above are closed forms for all of them: with
// A_n = 4 pi sigma w_n / (n+3),
//   fforce(q) = C_k / q^2 + sum_n A_n q^(n+1),          C_k = M(e_k) - sum_n A_n e_k^(n+3)
//   fpot(q)   = E_k - C_k / q + sum_n A_n q^(n+2)/(n+2)  (E_k from continuity at e_k+1,
//                                                        fpot(R) = -1/R)
// SoftenedKernel builds these coefficients once from the kernel's polynomial pieces (the
// piece polynomials are checked against Kernel<K,3>::w in the unit tests, the integrals
// against numerical quadrature). Pair symmetrisation (Price & Monaghan 2007, eq. for the
// force between particles of different softening lengths): the average of the values for
// h_i and h_j, see softened_pair().

#ifndef LMP_SPH_ASTRO_GRAVITY_KERNEL_H
#define LMP_SPH_ASTRO_GRAVITY_KERNEL_H

#include "sph_astro_kernel.h"

#include <cmath>

namespace SPHAstro {

// closed form for the cubic spline M4 (support 2h)
struct SoftenedCubic {
  static constexpr double radius = 2.0;
  static inline void eval(double q, double &fpot, double &fforce)
  {
    if (q < 1.0) {
      const double q2 = q * q;
      fpot = q2 * (2.0 / 3.0 + q2 * (-0.3 + 0.1 * q)) - 1.4;
      fforce = q * (4.0 / 3.0 + q2 * (-1.2 + 0.5 * q));
    } else if (q < 2.0) {
      const double q2 = q * q;
      fpot = q2 * (4.0 / 3.0 + q * (-1.0 + q * (0.3 - q / 30.0))) - 1.6 + 1.0 / (15.0 * q);
      fforce = q * (8.0 / 3.0 + q * (-3.0 + q * (1.2 - q / 6.0))) - 1.0 / (15.0 * q2);
    } else {
      fpot = -1.0 / q;
      fforce = 1.0 / (q * q);
    }
  }
};

// closed form for any piecewise-polynomial kernel (3D), coefficients built at construction
class SoftenedKernel {
 public:
  static constexpr int MAXPIECES = 3;
  static constexpr int MAXDEG = 10;    // degree of w(q) on a piece

  explicit SoftenedKernel(KernelType type);

  double radius() const { return radius_; }
  int npieces() const { return npieces_; }
  double edge(int k) const { return edge_[k]; }
  // kernel polynomial w(q) (unnormalised, as Kernel<K,3>::w) from the piece coefficients
  double w_poly(double q) const;

  inline void eval(double q, double &fpot, double &fforce) const
  {
    if (q >= radius_) {
      fpot = -1.0 / q;
      fforce = 1.0 / (q * q);
      return;
    }
    int k = 0;
    while (k < npieces_ - 1 && q >= edge_[k + 1]) k++;
    // Horner in q for sum_n A_n q^n and sum_n A_n q^n/(n+2)
    const double *a = force_[k];
    const double *p = pot_[k];
    double sf = a[deg_], sp = p[deg_];
    for (int n = deg_ - 1; n >= 0; n--) {
      sf = sf * q + a[n];
      sp = sp * q + p[n];
    }
    fforce = sf * q;
    fpot = sp * q * q + E_[k];
    if (C_[k] != 0.0) {
      fforce += C_[k] / (q * q);
      fpot -= C_[k] / q;
    }
  }

 private:
  double radius_ = 2.0;
  int npieces_ = 1, deg_ = 0;
  double edge_[MAXPIECES + 1] = {0.0};
  double w_[MAXPIECES][MAXDEG + 1] = {{0.0}};        // kernel polynomial coefficients
  double force_[MAXPIECES][MAXDEG + 1] = {{0.0}};    // A_n
  double pot_[MAXPIECES][MAXDEG + 1] = {{0.0}};      // A_n / (n+2)
  double C_[MAXPIECES] = {0.0}, E_[MAXPIECES] = {0.0};
};

// the shared instance of a kernel type (built on first use)
const SoftenedKernel &softened_kernel(KernelType type);

// softened potential phi(r,h) and dphi/dr of one particle (run-time kernel choice)
inline void softened(KernelType type, double r, double h, double &phi, double &dphidr)
{
  const double hinv = 1.0 / h;
  double fp, ff;
  if (type == KernelType::CUBIC)
    SoftenedCubic::eval(r * hinv, fp, ff);
  else
    softened_kernel(type).eval(r * hinv, fp, ff);
  phi = fp * hinv;
  dphidr = ff * hinv * hinv;
}

// dphi/dh of one particle at fixed r, for the adaptive-softening ("zeta") terms of
// Price & Monaghan 2007 (sec. 3). From phi = fpot(q)/h with q = r/h and dfpot/dq = fforce:
//   dphi/dh = -fpot(q)/h^2 + fforce(q) (-r/h^2)/h = -[fpot(q) + q fforce(q)] / h^2,
// zero outside the support (fpot = -1/q, fforce = 1/q^2 there) and -fpot(0)/h^2 > 0 at r = 0
// (1.4/h^2 for M4): a wider kernel makes the potential of the particle shallower.
inline double softened_dphidh(KernelType type, double r, double h)
{
  const double hinv = 1.0 / h;
  const double q = r * hinv;
  double fp, ff;
  if (type == KernelType::CUBIC) {
    if (q >= SoftenedCubic::radius) return 0.0;    // exactly zero outside
    SoftenedCubic::eval(q, fp, ff);
  } else {
    const SoftenedKernel &soft = softened_kernel(type);
    if (q >= soft.radius()) return 0.0;
    soft.eval(q, fp, ff);
  }
  return -(fp + q * ff) * hinv * hinv;
}

// radial derivative of the 3D kernel, dW/dr = sigma_3 w'(q) / h^4 (sph_astro_kernel.h), for
// the zeta terms (run-time kernel choice); the Gaussian has no softened potential here
inline double kernel_dwdr3(KernelType type, double r, double h)
{
  const double hinv = 1.0 / h;
  const double q = r * hinv;
  const double h4inv = hinv * hinv * hinv * hinv;
  switch (type) {
    case KernelType::CUBIC:
      return q < KernelCubic::radius ? KernelCubic::sigma(3) * KernelCubic::dw(q) * h4inv : 0.0;
    case KernelType::QUINTIC:
      return q < KernelQuintic::radius ? KernelQuintic::sigma(3) * KernelQuintic::dw(q) * h4inv
                                       : 0.0;
    case KernelType::WENDLAND_C2:
      return q < KernelWendlandC2::radius
          ? KernelWendlandC2::sigma(3) * KernelWendlandC2::dwd<3>(q) * h4inv
          : 0.0;
    case KernelType::WENDLAND_C4:
      return q < KernelWendlandC4::radius
          ? KernelWendlandC4::sigma(3) * KernelWendlandC4::dwd<3>(q) * h4inv
          : 0.0;
    case KernelType::GAUSSIAN:
      break;
  }
  return 0.0;
}

// pair form, symmetric in i and j (Price & Monaghan 2007): the mean of the softened potential
// and force for h_i and h_j, phi_ij = [phi(r,h_i) + phi(r,h_j)]/2, likewise dphi/dr
inline void softened_pair(KernelType type, double r, double hi, double hj, double &phi,
                          double &dphidr)
{
  double pi, fi, pj, fj;
  softened(type, r, hi, pi, fi);
  if (hj == hi) {
    phi = pi;
    dphidr = fi;
    return;
  }
  softened(type, r, hj, pj, fj);
  phi = 0.5 * (pi + pj);
  dphidr = 0.5 * (fi + fj);
}

}    // namespace SPHAstro

#endif
