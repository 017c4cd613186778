/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO: the force pass of pair sph/astro (template definitions)
------------------------------------------------------------------------- */

// Included by pair_sph_astro.cpp (pair forms HMEAN and GRADH) and pair_sph_astro_forms.cpp
// (the forms of the options symmetrise kernel and pressure geometric), so that the two
// halves of the instantiations compile in parallel; not a public header.

#ifndef LMP_PAIR_SPH_ASTRO_FORCE_H
#define LMP_PAIR_SPH_ASTRO_FORCE_H

#include "pair_sph_astro.h"

#include "sph_astro_pair_terms.h"
#include "sph_astro_reconstruction.h"

#include "atom.h"
#include "comm.h"
#include "force.h"
#include "neigh_list.h"

#include <cmath>

namespace LAMMPS_NS {
using namespace SPHAstro;

/* ----------------------------------------------------------------------
   force pass: accelerations, du/dt (heating and P dV), div v, over the half list.
   Kernel gradients by FORM: GRADH: grad W(h_i) and grad W(h_j) with the grad-h factors and
   their mean for the dissipative terms; HMEAN: grad W(h_ij), h_ij = (h_i + h_j)/2, for all
   terms; KMEAN: the averaged (grad W(h_i) + grad W(h_j))/2 for all terms (Omega = 1 but
   for GRADH). Pressure term P_i/rho_i^2 + P_j/rho_j^2, or with the geometric forms
   2 sqrt(P_i P_j)/(rho_i rho_j) = 2 g_i g_j, g = sqrt(P)/rho, whose P dV work
   g_i g_j m_j v_ij . grad_i W_ij is summed here pair by pair (seed 000). The dissipative
   terms are those of sph_astro_pair_terms.h. With reconstruction (VISC *_RECONSTRUCT) the
   viscosity sees v_ij^ . r_ij of sph_astro_reconstruction.h instead of v_ij . r_ij; the force
   it gives is the same pair force along r_ij, and its heating 1/2 m_j Pi_ij v_ij . gradbar W
   keeps the true v_ij, so energy is conserved pair by pair as before. It acts only on pairs
   that approach both truly and reconstructed, so that heating is never negative.
   Pressure-energy forms (Hopkins 2013 eqs. 16-18): pressure term
   e_i (e_j - C_i)/P_i dW_i + e_j (e_i - C_j)/P_j dW_j, e = (gamma-1) u, C the grad-h term
   (GRADH_PRESSURE_ENERGY; 0 for HMEAN_PRESSURE_ENERGY, where dW_i = dW_j = dW(h_ij)), and the
   P dV sum sum_j m_j (e_j - C_i) v_ij . grad_i W divided by e_i at the end, so that
   finish_thermal_rates' P_i/rho_i^2 x that sum (no Omega) is
   e_i/P_i sum_j m_j (e_j - C_i) v_ij . grad_i W_ij (rho_i = P_i/e_i).
------------------------------------------------------------------------- */

template <class KERNEL, int DIM, int FORM, bool ENERGY, int VISC, bool COND>
void PairSPHAstro::force_pass()
{
  using K = Kernel<KERNEL, DIM>;
  constexpr bool GH = form_gradh(FORM);
  constexpr bool KM = form_kmean(FORM);
  constexpr bool GEO = form_geometric(FORM);
  constexpr bool PE = form_pressure_energy(FORM);
  double **x = atom->x;
  double **f = atom->f;
  const int *type = atom->type;
  const double *rmass = atom->rmass;
  const double *mass = atom->mass;
  const double *rho = eval_density();
  const double *h = atom->dvector[state_.h];
  double *dudt = atom->dvector[state_.dudt];
  double **vest = atom->darray[state_.vest];
  const double *uest = atom->dvector[state_.uest];
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const int newton_pair = force->newton_pair;
  const int nzero = newton_pair ? nall : nlocal;

  const SPHAstro::NeighView nl = half_view();
  const int inum = nl.inum;
  const int *ilist = nl.ilist;
  const int *numneigh = nl.numneigh;
  int *const *firstneigh = nl.firstneigh;
  const double sigma = K::sigma();
  const double R2 = K::radius * K::radius;
  const double alpha = visc_alpha_, beta = visc_beta_, eps = visc_eps_;
  const double *alpha_atom = alpha_atom_;    // per-atom alpha of a switch, or null
  const double beta_factor = alpha > 0.0 ? beta / alpha : 0.0;
  const double alpha_u = cond_alpha_;
  // geometric forms: sqrt(P)/rho; pressure-energy: e = (gamma-1) u (owned and ghost atoms)
  const double *pgeo = pgeo_;
  double **vgrad = vgrad_;    // reconstruction: symmetric grad v and spacing (owned + ghost)
  const int gate = recon_gate_;

  for (int i = 0; i < nzero; i++) {
    vdotgradw_[i] = 0.0;
    if (ENERGY) dudt[i] = 0.0;
    if (visc_signal(VISC)) vsigmax_[i] = 2.0 * soundspeed_[i];    // at least the pair with itself
    if (COND) condrate_[i] = 0.0;
  }
  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    const double xi = x[i][0], yi = x[i][1], zi = x[i][2];
    const double vxi = vest[i][0], vyi = vest[i][1], vzi = vest[i][2];
    const double hi = h[i];
    const double hinvi = 1.0 / hi;
    const double normi = sigma * inv_h_pow_dim<DIM>(hinvi) * hinvi;
    const double hR2i = R2 * hi * hi;
    const double mi = rmass ? rmass[i] : mass[type[i]];
    const double rhoi = rho[i];
    // P_i/(Omega_i rho_i^2), or g_i = sqrt(P_i)/rho_i for the geometric forms, or e_i / P_i
    const double prhoi = GEO ? pgeo[i]
        : PE                 ? pgeo[i] / pressure_[i]
                             : pressure_[i] / ((GH ? omega_[i] : 1.0) * rhoi * rhoi);
    const double ei = PE ? pgeo[i] : 0.0;
    const double ci_gradh = (PE && GH) ? pe_gradh_[i] : 0.0;    // C_i
    const double ci = soundspeed_[i];
    double fxi = 0.0, fyi = 0.0, fzi = 0.0, vgwi = 0.0, heati = 0.0, vsigi = 0.0, condi = 0.0;
    const int *jlist = firstneigh[i];
    const int jnum = numneigh[i];
    for (int jj = 0; jj < jnum; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      const double dx = xi - x[j][0], dy = yi - x[j][1], dz = zi - x[j][2];
      const double r2 = dx * dx + dy * dy + dz * dz;
      const double hj = h[j];
      const double hij = 0.5 * (hi + hj);
      // (dW/dr)/r for h_i and h_j (GRADH), their mean (KMEAN) or for h_ij:
      // grad_i W_ij(h) = dw * r_ij; grad W(0) = 0
      double dwi, dwj, r;
      if (GH || KM) {
        const double hR2j = R2 * hj * hj;
        if ((r2 >= hR2i && r2 >= hR2j) || r2 == 0.0) continue;
        r = std::sqrt(r2);
        const double rinv = 1.0 / r;
        const double hinvj = 1.0 / hj;
        dwi = r2 < hR2i ? normi * K::dw(r * hinvi) * rinv : 0.0;
        dwj = r2 < hR2j ? sigma * inv_h_pow_dim<DIM>(hinvj) * hinvj * K::dw(r * hinvj) * rinv : 0.0;
        if (KM) dwi = dwj = 0.5 * (dwi + dwj);
      } else {
        if (r2 >= R2 * hij * hij || r2 == 0.0) continue;
        r = std::sqrt(r2);
        const double hinv = 1.0 / hij;
        dwi = dwj = sigma * inv_h_pow_dim<DIM>(hinv) * hinv * K::dw(r * hinv) / r;
      }
      const double dwbar = 0.5 * (dwi + dwj);
      const double mj = rmass ? rmass[j] : mass[type[j]];
      const double rhoj = rho[j];
      const double prhoj = GEO ? pgeo[j]
          : PE                 ? pgeo[j] / pressure_[j]
                               : pressure_[j] / ((GH ? omega_[j] : 1.0) * rhoj * rhoj);
      const double ej = PE ? pgeo[j] : 0.0;
      const double cj_gradh = (PE && GH) ? pe_gradh_[j] : 0.0;    // C_j
      const double dvx = vxi - vest[j][0], dvy = vyi - vest[j][1], dvz = vzi - vest[j][2];
      const double vdotr = dvx * dx + dvy * dy + dvz * dz;
      double visc = 0.0;
      if (visc_signal(VISC)) {
        const double vsig = signal_velocity(vdotr / r, ci, soundspeed_[j], beta);
        vsigi = MAX(vsigi, vsig);
        if (newton_pair || j < nlocal) vsigmax_[j] = MAX(vsigmax_[j], vsig);
      }
      // the approach speed x r the viscosity acts on
      const double vdotr_visc = visc_reconstruct(VISC)
          ? reconstructed_vdotr(vdotr, velocity_slope(vgrad[i], dx, dy, dz),
                                velocity_slope(vgrad[j], dx, dy, dz), r,
                                0.5 * (vgrad[i][6] + vgrad[j][6]), MAX(hi, hj), gate)
          : vdotr;
      // with reconstruction, only pairs that approach in both senses: the heating uses the
      // true v_ij . r_ij, so it stays >= 0 pair by pair
      if (VISC && vdotr_visc < 0.0 && (!visc_reconstruct(VISC) || vdotr < 0.0)) {
        const double a = alpha_atom ? 0.5 * (alpha_atom[i] + alpha_atom[j]) : alpha;
        const double shear = visc_balsara(VISC) ? 0.5 * (balsara_[i] + balsara_[j]) : 1.0;
        if (visc_signal(VISC))
          visc = viscosity_signal(vdotr_visc, r, a, beta, ci, soundspeed_[j], 0.5 * (rhoi + rhoj),
                                  shear);
        else
          visc = viscosity_classic(vdotr_visc, r2, hij, a, alpha_atom ? beta_factor * a : beta, eps,
                                   0.5 * (ci + soundspeed_[j]), 0.5 * (rhoi + rhoj), shear);
      }
      const double pterm = GEO ? pressure_geometric_term(prhoi, prhoj) * dwi
          : PE                 ? (ej - ci_gradh) * prhoi * dwi + (ei - cj_gradh) * prhoj * dwj
                               : prhoi * dwi + prhoj * dwj;
      const double fpair = -mi * mj * (pterm + visc * dwbar);
      fxi += dx * fpair;
      fyi += dy * fpair;
      fzi += dz * fpair;
      // drho_i/dt, -rho_i div v_i; PE: sum_j m_j (e_j - C_i) v_ij . grad W, / e_i below
      vgwi += continuity_rate(PE ? mj * (ej - ci_gradh) : mj, vdotr, dwi);
      // geometric forms: P dV work g_i g_j v_ij . grad W, the same for i and j
      const double pdv = (ENERGY && GEO) ? prhoi * prhoj * vdotr * dwi : 0.0;
      if (ENERGY && GEO) heati += mj * pdv;
      if (ENERGY && VISC) heati += 0.5 * mj * visc * vdotr * dwbar;
      double cond = 0.0;     // conductivity flux times the (mean) dW/dr
      double crate = 0.0;    // its coefficient times |dW/dr|: the diffusion rate of the pair
      if (COND) {
        crate =
            -conductivity_coefficient(alpha_u, pressure_[i], pressure_[j], 0.5 * (rhoi + rhoj)) *
            dwbar * r;
        cond = -crate * (uest[i] - uest[j]);
        heati += mj * cond;
        condi += mj * crate;
      }
      if (newton_pair || j < nlocal) {
        f[j][0] -= dx * fpair;
        f[j][1] -= dy * fpair;
        f[j][2] -= dz * fpair;
        vdotgradw_[j] += continuity_rate(PE ? mi * (ei - cj_gradh) : mi, vdotr, dwj);
        if (ENERGY && GEO) dudt[j] += mi * pdv;
        if (ENERGY && VISC) dudt[j] += 0.5 * mi * visc * vdotr * dwbar;
        if (COND) {
          dudt[j] -= mi * cond;
          condrate_[j] += mi * crate;
        }
      }
      if (evflag) ev_tally(i, j, nlocal, newton_pair, 0.0, 0.0, fpair, dx, dy, dz);
    }
    f[i][0] += fxi;
    f[i][1] += fyi;
    f[i][2] += fzi;
    vdotgradw_[i] += vgwi;
    if (ENERGY) dudt[i] += heati;
    if (visc_signal(VISC)) vsigmax_[i] = MAX(vsigmax_[i], vsigi);
    if (COND) condrate_[i] += condi;
  }
  if (newton_pair) {
    comm_stage_ = Stage::FORCE;
    comm->reverse_comm(this);
  }
  if (PE)
    for (int i = 0; i < nlocal; i++) vdotgradw_[i] /= pgeo[i];
  // (the pressure-energy grad-h terms are in C, not in Omega)
  constexpr bool OMEGA = GH && !PE;
  for (int i = 0; i < nlocal; i++) divv_[i] = -vdotgradw_[i] / ((OMEGA ? omega_[i] : 1.0) * rho[i]);
  if (ENERGY) finish_thermal_rates(OMEGA, GEO);
}

template <class KERNEL, int DIM, int FORM> void PairSPHAstro::dispatch_force()
{
  // only the ideal gas evolves u, so only it has conductivity
  const bool energy = eos_.uses_energy();
  const bool cond = artificial_conductivity();
  int visc = NO_VISCOSITY;
  if (visc_on_ && visc_signal_)
    visc = balsara_on_ ? SIGNAL_BALSARA : (recon_on_ ? SIGNAL_RECONSTRUCT : SIGNAL);
  else if (visc_on_)
    visc = balsara_on_ ? BALSARA : (recon_on_ ? CLASSIC_RECONSTRUCT : CLASSIC);
#define SPH_ASTRO_FORCE(E, V, C)              \
  {                                           \
    force_pass<KERNEL, DIM, FORM, E, V, C>(); \
    return;                                   \
  }
#define SPH_ASTRO_FORCE_VISC(E, C)                                               \
  {                                                                              \
    if (visc == SIGNAL_BALSARA) SPH_ASTRO_FORCE(E, SIGNAL_BALSARA, C);           \
    if (visc == SIGNAL_RECONSTRUCT) SPH_ASTRO_FORCE(E, SIGNAL_RECONSTRUCT, C);   \
    if (visc == CLASSIC_RECONSTRUCT) SPH_ASTRO_FORCE(E, CLASSIC_RECONSTRUCT, C); \
    if (visc == SIGNAL) SPH_ASTRO_FORCE(E, SIGNAL, C);                           \
    if (visc == BALSARA) SPH_ASTRO_FORCE(E, BALSARA, C);                         \
    if (visc == CLASSIC) SPH_ASTRO_FORCE(E, CLASSIC, C);                         \
    SPH_ASTRO_FORCE(E, NO_VISCOSITY, C);                                         \
  }
  if (cond) SPH_ASTRO_FORCE_VISC(true, true);
  // pressure-energy always evolves u (init_style asks for eos ideal)
  if constexpr (form_pressure_energy(FORM)) {
    SPH_ASTRO_FORCE_VISC(true, false);
  } else {
    if (energy) SPH_ASTRO_FORCE_VISC(true, false);
    SPH_ASTRO_FORCE_VISC(false, false);
  }
#undef SPH_ASTRO_FORCE_VISC
#undef SPH_ASTRO_FORCE
}

// explicit instantiations of dispatch_force for the forms other than HMEAN and GRADH live in
// pair_sph_astro_forms.cpp
#define SPH_ASTRO_FORMS_OF_KERNEL(PREFIX, KT)                                                \
  PREFIX template void PairSPHAstro::dispatch_force<SPHAstro::KT, 2, PairSPHAstro::KMEAN>(); \
  PREFIX template void PairSPHAstro::dispatch_force<SPHAstro::KT, 3, PairSPHAstro::KMEAN>(); \
  PREFIX template void                                                                       \
  PairSPHAstro::dispatch_force<SPHAstro::KT, 2, PairSPHAstro::HMEAN_GEOMETRIC>();            \
  PREFIX template void                                                                       \
  PairSPHAstro::dispatch_force<SPHAstro::KT, 3, PairSPHAstro::HMEAN_GEOMETRIC>();            \
  PREFIX template void                                                                       \
  PairSPHAstro::dispatch_force<SPHAstro::KT, 2, PairSPHAstro::KMEAN_GEOMETRIC>();            \
  PREFIX template void                                                                       \
  PairSPHAstro::dispatch_force<SPHAstro::KT, 3, PairSPHAstro::KMEAN_GEOMETRIC>();            \
  PREFIX template void                                                                       \
  PairSPHAstro::dispatch_force<SPHAstro::KT, 2, PairSPHAstro::HMEAN_PRESSURE_ENERGY>();      \
  PREFIX template void                                                                       \
  PairSPHAstro::dispatch_force<SPHAstro::KT, 3, PairSPHAstro::HMEAN_PRESSURE_ENERGY>();      \
  PREFIX template void                                                                       \
  PairSPHAstro::dispatch_force<SPHAstro::KT, 2, PairSPHAstro::GRADH_PRESSURE_ENERGY>();      \
  PREFIX template void                                                                       \
  PairSPHAstro::dispatch_force<SPHAstro::KT, 3, PairSPHAstro::GRADH_PRESSURE_ENERGY>();
#define SPH_ASTRO_OPTION_FORMS(PREFIX)                \
  SPH_ASTRO_FORMS_OF_KERNEL(PREFIX, KernelCubic)      \
  SPH_ASTRO_FORMS_OF_KERNEL(PREFIX, KernelQuintic)    \
  SPH_ASTRO_FORMS_OF_KERNEL(PREFIX, KernelWendlandC2) \
  SPH_ASTRO_FORMS_OF_KERNEL(PREFIX, KernelWendlandC4) \
  SPH_ASTRO_FORMS_OF_KERNEL(PREFIX, KernelGaussian)

}    // namespace LAMMPS_NS

#endif
