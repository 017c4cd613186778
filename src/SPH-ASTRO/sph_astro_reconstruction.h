/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Slope-limited linear reconstruction of the velocity for the artificial viscosity

// Plain functions (no LAMMPS), shared by the pair passes and the unit tests.
//
// The viscosity of a pair acts on the velocity jump v_ij. In a smooth flow, v_ij is mostly the
// linear part of the field, grad v . r_ij, which no shock needs damping: in a converging
// inflow (Noh) it heats the cold gas ahead of the shock. Reconstructing both velocities to
// the pair's midpoint before the viscosity sees them removes that part (Frontiere, Raskin &
// Owen 2017, J. Comput. Phys. 332, 160, sect. 2.3; Rosswog 2020, MNRAS 498, 4230, sect. 2.3):
//   v_i^ = v_i - (Phi_ij / 2) (grad v)_i . r_ij,   v_j^ = v_j + (Phi_ij / 2) (grad v)_j . r_ij
//   v_ij^ . r_ij = v_ij . r_ij - (Phi_ij / 2) (s_i + s_j),   s = r_ij . (grad v) . r_ij
// with the van Leer (1974) limiter on the ratio A = s_i / s_j of the two slopes,
//   Phi_ij = max(0, min(1, 4 A / (1 + A)^2)) = 4 s_i s_j / (s_i + s_j)^2 if s_i s_j > 0, else 0
// (the min is never active: 4A <= (1 + A)^2), so the reconstruction fades where the slopes
// differ, as across a shock, and full viscosity acts there. Particles closer than their mean
// spacing Delta get the full viscosity back smoothly (Rosswog 2020's noise trigger, in units
// of the spacing): Phi_ij *= exp(-((r - Delta_ij) / (0.2 h_max))^2) for r < Delta_ij,
// Delta_ij = T (Delta_i + Delta_j)/2, Delta = (m / rho)^(1/d), h_max = max(h_i, h_j), T the
// trigger radius in spacings (1 as Rosswog's; Frontiere et al.'s corresponds to about 2).
//
// Smoothness gate (this package's addition, measured on the Noh implosion, see
// examples/noh/README.md): the kernel-smoothed gradients of two particles inside an SPH shock,
// which is spread over ~3 h, agree, so the van Leer factor alone reconstructs the shock's own
// jump away and cold strong shocks let particles through (post-shock velocity scatter +-0.4 in
// Noh). Where the flow is smooth on the pair's scale, the pair's own jump v_ij . r_ij equals
// the mean slope (s_i + s_j)/2 up to curvature terms; the gate keeps the reconstruction only
// there: Phi_ij *= (4 k / (1 + k)^2)^P, k = 2 v_ij . r_ij / (s_i + s_j) (the same van Leer
// form, so 0 for k <= 0), P = 16 by default: k = 1.2 keeps 0.87, k = 1.5 0.52, k = 2 0.15.
// P = 0 turns the gate off.
//
// grad v is the linearly exact SPH gradient (Price 2012, J. Comput. Phys. 231, 759, sect.
// 2.3.2; Rosswog 2015, MNRAS 448, 3628, eq. 12): with the same weights w_j = m_j dW/dr / r in
//   M = sum_j w_j r_ij r_ij^T,   G = sum_j w_j v_ij r_ij^T,   grad v = G M^-1
// (rows: velocity components, columns: derivatives) a linear field v = v_i + A (x - x_i) gives
// G = A M, so grad v = A to round-off on any particle arrangement with d independent
// neighbours. Only the symmetric part of grad v enters s, so six numbers per particle suffice.

#ifndef LMP_SPH_ASTRO_RECONSTRUCTION_H
#define LMP_SPH_ASTRO_RECONSTRUCTION_H

#include <cmath>

namespace SPHAstro {

// sums per particle: M (xx, yy, zz, xy, xz, yz), then G row-major (G[3 a + k] = sum w v_a r_k)
constexpr int VGRAD_SUMS = 15;
// per-particle reconstruction data: symmetric part of grad v (xx, yy, zz, xy, xz, yz), Delta
constexpr int VGRAD_DATA = 7;

// the pair's contribution to the sums of particle i (and, with the same sign, of j: w, v_ij
// r_ij^T and r_ij r_ij^T do not change when i and j swap)
inline void velocity_gradient_add(double *sums, double w, double dvx, double dvy, double dvz,
                                  double dx, double dy, double dz)
{
  const double wx = w * dx, wy = w * dy, wz = w * dz;
  sums[0] += wx * dx;
  sums[1] += wy * dy;
  sums[2] += wz * dz;
  sums[3] += wx * dy;
  sums[4] += wx * dz;
  sums[5] += wy * dz;
  sums[6] += dvx * wx;
  sums[7] += dvx * wy;
  sums[8] += dvx * wz;
  sums[9] += dvy * wx;
  sums[10] += dvy * wy;
  sums[11] += dvy * wz;
  sums[12] += dvz * wx;
  sums[13] += dvz * wy;
  sums[14] += dvz * wz;
}

// grad v = G M^-1 in DIM dimensions, its symmetric part into sym[6]. Returns false, with
// sym = 0 (no reconstruction: the plain viscosity), when M is singular (fewer than DIM
// independent neighbours, e.g. an isolated particle or a plane of them):
// |det M| < 1e-6 (tr M / DIM)^DIM.
template <int DIM> inline bool velocity_gradient_symmetric(const double *sums, double *sym)
{
  for (int k = 0; k < 6; k++) sym[k] = 0.0;
  const double mxx = sums[0], myy = sums[1], mzz = sums[2], mxy = sums[3], mxz = sums[4],
               myz = sums[5];
  double inv[3][3] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
  if (DIM == 2) {
    const double det = mxx * myy - mxy * mxy;
    const double t = 0.5 * (mxx + myy);
    if (!(std::fabs(det) > 1e-6 * t * t) || !std::isfinite(det)) return false;
    inv[0][0] = myy / det;
    inv[1][1] = mxx / det;
    inv[0][1] = inv[1][0] = -mxy / det;
  } else {
    const double c00 = myy * mzz - myz * myz, c01 = mxz * myz - mxy * mzz,
                 c02 = mxy * myz - mxz * myy;
    const double det = mxx * c00 + mxy * c01 + mxz * c02;
    const double t = (mxx + myy + mzz) / 3.0;
    if (!(std::fabs(det) > 1e-6 * std::fabs(t * t * t)) || !std::isfinite(det)) return false;
    inv[0][0] = c00 / det;
    inv[0][1] = inv[1][0] = c01 / det;
    inv[0][2] = inv[2][0] = c02 / det;
    inv[1][1] = (mxx * mzz - mxz * mxz) / det;
    inv[1][2] = inv[2][1] = (mxy * mxz - mxx * myz) / det;
    inv[2][2] = (mxx * myy - mxy * mxy) / det;
  }
  double grad[3][3];
  for (int a = 0; a < 3; a++)
    for (int l = 0; l < 3; l++) {
      double g = 0.0;
      for (int k = 0; k < DIM; k++) g += sums[6 + 3 * a + k] * inv[k][l];
      grad[a][l] = g;
    }
  sym[0] = grad[0][0];
  sym[1] = grad[1][1];
  sym[2] = grad[2][2];
  sym[3] = 0.5 * (grad[0][1] + grad[1][0]);
  sym[4] = 0.5 * (grad[0][2] + grad[2][0]);
  sym[5] = 0.5 * (grad[1][2] + grad[2][1]);
  return true;
}

// s = r . (grad v) . r from the symmetric part
inline double velocity_slope(const double *sym, double dx, double dy, double dz)
{
  return sym[0] * dx * dx + sym[1] * dy * dy + sym[2] * dz * dz +
      2.0 * (sym[3] * dx * dy + sym[4] * dx * dz + sym[5] * dy * dz);
}

// van Leer limiter of the two slopes: 4 s_i s_j / (s_i + s_j)^2, 0 if they differ in sign
inline double van_leer_limiter(double si, double sj)
{
  const double p = si * sj;
  if (!(p > 0.0)) return 0.0;
  const double s = si + sj;
  return 4.0 * p / (s * s);
}

// x^n for integer n >= 0 by repeated squaring (the gate's exponent; no pow in the pair loop)
inline double integer_power(double x, int n)
{
  double result = 1.0;
  while (n > 0) {
    if (n & 1) result *= x;
    x *= x;
    n >>= 1;
  }
  return result;
}

// v_ij^ . r_ij, the pair's reconstructed approach speed times r (header comment); gate: the
// exponent P of the smoothness gate (0: off)
inline double reconstructed_vdotr(double vdotr, double si, double sj, double r, double delta,
                                  double hmax, int gate = 0)
{
  double phi = van_leer_limiter(si, sj);
  if (gate > 0 && phi > 0.0) phi *= integer_power(van_leer_limiter(0.5 * (si + sj), vdotr), gate);
  if (phi > 0.0 && r < delta) {
    const double e = (r - delta) / (0.2 * hmax);
    phi *= std::exp(-e * e);
  }
  return vdotr - 0.5 * phi * (si + sj);
}

}    // namespace SPHAstro

#endif
