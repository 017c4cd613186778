/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The interaction functions of one pair (sph_astro_iact.h), the code the pair loops call,
// without LAMMPS. In the manner of SWIFT's testSymmetry.c: for every combination of options
// the pair seen from i and seen from j gives equal and opposite forces, the same heating and
// rates to each partner, and the pair conserves total energy: the work of its force on the
// two velocities is what the two du/dt take.

#include "sph_astro_iact.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

using namespace SPHAstro;

namespace {

struct Pair {
  ForceParticle i, j;
  double vgrad_i[VGRAD_DATA], vgrad_j[VGRAD_DATA];
  double dx, dy, dz;
  PairGradient g;
};

// a random pair inside the support, approaching (so the viscosity acts) or not
Pair random_pair(std::mt19937 &gen, bool approaching, PressureForm form)
{
  std::uniform_real_distribution<double> u(0.2, 1.5), s(-1.0, 1.0);
  Pair p;
  for (ForceParticle *q : {&p.i, &p.j}) {
    q->m = u(gen);
    q->rho = u(gen);
    q->P = u(gen);
    q->c = u(gen);
    q->h = 0.5 * u(gen) + 0.5;
    const double e = u(gen);
    q->C = form == PressureForm::PRESSURE_ENERGY ? 0.1 * s(gen) : 0.0;
    q->alpha = u(gen);
    q->shear = 0.5 * u(gen);
    q->u = u(gen);
    q->vx = s(gen);
    q->vy = s(gen);
    q->vz = s(gen);
    // the per-particle factor of each pressure form: P/(Omega rho^2), sqrt(P)/rho, e/P
    const double omega = 0.8 + 0.3 * u(gen);
    q->prho = form == PressureForm::GEOMETRIC   ? pressure_geometric_factor(q->P, q->rho)
        : form == PressureForm::PRESSURE_ENERGY ? e / q->P
                                                : q->P / (omega * q->rho * q->rho);
    q->b = form == PressureForm::GEOMETRIC      ? q->prho
        : form == PressureForm::PRESSURE_ENERGY ? e
                                                : 1.0;
    q->w = form == PressureForm::PRESSURE_ENERGY ? e : 1.0;
  }
  for (int k = 0; k < VGRAD_DATA; k++) {
    p.vgrad_i[k] = s(gen);
    p.vgrad_j[k] = s(gen);
  }
  p.vgrad_i[6] = p.vgrad_j[6] = 0.3 * u(gen);    // spacings
  p.i.vgrad = p.vgrad_i;
  p.j.vgrad = p.vgrad_j;
  p.dx = s(gen);
  p.dy = s(gen);
  p.dz = s(gen);
  const double vdotr =
      (p.i.vx - p.j.vx) * p.dx + (p.i.vy - p.j.vy) * p.dy + (p.i.vz - p.j.vz) * p.dz;
  if ((vdotr < 0.0) != approaching)
    std::swap(p.i.vx, p.j.vx), std::swap(p.i.vy, p.j.vy), std::swap(p.i.vz, p.j.vz);
  p.g.r2 = p.dx * p.dx + p.dy * p.dy + p.dz * p.dz;
  p.g.r = std::sqrt(p.g.r2);
  p.g.dwi = -u(gen);    // (dW/dr)/r < 0
  p.g.dwj = -u(gen);
  return p;
}

// du/dt of a particle from one pair: P dV term (prho x the weighted v.gradW sum) + heating;
// with pressure geometric the P dV work is in the heating already
double dudt_of(const ForceSettings &s, const ForceParticle &q, double vgw, double heat)
{
  return s.pressure == PressureForm::GEOMETRIC ? heat : q.prho * vgw + heat;
}

std::string describe(const ForceSettings &s)
{
  const char *forms[] = {"standard", "geometric", "pressure-energy"};
  return std::string(forms[static_cast<int>(s.pressure)]) + (s.viscosity ? " visc" : "") +
      (s.signal ? " signal" : "") + (s.reconstruct ? " reconstruct" : "") +
      (s.balsara ? " balsara" : "") + (s.alpha_per_particle ? " switch" : "") +
      (s.energy ? " energy" : "") + (s.alpha_u > 0.0 ? " conductivity" : "") +
      (s.gradh ? " gradh" : "");
}

// every combination of the force options
template <class F> void for_every_option(F &&f)
{
  for (PressureForm form :
       {PressureForm::STANDARD, PressureForm::GEOMETRIC, PressureForm::PRESSURE_ENERGY})
    for (int visc = 0; visc < 3; visc++)
      for (int limiter = 0; limiter < 3; limiter++)    // none, Balsara, reconstruction
        for (bool per_particle : {false, true})
          for (bool energy : {false, true})
            for (bool cond : {false, true})
              for (bool gradh : {false, true}) {
                if (visc == 0 && (limiter || per_particle)) continue;
                if (cond && !energy) continue;    // conductivity only where u evolves
                // the geometric mean needs one kernel gradient (mean h or averaged kernel)
                if (form == PressureForm::GEOMETRIC && gradh) continue;
                ForceSettings s;
                s.pressure = form;
                s.viscosity = visc > 0;
                s.signal = visc == 2;
                s.balsara = limiter == 1;
                s.reconstruct = limiter == 2;
                s.alpha_per_particle = per_particle;
                s.alpha = 0.8;
                s.beta = s.signal ? 3.0 : 1.6;
                s.beta_factor = 2.0;
                s.epsilon = 0.01;
                s.gate = 16;
                s.energy = energy;
                s.alpha_u = cond ? 0.7 : 0.0;
                s.gradh = gradh;
                f(s);
              }
}

}    // namespace

TEST(PairInteraction, SymmetricAndConservativeForEveryOptionCombination)
{
  std::mt19937 gen(2013);
  int combinations = 0;
  double worst_symmetry = 0.0, worst_energy = 0.0;
  for_every_option([&](const ForceSettings &s) {
    combinations++;
    for (int trial = 0; trial < 40; trial++) {
      Pair p = random_pair(gen, trial % 4 != 0, s.pressure);
      if (!s.gradh) {    // mean h or the averaged kernel: one gradient, no grad-h term C
        p.g.dwj = p.g.dwi;
        p.i.C = p.j.C = 0.0;
      }
      ForceContribution ij, ji;
      iact_force(s, p.i, p.j, p.dx, p.dy, p.dz, p.g, ij);
      PairGradient gji = p.g;    // seen from j: r_ji = -r_ij, the two kernels swap
      std::swap(gji.dwi, gji.dwj);
      iact_force(s, p.j, p.i, -p.dx, -p.dy, -p.dz, gji, ji);

      // forces: r_ij fpair on i, r_ji fpair' on j, equal and opposite
      const double scale = std::fabs(ij.fpair) + 1e-300;
      const double d_force = std::fabs(ij.fpair - ji.fpair) / scale;
      EXPECT_LT(d_force, 1e-13) << describe(s);
      // each partner's sums are the same from either side
      for (auto [a, b] : {std::pair<double, double>{ij.vgw_i, ji.vgw_j},
                          {ij.vgw_j, ji.vgw_i},
                          {ij.heat_i, ji.heat_j},
                          {ij.heat_j, ji.heat_i},
                          {ij.crate_i, ji.crate_j},
                          {ij.crate_j, ji.crate_i},
                          {ij.vsig, ji.vsig}}) {
        const double d = std::fabs(a - b) / (std::fabs(a) + std::fabs(b) + 1e-300);
        EXPECT_LT(d, 1e-13) << describe(s);
        worst_symmetry = std::max(worst_symmetry, std::max(d, d_force));
      }
      // energy: m_i du_i + m_j du_j + (v_i - v_j) . r_ij fpair = 0
      if (!s.energy) continue;
      const double vdotr =
          (p.i.vx - p.j.vx) * p.dx + (p.i.vy - p.j.vy) * p.dy + (p.i.vz - p.j.vz) * p.dz;
      const double thermal = p.i.m * dudt_of(s, p.i, ij.vgw_i, ij.heat_i) +
          p.j.m * dudt_of(s, p.j, ij.vgw_j, ij.heat_j);
      const double work = vdotr * ij.fpair;
      const double e = std::fabs(thermal + work) / (std::fabs(thermal) + std::fabs(work) + 1e-300);
      EXPECT_LT(e, 1e-13) << describe(s) << ": thermal " << thermal << " work " << work;
      worst_energy = std::max(worst_energy, e);
    }
  });
  printf("%d option combinations: largest relative asymmetry %.2e, energy imbalance %.2e\n",
         combinations, worst_symmetry, worst_energy);
  EXPECT_EQ(combinations, 195);    // the loop reached every combination it lists
}

// the viscosity heats, never cools: sum m du from the dissipative terms >= 0 for each pair
// (with reconstruction only pairs that approach truly and reconstructed get viscosity)
TEST(PairInteraction, ViscousHeatingIsNeverNegative)
{
  std::mt19937 gen(1997);
  for_every_option([&](const ForceSettings &s) {
    if (!s.energy || s.pressure == PressureForm::GEOMETRIC || s.alpha_u > 0.0) return;
    for (int trial = 0; trial < 40; trial++) {
      Pair p = random_pair(gen, trial % 2 == 0, s.pressure);
      if (!s.gradh) p.g.dwj = p.g.dwi;
      ForceContribution c;
      iact_force(s, p.i, p.j, p.dx, p.dy, p.dz, p.g, c);
      EXPECT_GE(p.i.m * c.heat_i + p.j.m * c.heat_j, 0.0) << describe(s);
    }
  });
}

// pressure geometric: the force is 2 g_i g_j m_i m_j dW r_ij and both partners take the P dV
// work g_i g_j v_ij . grad W, so the pair conserves energy
TEST(PairInteraction, GeometricPressureTermAndWork)
{
  ForceSettings s;
  s.pressure = PressureForm::GEOMETRIC;
  s.viscosity = false;
  std::mt19937 gen(1989);
  Pair p = random_pair(gen, true, s.pressure);
  p.g.dwj = p.g.dwi;
  ForceContribution c;
  iact_force(s, p.i, p.j, p.dx, p.dy, p.dz, p.g, c);
  // 2 sqrt(P_i P_j)/(rho_i rho_j) in place of P_i/rho_i^2 + P_j/rho_j^2
  const double geo = 2.0 * std::sqrt(p.i.P * p.j.P) / (p.i.rho * p.j.rho);
  EXPECT_NEAR(c.fpair, -p.i.m * p.j.m * geo * p.g.dwi, 1e-13);
  // below the standard term where P/rho^2 differ (arithmetic-geometric mean)
  ForceSettings st = s;
  st.pressure = PressureForm::STANDARD;
  Pair q = p;
  for (ForceParticle *x : {&q.i, &q.j}) {
    x->prho = x->P / (x->rho * x->rho);
    x->b = 1.0;
  }
  ForceContribution cs;
  iact_force(st, q.i, q.j, q.dx, q.dy, q.dz, q.g, cs);
  EXPECT_LT(std::fabs(c.fpair), std::fabs(cs.fpair));
  const double vdotr =
      (p.i.vx - p.j.vx) * p.dx + (p.i.vy - p.j.vy) * p.dy + (p.i.vz - p.j.vz) * p.dz;
  EXPECT_NEAR(c.heat_i, p.j.m * p.i.prho * p.j.prho * vdotr * p.g.dwi, 1e-14);
  EXPECT_NEAR(p.i.m * c.heat_i + p.j.m * c.heat_j, -vdotr * c.fpair, 1e-14);
}

// the kernel of a pair: mean h gives one gradient at h_ij; two h gives W(h_i) and W(h_j),
// the averaged kernel their mean; outside every support and at r = 0 nothing
TEST(PairInteraction, PairKernelForms)
{
  const PairKernel<KernelCubic, 3> kern;
  const double hi = 0.5, hj = 0.8, r = 0.9;
  const KernelSide ki(hi, kern.R2);
  PairGradient g;
  ASSERT_TRUE((pair_kernel_gradient<KernelCubic, 3, false>(kern, ki, hj, r * r, false, g)));
  EXPECT_NEAR(g.dwi, kernel_dWdr(KernelType::CUBIC, 3, r, 0.5 * (hi + hj)) / r, 1e-13);
  EXPECT_EQ(g.dwi, g.dwj);
  ASSERT_TRUE((pair_kernel_gradient<KernelCubic, 3, true>(kern, ki, hj, r * r, false, g)));
  EXPECT_NEAR(g.dwi, kernel_dWdr(KernelType::CUBIC, 3, r, hi) / r, 1e-13);
  EXPECT_NEAR(g.dwj, kernel_dWdr(KernelType::CUBIC, 3, r, hj) / r, 1e-13);
  const double mean = g.mean();
  ASSERT_TRUE((pair_kernel_gradient<KernelCubic, 3, true>(kern, ki, hj, r * r, true, g)));
  EXPECT_DOUBLE_EQ(g.dwi, mean);
  EXPECT_DOUBLE_EQ(g.dwj, mean);
  double w;
  ASSERT_TRUE((pair_kernel_value<KernelCubic, 3, true>(kern, ki, hj, r * r, w)));
  EXPECT_NEAR(w,
              0.5 * (kernel_W(KernelType::CUBIC, 3, r, hi) + kernel_W(KernelType::CUBIC, 3, r, hj)),
              1e-13);
  // r = 1.7: outside 2 h_ij = 1.3 and both supports 2 h_i = 1.0, 2 h_j = 1.6
  EXPECT_FALSE((pair_kernel_gradient<KernelCubic, 3, false>(kern, ki, hj, 1.7 * 1.7, false, g)));
  EXPECT_FALSE((pair_kernel_gradient<KernelCubic, 3, true>(kern, ki, hj, 1.7 * 1.7, false, g)));
  // r = 1.5: outside 2 h_ij = 1.3, inside 2 h_j = 1.6 (two h only)
  EXPECT_FALSE((pair_kernel_gradient<KernelCubic, 3, false>(kern, ki, hj, 1.5 * 1.5, false, g)));
  EXPECT_TRUE((pair_kernel_gradient<KernelCubic, 3, true>(kern, ki, hj, 1.5 * 1.5, false, g)));
  EXPECT_EQ(g.dwi, 0.0);
  EXPECT_LT(g.dwj, 0.0);
  EXPECT_FALSE((pair_kernel_gradient<KernelCubic, 3, true>(kern, ki, hj, 0.0, false, g)));
}

// density pair term: m_j W to i, m_i W to j; the h-rho sums' dW/dh term
TEST(PairInteraction, DensityTerms)
{
  const DensityContribution c = iact_density(0.3, 0.7, 2.0);
  EXPECT_DOUBLE_EQ(c.to_i, 1.4);
  EXPECT_DOUBLE_EQ(c.to_j, 0.6);
  // sum_j m_j dW/dh h^(d+1)/sigma = -sum_j m_j (d w + q w'): compare with a finite difference
  const double h = 0.9, r = 1.1, m = 0.4;
  GradhSums sums;
  const double q = r / h;
  sums.add(m, KernelCubic::w(q), KernelCubic::dw(q), q, 3);
  const double sigma = KernelCubic::sigma(3);
  const double dwdh = sigma / std::pow(h, 4) * sums.dwdh / m;
  const double eps = 1e-6;
  const double fd =
      (kernel_W(KernelType::CUBIC, 3, r, h + eps) - kernel_W(KernelType::CUBIC, 3, r, h - eps)) /
      (2 * eps);
  EXPECT_NEAR(dwdh, fd, 1e-7);
}
