/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: astrophysical smoothed particle hydrodynamics for LAMMPS
------------------------------------------------------------------------- */

// Smoothing kernels W(r,h) = sigma_d / h^d * w(q), q = r/h, with compact support
// q < kernel_radius (h is the smoothing length; the support is kernel_radius * h).
//
//   cubic spline M4  (Monaghan & Lattanzio 1985, A&A 149, 135; Monaghan 1992), support 2h
//   quintic spline M6 (Price 2012, J. Comput. Phys. 231, 759, eq. 11), support 3h
//   Wendland C2, C4  (Dehnen & Aly 2012, MNRAS 425, 1068, table 1), support 2h
//   Gaussian         (Gingold & Monaghan 1977, MNRAS 181, 375),
//                    truncated at q = 3 and shifted to zero there, support 3h
//
// Each kernel is a struct of static inline functions of q only so that the pair loops can
// be instantiated per kernel without branches; sigma(dim) is the normalisation in 1, 2, 3D.

#ifndef LMP_SPH_ASTRO_KERNEL_H
#define LMP_SPH_ASTRO_KERNEL_H

#include <cmath>

namespace SPHAstro {

enum class KernelType { CUBIC, QUINTIC, WENDLAND_C2, WENDLAND_C4, GAUSSIAN };

struct KernelCubic {
  static constexpr double radius = 2.0;
  static constexpr const char *name = "m4";
  static double sigma(int dim)
  {
    return dim == 1 ? 2.0 / 3.0 : (dim == 2 ? 10.0 / (7.0 * M_PI) : 1.0 / M_PI);
  }
  // w(q) and w'(q) = dw/dq
  static inline double w(double q)
  {
    if (q < 1.0) return 1.0 - 1.5 * q * q + 0.75 * q * q * q;
    if (q < 2.0) {
      const double t = 2.0 - q;
      return 0.25 * t * t * t;
    }
    return 0.0;
  }
  static inline double dw(double q)
  {
    if (q < 1.0) return q * (-3.0 + 2.25 * q);
    if (q < 2.0) {
      const double t = 2.0 - q;
      return -0.75 * t * t;
    }
    return 0.0;
  }
};

struct KernelQuintic {
  static constexpr double radius = 3.0;
  static constexpr const char *name = "m6";
  static double sigma(int dim)
  {
    return dim == 1 ? 1.0 / 120.0 : (dim == 2 ? 7.0 / (478.0 * M_PI) : 1.0 / (120.0 * M_PI));
  }
  static inline double p5(double t) { return t * t * t * t * t; }
  static inline double p4(double t) { return t * t * t * t; }
  static inline double w(double q)
  {
    if (q >= 3.0) return 0.0;
    double s = p5(3.0 - q);
    if (q < 2.0) s -= 6.0 * p5(2.0 - q);
    if (q < 1.0) s += 15.0 * p5(1.0 - q);
    return s;
  }
  static inline double dw(double q)
  {
    if (q >= 3.0) return 0.0;
    double s = -5.0 * p4(3.0 - q);
    if (q < 2.0) s += 30.0 * p4(2.0 - q);
    if (q < 1.0) s -= 75.0 * p4(1.0 - q);
    return s;
  }
};

// Wendland functions are dimension dependent: psi_{3,1} (C2) and psi_{3,2} (C4) in 2D/3D,
// psi_{2,1} and psi_{2,2} in 1D. With support H = 2h and s = q/2 (Dehnen & Aly 2012, table 1):
//   C2, 2D/3D: (1-s)^4 (1+4s), sigma = 7/(pi H^2), 21/(2 pi H^3);   1D: (1-s)^3 (1+3s), 5/(4H)
//   C4, 2D/3D: (1-s)^6 (1+6s+35/3 s^2), sigma = 9/(pi H^2), 495/(32 pi H^3);
//       1D: (1-s)^5 (1+5s+8s^2), 3/(2H)
// The 1D forms are selected by the dimension template argument of w1/dw1 below.
struct KernelWendlandC2 {
  static constexpr double radius = 2.0;
  static constexpr const char *name = "wendland/c2";
  static double sigma(int dim)
  {
    return dim == 1 ? 5.0 / 8.0 : (dim == 2 ? 7.0 / (4.0 * M_PI) : 21.0 / (16.0 * M_PI));
  }
  template <int DIM> static inline double wd(double q)
  {
    if (q >= 2.0) return 0.0;
    const double t = 1.0 - 0.5 * q;
    if (DIM == 1) return t * t * t * (1.0 + 1.5 * q);
    return t * t * t * t * (1.0 + 2.0 * q);
  }
  template <int DIM> static inline double dwd(double q)
  {
    if (q >= 2.0) return 0.0;
    const double t = 1.0 - 0.5 * q;
    if (DIM == 1) return -3.0 * q * t * t;    // d/dq[(1-q/2)^3 (1+3q/2)]
    return -5.0 * q * t * t * t;              // d/dq[(1-q/2)^4 (1+2q)]
  }
};

struct KernelWendlandC4 {
  static constexpr double radius = 2.0;
  static constexpr const char *name = "wendland/c4";
  static double sigma(int dim)
  {
    return dim == 1 ? 3.0 / 4.0 : (dim == 2 ? 9.0 / (4.0 * M_PI) : 495.0 / (256.0 * M_PI));
  }
  template <int DIM> static inline double wd(double q)
  {
    if (q >= 2.0) return 0.0;
    const double s = 0.5 * q;
    const double t = 1.0 - s;
    const double t2 = t * t;
    if (DIM == 1) return t2 * t2 * t * (1.0 + 5.0 * s + 8.0 * s * s);
    return t2 * t2 * t2 * (1.0 + 6.0 * s + (35.0 / 3.0) * s * s);
  }
  template <int DIM> static inline double dwd(double q)
  {
    if (q >= 2.0) return 0.0;
    const double s = 0.5 * q;
    const double t = 1.0 - s;
    const double t2 = t * t;
    // d/dq = 0.5 d/ds; d/ds[(1-s)^5 (1+5s+8s^2)] = -14 s (1-s)^4 (1+4s)
    if (DIM == 1) return -7.0 * s * t2 * t2 * (1.0 + 4.0 * s);
    // d/ds[(1-s)^6 (1+6s+35/3 s^2)] = -56/3 s (1-s)^5 (1+5s)
    return -(28.0 / 3.0) * s * t2 * t2 * t * (1.0 + 5.0 * s);
  }
};

// Gaussian kernel of Gingold & Monaghan 1977, W = (1/(h sqrt(pi)))^d exp(-q^2), truncated at q = 3
// (support 3h) so that it fits neighbour lists. Truncation and shift:
//   w(q) = exp(-q^2) - exp(-9)  for q < 3,  0 otherwise
// The shift makes W continuous at the support edge (W(3h) = 0), so the density and the thermal
// energy do not jump when a neighbour crosses 3h. The slope is not shifted: w'(3-) = -6 exp(-9)
// = -7.4e-4, 0.09 % of the largest |w'| (sqrt(2/e) = 0.858 at q = 1/sqrt(2)); a force term
// that makes w'(3) = 0 as well (w - (q-3) w'(3)) would give w'(0) != 0, a cusp at the origin of
// the same size, so the small jump of the gradient at the edge is accepted instead.
// Normalisation: sigma_d = 1 / integral over |q| < 3 of w(q) d^d q, evaluated exactly:
//   1D: sqrt(pi) erf(3) - 6 e^-9
//   2D: pi (1 - e^-9) - 9 pi e^-9 = pi (1 - 10 e^-9)
//   3D: 4 pi int_0^3 q^2 e^-q^2 dq - (4/3) pi 27 e^-9 = pi^(3/2) erf(3) - 6 pi e^-9 - 36 pi e^-9
// (the untruncated values are pi^(-d/2); these are larger by 0.04 %, 0.12 % and
// 0.30 % in 1D, 2D and 3D).
struct KernelGaussian {
  static constexpr double radius = 3.0;
  static constexpr const char *name = "gaussian";
  static double sigma(int dim)
  {
    const double e9 = std::exp(-9.0);
    if (dim == 1) return 1.0 / (std::sqrt(M_PI) * std::erf(3.0) - 6.0 * e9);
    if (dim == 2) return 1.0 / (M_PI * (1.0 - 10.0 * e9));
    return 1.0 / (M_PI * std::sqrt(M_PI) * std::erf(3.0) - 42.0 * M_PI * e9);
  }
  static inline double w(double q)
  {
    if (q >= 3.0) return 0.0;
    return std::exp(-q * q) - 1.2340980408667956e-4;    // e^-9
  }
  static inline double dw(double q)
  {
    if (q >= 3.0) return 0.0;
    return -2.0 * q * std::exp(-q * q);
  }
};

// Uniform interface for the pair loops: Kernel<K, DIM>::w(q), ::dw(q), with the
// dimension-independent splines forwarding to their one-argument forms.
template <class K, int DIM> struct Kernel {
  static constexpr double radius = K::radius;
  static inline double w(double q) { return K::w(q); }
  static inline double dw(double q) { return K::dw(q); }
  static double sigma() { return K::sigma(DIM); }
};
template <int DIM> struct Kernel<KernelWendlandC2, DIM> {
  static constexpr double radius = KernelWendlandC2::radius;
  static inline double w(double q) { return KernelWendlandC2::wd<DIM>(q); }
  static inline double dw(double q) { return KernelWendlandC2::dwd<DIM>(q); }
  static double sigma() { return KernelWendlandC2::sigma(DIM); }
};
template <int DIM> struct Kernel<KernelWendlandC4, DIM> {
  static constexpr double radius = KernelWendlandC4::radius;
  static inline double w(double q) { return KernelWendlandC4::wd<DIM>(q); }
  static inline double dw(double q) { return KernelWendlandC4::dwd<DIM>(q); }
  static double sigma() { return KernelWendlandC4::sigma(DIM); }
};

// 1/h^d for the kernel normalisation without pow()
template <int DIM> static inline double inv_h_pow_dim(double hinv)
{
  return DIM == 1 ? hinv : (DIM == 2 ? hinv * hinv : hinv * hinv * hinv);
}

// Full kernel and radial derivative for tests and tools (not used in the hot loops):
// W(r,h) and dW/dr for a kernel type and dimension chosen at run time.
double kernel_W(KernelType type, int dim, double r, double h);
double kernel_dWdr(KernelType type, int dim, double r, double h);
double kernel_radius(KernelType type);
const char *kernel_name(KernelType type);
bool kernel_from_name(const char *name, KernelType &type);

}    // namespace SPHAstro

#endif
