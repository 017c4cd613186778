/* ----------------------------------------------------------------------
   SPH-ASTRO: astrophysical smoothed particle hydrodynamics for LAMMPS
------------------------------------------------------------------------- */

// Pair style sph/astro: density summation, equation of state, pressure force, classic
// artificial viscosity and the matching energy equation. Symmetrisation by the mean
// smoothing length h_ij = (h_i + h_j)/2 (seed 000, "some notation").
//
// pass 1  rho_i = sum_j m_j W(r_ij, h_ij)                                  (seed 000, density)
// pass 2  dv_i/dt = -sum_j m_j (P_i/rho_i^2 + P_j/rho_j^2 + Pi_ij) grad_i W_ij  (seed 000)
//         du_i/dt = P_i/rho_i^2 sum_j m_j v_ij . grad_i W_ij
//                   + 1/2 sum_j m_j Pi_ij v_ij . grad_i W_ij        (seed 000; seed 004 eq. 48)
//         Pi_ij = (-alpha c_ij mu_ij + beta mu_ij^2) / rho_ij  for v_ij . r_ij < 0, else 0
//         mu_ij = h_ij v_ij . r_ij / (r_ij^2 + eps h_ij^2), eps = 0.01    (Monaghan 1992; seed 000)
//         div v_i = -1/rho_i sum_j m_j v_ij . grad_i W_ij               (seed 004 eq. 33 form)
// Total energy sum_i m_i (v_i^2/2 + u_i) is conserved by these pair terms up to time
// integration error (seed 004 sec. 9.5.3). Velocities in pass 2 are the predicted ones
// (d2_vest) written by fix sph/astro, so the viscosity sees v at the end of the step.
//
// Options for fixed h and dh/dt (keywords density, symmetrise, pressure):
//   density continuity  pass 1 is skipped: rho is integrated by fix sph/astro with
//                       drho_i/dt = sum_j m_j v_ij . grad_i W_ij           (seed 004 eq. 33)
//                       (after one summation at the first force evaluation)
//   symmetrise kernel   W_ij = (W(r_ij, h_i) + W(r_ij, h_j))/2 and its gradient in every term
//                       (seed 000, "alternative ways to force anti-symmetry")
//   pressure geometric  dv_i/dt = -sum_j m_j (2 sqrt(P_i P_j)/(rho_i rho_j) + Pi_ij) grad_i W_ij
//                       du_i/dt = sum_j m_j sqrt(P_i P_j)/(rho_i rho_j) v_ij . grad_i W_ij + visc.
//                       (seed 000 ibid.; the energy equation in the form of the force, as
//                       seed 004 eqs. 41-42 pair with eqs. 23 and 26)
// Keyword formulation pressure-energy (Saitoh & Makino 2013, ApJ 768, 44, "density-independent
// SPH"; Hopkins 2013, MNRAS 428, 2840, eqs. 16-18; f_ij = 1 with fixed h or dh/dt):
//   pass 1  P_i = (gamma-1) sum_j m_j u_j W_ij,  rho_i = P_i / ((gamma-1) u_i)  (u_i > 0)
//   pass 2  dv_i/dt = -sum_j m_j [(gamma-1)^2 u_i u_j (1/P_i + 1/P_j) + Pi_ij] grad_i W_ij
//           du_i/dt = (gamma-1)^2 u_i / P_i sum_j m_j u_j v_ij . grad_i W_ij + visc.
//           div v_i = -1/rho_i sum_j m_j (u_j/u_i) v_ij . grad_i W_ij
//   With uniform u these are the standard equations; across a contact in pressure balance P is
//   smooth and rho jumps with u from one particle to the next (no pressure blip). Pair by pair
//   the two P dV terms and the force's work cancel, so energy is conserved as before.
//   With fix sph/astro/h iterate, h_i = hfact (m_i/rho^m_i)^(1/d) with the mass density
//   rho^m_i = sum_j m_j W_ij(h_i) as without this keyword, and the kernels W(h_i), W(h_j):
//     (gamma-1)^2 u_i u_j (1/P_i + 1/P_j) grad W -> e_i (e_j - C_i)/P_i grad_i W(h_i)
//                                                 + e_j (e_i - C_j)/P_j grad_i W(h_j)
//     du_i/dt = e_i/P_i sum_j m_j (e_j - C_i) v_ij . grad_i W_ij(h_i) + visc.,  e = (gamma-1) u
//   C_i = h_i (dP_i/dh_i) / (d rho^m_i Omega_i) (0 at the h cap): from dP_i/dt with dh_i/dt
//   = -h_i/(d rho^m_i Omega_i) drho^m_i/dt (Hopkins' f_ij with the mass-density h of this
//   package: e_j f_ij = e_j - C_i); the work of the forces is again minus the P dV terms.
// Keyword reconstruct: the viscosity (only) sees v_ij . r_ij of the velocities reconstructed
// to the pair midpoint with the linearly exact grad v, a van Leer limiter, a noise trigger and
// a smoothness gate (sph_astro_reconstruction.h); the energy equation keeps the true v_ij, so
// the pair still conserves energy.

#include "pair_sph_astro.h"
#include "pair_sph_astro_force.h"

#include "fix_sph_astro.h"
#include "fix_sph_astro_h.h"
#include "fix_sph_astro_switch.h"
#include "sph_astro_pair_terms.h"
#include "sph_astro_reconstruction.h"

#include "sph_astro_pair_coeff.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "neigh_request.h"
#include "neighbor.h"
#include "update.h"
#include "utils.h"

#include <cmath>
#include <cstring>
#include <vector>

using namespace LAMMPS_NS;
using namespace SPHAstro;

PairSPHAstro::PairSPHAstro(LAMMPS *lmp) : Pair(lmp)
{
  single_enable = 0;
  restartinfo = 1;
  one_coeff = 1;
  manybody_flag = 1;    // forces depend on densities of both partners
  finitecutflag = 1;    // per-atom cutoffs kernel_radius h_i for neighbor multi collections
  // rho, P, c_s, vest[3]; h, Omega, C (pressure-energy); alpha; u (cond.); Balsara f;
  // symmetric grad v, Delta
  comm_forward = 12 + SPHAstro::VGRAD_DATA;
  // rho, nneigh | dudt, sum v.gradW, max v_sig | div and curl sums | grad v sums
  comm_reverse = SPHAstro::VGRAD_SUMS;
}

PairSPHAstro::~PairSPHAstro()
{
  if (copymode) return;
  memory->destroy(pressure_);
  memory->destroy(soundspeed_);
  memory->destroy(vdotgradw_);
  memory->destroy(divv_);
  memory->destroy(nneigh_);
  memory->destroy(omega_);
  memory->destroy(dcurl_);
  memory->destroy(curlv_);
  memory->destroy(balsara_);
  memory->destroy(vsigmax_);
  memory->destroy(vgsum_);
  memory->destroy(vgrad_);
  memory->destroy(condrate_);
  memory->destroy(pe_gradh_);
  memory->destroy(pgeo_);
  memory->destroy(hprune_);
  memory->destroy(hcap_type_);
  memory->destroy(conduct_);
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
  }
}

void PairSPHAstro::allocate()
{
  allocated = 1;
  const int n = atom->ntypes + 1;
  memory->create(setflag, n, n, "pair:setflag");
  for (int i = 1; i < n; i++)
    for (int j = i; j < n; j++) setflag[i][j] = 0;
  memory->create(cutsq, n, n, "pair:cutsq");
  memory->create(hcap_type_, n, "pair:hcap_type");
}

void PairSPHAstro::grow_work_arrays()
{
  // (re)allocate also when curl v or v_sig became needed after the arrays were made
  if (atom->nmax <= nmax_ && (!curl_on_ || curlv_) && (!signal_viscosity() || vsigmax_) &&
      (!(pressure_geometric_ || pressure_energy_) || pgeo_) && (!reconstruction() || vgrad_) &&
      (!prune_on_ || hprune_) && (!artificial_conductivity() || condrate_) &&
      (!pressure_energy_ || pe_gradh_))
    return;
  nmax_ = MAX(nmax_, atom->nmax);
  if (prune_on_) memory->grow(hprune_, nmax_, "pair:sph/astro:hprune");    // kept until a build
  memory->destroy(pressure_);
  memory->destroy(soundspeed_);
  memory->destroy(vdotgradw_);
  memory->destroy(divv_);
  memory->destroy(nneigh_);
  memory->destroy(omega_);
  memory->create(omega_, nmax_, "pair:sph/astro:omega");
  memory->destroy(dcurl_);
  memory->destroy(curlv_);
  memory->destroy(balsara_);
  memory->destroy(vsigmax_);
  if (curl_on_) {
    memory->create(dcurl_, nmax_, 4, "pair:sph/astro:dcurl");
    memory->create(curlv_, nmax_, "pair:sph/astro:curlv");
  }
  if (balsara_on_) memory->create(balsara_, nmax_, "pair:sph/astro:balsara");
  if (signal_viscosity()) memory->create(vsigmax_, nmax_, "pair:sph/astro:vsigmax");
  memory->destroy(vgsum_);
  memory->destroy(vgrad_);
  if (reconstruction()) {
    memory->create(vgsum_, nmax_, VGRAD_SUMS, "pair:sph/astro:vgsum");
    memory->create(vgrad_, nmax_, VGRAD_DATA, "pair:sph/astro:vgrad");
  }
  memory->destroy(condrate_);
  if (artificial_conductivity()) memory->create(condrate_, nmax_, "pair:sph/astro:condrate");
  memory->destroy(pe_gradh_);
  if (pressure_energy_) memory->create(pe_gradh_, nmax_, "pair:sph/astro:pe_gradh");
  memory->destroy(pgeo_);
  if (pressure_geometric_ || pressure_energy_) memory->create(pgeo_, nmax_, "pair:sph/astro:pgeo");
  memory->create(pressure_, nmax_, "pair:sph/astro:pressure");
  memory->create(soundspeed_, nmax_, "pair:sph/astro:soundspeed");
  memory->create(vdotgradw_, nmax_, "pair:sph/astro:vdotgradw");
  memory->create(divv_, nmax_, "pair:sph/astro:divv");
  memory->create(nneigh_, nmax_, "pair:sph/astro:nneigh");
}

/* ----------------------------------------------------------------------
   pair_style sph/astro [kernel NAME] [eos ideal GAMMA | isothermal CS | polytropic K GAMMA]
                        [viscosity classic ALPHA BETA | signal ALPHA [BETA] | none]
                        [balsara yes|no] [conductivity ALPHA_U] [conduction KAPPA]
                        [epsilon EPS] [density summation|continuity]
                        [symmetrise hmean|kernel] [pressure standard|geometric]
                        [formulation density-energy|pressure-energy]
------------------------------------------------------------------------- */

void PairSPHAstro::settings(int narg, char **arg)
{
  // a repeated pair_style command starts again from the defaults
  kernel_ = KernelType::CUBIC;
  eos_ = EOS();
  visc_on_ = true;
  visc_alpha_ = 1.0;
  visc_beta_ = 2.0;
  visc_eps_ = 0.01;
  cond_alpha_ = 0.0;
  balsara_on_ = false;
  visc_signal_ = false;
  recon_on_ = false;
  recon_trigger_ = 1.0;
  recon_gate_ = 16;
  cond_kappa_ = 0.0;
  density_continuity_ = false;
  symmetrise_kernel_ = false;
  pressure_geometric_ = false;
  pressure_energy_ = false;
  prune_on_ = true;
  int iarg = 0;
  while (iarg < narg) {
    const std::string key = arg[iarg];
    if (key == "kernel") {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "pair_style sph/astro kernel", error);
      if (!kernel_from_name(arg[iarg + 1], kernel_))
        error->all(FLERR,
                   "pair_style sph/astro: unknown kernel '{}'; allowed: m4 (cubic), m6 "
                   "(quintic), wendland/c2, wendland/c4, gaussian",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (key == "eos") {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "pair_style sph/astro eos", error);
      const std::string model = arg[iarg + 1];
      if (model == "ideal") {
        if (iarg + 3 > narg)
          utils::missing_cmd_args(FLERR, "pair_style sph/astro eos ideal", error);
        eos_.type = EOSType::IDEAL;
        eos_.gamma = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
        if (!(eos_.gamma > 1.0))
          error->all(FLERR, "pair_style sph/astro eos ideal: gamma = {} must be > 1",
                     arg[iarg + 2]);
        iarg += 3;
      } else if (model == "isothermal") {
        if (iarg + 3 > narg)
          utils::missing_cmd_args(FLERR, "pair_style sph/astro eos isothermal", error);
        eos_.type = EOSType::ISOTHERMAL;
        eos_.cs = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
        if (!(eos_.cs > 0.0))
          error->all(FLERR, "pair_style sph/astro eos isothermal: sound speed {} must be > 0",
                     arg[iarg + 2]);
        iarg += 3;
      } else if (model == "polytropic") {
        if (iarg + 4 > narg)
          utils::missing_cmd_args(FLERR, "pair_style sph/astro eos polytropic", error);
        eos_.type = EOSType::POLYTROPIC;
        eos_.K = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
        eos_.gamma = utils::numeric(FLERR, arg[iarg + 3], false, lmp);
        if (!(eos_.K > 0.0))
          error->all(FLERR, "pair_style sph/astro eos polytropic: K = {} must be > 0",
                     arg[iarg + 2]);
        if (!(eos_.gamma > 1.0))
          error->all(FLERR, "pair_style sph/astro eos polytropic: gamma = {} must be > 1",
                     arg[iarg + 3]);
        iarg += 4;
      } else
        error->all(FLERR,
                   "pair_style sph/astro: unknown eos '{}'; allowed: ideal GAMMA, isothermal CS, "
                   "polytropic K GAMMA",
                   model);
    } else if (key == "viscosity") {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "pair_style sph/astro viscosity", error);
      const std::string form = arg[iarg + 1];
      if (form == "none") {
        visc_on_ = false;
        visc_alpha_ = visc_beta_ = 0.0;
        iarg += 2;
      } else if (form == "classic") {
        if (iarg + 4 > narg)
          utils::missing_cmd_args(FLERR, "pair_style sph/astro viscosity classic", error);
        visc_alpha_ = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
        visc_beta_ = utils::numeric(FLERR, arg[iarg + 3], false, lmp);
        if (visc_alpha_ < 0.0 || visc_beta_ < 0.0)
          error->all(FLERR,
                     "pair_style sph/astro viscosity classic: alpha = {} and beta = {} must be "
                     ">= 0",
                     arg[iarg + 2], arg[iarg + 3]);
        visc_on_ = (visc_alpha_ > 0.0 || visc_beta_ > 0.0);
        visc_signal_ = false;
        iarg += 4;
      } else if (form == "signal") {
        // viscosity signal ALPHA [BETA]: BETA (default 3) is a number only if one follows
        if (iarg + 3 > narg)
          utils::missing_cmd_args(FLERR, "pair_style sph/astro viscosity signal", error);
        visc_alpha_ = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
        visc_beta_ = 3.0;
        iarg += 3;
        if (iarg < narg && utils::is_double(arg[iarg])) {
          visc_beta_ = utils::numeric(FLERR, arg[iarg], false, lmp);
          iarg++;
        }
        if (!(visc_alpha_ > 0.0) || visc_beta_ < 0.0)
          error->all(FLERR,
                     "pair_style sph/astro viscosity signal: alpha = {} must be > 0 and beta = "
                     "{} >= 0",
                     visc_alpha_, visc_beta_);
        visc_on_ = true;
        visc_signal_ = true;
      } else
        error->all(FLERR,
                   "pair_style sph/astro: unknown viscosity '{}'; allowed: classic ALPHA BETA, "
                   "signal ALPHA [BETA], none",
                   form);
    } else if (key == "balsara") {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "pair_style sph/astro balsara", error);
      balsara_on_ = utils::logical(FLERR, arg[iarg + 1], false, lmp) == 1;
      iarg += 2;
    } else if (key == "reconstruct") {
      if (iarg + 2 > narg)
        utils::missing_cmd_args(FLERR, "pair_style sph/astro reconstruct", error);
      recon_on_ = utils::logical(FLERR, arg[iarg + 1], false, lmp) == 1;
      iarg += 2;
      // optional: trigger T (noise trigger radius, spacings), gate P (smoothness gate)
      while (iarg < narg && (strcmp(arg[iarg], "trigger") == 0 || strcmp(arg[iarg], "gate") == 0)) {
        const std::string sub = arg[iarg];
        if (iarg + 2 > narg)
          utils::missing_cmd_args(FLERR, "pair_style sph/astro reconstruct " + sub, error);
        if (sub == "trigger") {
          recon_trigger_ = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
          if (!(recon_trigger_ >= 0.0) || !std::isfinite(recon_trigger_))
            error->all(FLERR,
                       "pair_style sph/astro reconstruct trigger {} must be >= 0 (pairs closer "
                       "than this many particle spacings get the plain viscosity back; 0: never)",
                       arg[iarg + 1]);
        } else {
          recon_gate_ = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
          if (recon_gate_ < 0 || recon_gate_ > 64)
            error->all(FLERR,
                       "pair_style sph/astro reconstruct gate {} must be an integer in 0-64 (the "
                       "exponent of the smoothness gate; 0: off, default 16)",
                       arg[iarg + 1]);
        }
        iarg += 2;
      }
    } else if (key == "conductivity") {
      if (iarg + 2 > narg)
        utils::missing_cmd_args(FLERR, "pair_style sph/astro conductivity", error);
      cond_alpha_ = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (cond_alpha_ < 0.0)
        error->all(FLERR, "pair_style sph/astro: conductivity alpha_u = {} must be >= 0",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (key == "conduction") {
      // physical heat conduction kappa = k / c_v (pair_sph_astro_conduction.cpp)
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "pair_style sph/astro conduction", error);
      cond_kappa_ = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(cond_kappa_ >= 0.0) || !std::isfinite(cond_kappa_))
        error->all(FLERR,
                   "pair_style sph/astro: conduction kappa = {} must be finite and >= 0 (0: no "
                   "heat conduction)",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (key == "epsilon") {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "pair_style sph/astro epsilon", error);
      visc_eps_ = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(visc_eps_ > 0.0))
        error->all(FLERR, "pair_style sph/astro: epsilon = {} must be > 0", arg[iarg + 1]);
      iarg += 2;
    } else if (key == "density") {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "pair_style sph/astro density", error);
      const std::string value = arg[iarg + 1];
      if (value == "summation")
        density_continuity_ = false;
      else if (value == "continuity")
        density_continuity_ = true;
      else
        error->all(FLERR,
                   "pair_style sph/astro: unknown density '{}'; allowed: summation, continuity",
                   value);
      iarg += 2;
    } else if (key == "symmetrise") {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "pair_style sph/astro symmetrise", error);
      const std::string value = arg[iarg + 1];
      if (value == "hmean")
        symmetrise_kernel_ = false;
      else if (value == "kernel")
        symmetrise_kernel_ = true;
      else
        error->all(FLERR, "pair_style sph/astro: unknown symmetrise '{}'; allowed: hmean, kernel",
                   value);
      iarg += 2;
    } else if (key == "pressure") {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "pair_style sph/astro pressure", error);
      const std::string value = arg[iarg + 1];
      if (value == "standard")
        pressure_geometric_ = false;
      else if (value == "geometric")
        pressure_geometric_ = true;
      else
        error->all(FLERR,
                   "pair_style sph/astro: unknown pressure '{}'; allowed: standard, geometric",
                   value);
      iarg += 2;
    } else if (key == "formulation") {
      if (iarg + 2 > narg)
        utils::missing_cmd_args(FLERR, "pair_style sph/astro formulation", error);
      const std::string value = arg[iarg + 1];
      if (value == "density-energy")
        pressure_energy_ = false;
      else if (value == "pressure-energy")
        pressure_energy_ = true;
      else
        error->all(FLERR,
                   "pair_style sph/astro: unknown formulation '{}'; allowed: density-energy, "
                   "pressure-energy",
                   value);
      iarg += 2;
    } else if (key == "prune") {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "pair_style sph/astro prune", error);
      prune_on_ = utils::logical(FLERR, arg[iarg + 1], false, lmp) == 1;
      iarg += 2;
    } else
      error->all(FLERR,
                 "pair_style sph/astro: unknown keyword '{}'; allowed: kernel, eos, viscosity, "
                 "balsara, reconstruct, conductivity, conduction, epsilon, density, symmetrise, "
                 "pressure, formulation, prune",
                 key);
  }
  // the integrated density and its prediction live in their own per-atom state; it is
  // created here or, after read_restart, by fix sph/astro (then LAMMPS restores its values)
  if (density_continuity_) ensure_continuity_state(lmp, "pair_style sph/astro density continuity");
  kernel_radius_ = SPHAstro::kernel_radius(kernel_);
  if (balsara_on_ && !visc_on_)
    error->all(FLERR, "pair_style sph/astro: balsara yes needs viscosity classic or signal");
  if (recon_on_ && !visc_on_)
    error->all(FLERR, "pair_style sph/astro: reconstruct yes needs viscosity classic or signal");
  if (recon_on_ && balsara_on_)
    error->all(FLERR,
               "pair_style sph/astro: reconstruct yes and balsara yes cannot be combined (the "
               "reconstruction removes the viscosity of a linear shear flow already); use one");
}

/* ----------------------------------------------------------------------
   pair_coeff * *  (all pairs of SPH particle types; no parameters)
------------------------------------------------------------------------- */

void PairSPHAstro::coeff(int narg, char **arg)
{
  if (!allocated) allocate();
  SPHAstro::set_type_pairs(lmp, "sph/astro", narg, arg, setflag);
}

void PairSPHAstro::init_style()
{
  if (!find_state(lmp, state_))
    error->all(FLERR,
               "pair_style sph/astro needs the SPH per-particle state: define fix sph/astro "
               "(it creates fix {})",
               STATE_FIX_ID);
  auto integrators = modify->get_fix_by_style("^sph/astro$");
  if (integrators.empty())
    error->all(FLERR,
               "pair_style sph/astro requires fix sph/astro: it integrates u and predicts the "
               "velocities the viscosity uses");
  integrator_ = dynamic_cast<FixSPHAstro *>(integrators.front());
  entropy_ = integrator_ && integrator_->entropy();
  if (entropy_ && !find_entropy_state(lmp, entropy_index_))
    error->all(FLERR, "pair_style sph/astro: the entropy state fix {} is missing", ENTROPY_FIX_ID);
  if (domain->dimension != 2 && domain->dimension != 3)
    error->all(FLERR, "pair_style sph/astro: dimension {} not supported", domain->dimension);

  auto hfixes = modify->get_fix_by_style("^sph/astro/h$");
  hfix_ = hfixes.empty() ? nullptr : dynamic_cast<FixSPHAstroH *>(hfixes.front());
  if (!hfix_)
    hmode_ = HMode::FIXED;
  else
    hmode_ = hfix_->mode() == FixSPHAstroH::Mode::ITERATE ? HMode::GRADH : HMode::DHDT;
  const double margin = hfix_ ? hfix_->margin() : 1.0;

  if (cond_alpha_ > 0.0 && !eos_.uses_energy() && comm->me == 0)
    error->warning(FLERR,
                   "pair_style sph/astro: conductivity {} has no effect with eos {} (only the "
                   "ideal gas evolves u)",
                   cond_alpha_, eos_.type == EOSType::ISOTHERMAL ? "isothermal" : "polytropic");

  if (cond_kappa_ > 0.0 && !eos_.uses_energy())
    error->all(FLERR,
               "pair_style sph/astro: conduction {} needs eos ideal (the energy equation); eos {} "
               "does not evolve u",
               cond_kappa_, eos_.type == EOSType::ISOTHERMAL ? "isothermal" : "polytropic");

  auto switches = modify->get_fix_by_style("^sph/astro/switch$");
  switch_ = switches.empty() ? nullptr : dynamic_cast<FixSPHAstroSwitch *>(switches.front());
  if (switch_ && !(visc_on_ && visc_alpha_ > 0.0))
    error->all(FLERR,
               "fix sph/astro/switch needs pair_style sph/astro viscosity classic or signal with "
               "alpha > 0 (classic: beta scales with the particle's alpha as beta/alpha)");
  curl_on_ = balsara_on_ || (switch_ && switch_->needs_curl());

  // the seeds' other choices are those of the fixed-h equations; with grad-h terms the
  // density, its kernels and the pressure term follow from the h-rho relation
  if (hmode_ == HMode::GRADH) {
    if (density_continuity_)
      error->all(FLERR,
                 "pair_style sph/astro density continuity needs fixed h or fix sph/astro/h dhdt: "
                 "with fix sph/astro/h iterate h follows from the summed density");
    if (symmetrise_kernel_)
      error->all(FLERR,
                 "pair_style sph/astro symmetrise kernel needs fixed h or fix sph/astro/h dhdt: "
                 "with fix sph/astro/h iterate the grad-h equations use W(h_i) and W(h_j) "
                 "already");
    if (pressure_geometric_)
      error->all(FLERR,
                 "pair_style sph/astro pressure geometric needs fixed h or fix sph/astro/h dhdt: "
                 "the grad-h equations (fix sph/astro/h iterate) have their own pressure term");
  }
  if (pressure_geometric_ && entropy_)
    error->all(FLERR,
               "pair_style sph/astro pressure geometric needs fix sph/astro thermal energy: with "
               "thermal entropy the P dV work is P_i/rho_i^2 drho_i/dt, which does not match the "
               "geometric-mean force");
  if (pressure_energy_) {
    const char *what = nullptr;
    if (eos_.type != EOSType::IDEAL)
      what = "eos ideal (the smoothed pressure is (gamma-1) sum_j m_j u_j W_ij)";
    else if (entropy_)
      what = "fix sph/astro thermal energy (it evolves u; thermal entropy is not supported)";
    else if (density_continuity_)
      what = "density summation (its density follows from the smoothed pressure)";
    else if (symmetrise_kernel_)
      what = "symmetrise hmean";
    else if (pressure_geometric_)
      what = "pressure standard (it has a pressure term of its own)";
    if (what) error->all(FLERR, "pair_style sph/astro formulation pressure-energy needs {}", what);
  }
  if (density_continuity_ && !find_continuity_state(lmp, continuity_index_))
    error->all(FLERR,
               "pair_style sph/astro density continuity: the per-atom state fix {} is missing",
               CONTINUITY_FIX_ID);

  // every particle needs a positive mass and smoothing length; the list cutoffs are set
  // by the largest h of each type
  const int nlocal = atom->nlocal;
  const int ntypes = atom->ntypes;
  const double *h = atom->dvector[state_.h];
  const double *rmass = atom->rmass;
  const double *mass = atom->mass;
  const int *type = atom->type;
  std::vector<double> hmax_local(ntypes + 1, 0.0);
  for (int i = 0; i < nlocal; i++) {
    const double mi = rmass ? rmass[i] : mass[type[i]];
    if (!(mi > 0.0) || !std::isfinite(mi))
      error->one(FLERR, "pair_style sph/astro: atom {} has mass {}; the mass must be > 0",
                 atom->tag[i], mi);
    if (!(h[i] > 0.0) || !std::isfinite(h[i]))
      error->one(FLERR,
                 "pair_style sph/astro: atom {} has smoothing length h = {}; h must be > 0 "
                 "(set it with: set group all d_h VALUE)",
                 atom->tag[i], h[i]);
    hmax_local[type[i]] = MAX(hmax_local[type[i]], h[i]);
  }
  MPI_Allreduce(hmax_local.data(), hcap_type_, ntypes + 1, MPI_DOUBLE, MPI_MAX, world);
  double hmax = 0.0;
  for (int t = 1; t <= ntypes; t++) hmax = MAX(hmax, hcap_type_[t]);
  if (hmax <= 0.0)
    error->all(FLERR, "pair_style sph/astro: no particle has h > 0 (set group all d_h VALUE)");
  // a type without particles yet gets the largest h of all
  for (int t = 1; t <= ntypes; t++)
    hcap_type_[t] = margin * (hcap_type_[t] > 0.0 ? hcap_type_[t] : hmax);

  const double support = kernel_radius_ * hmax;
  if (neighbor->skin > support && comm->me == 0)
    error->warning(FLERR,
                   "pair_style sph/astro: neighbor skin {} exceeds the kernel support {}: the "
                   "neighbour lists hold many non-neighbours; a skin of 0.1-0.3 x support is "
                   "usual",
                   neighbor->skin, support);

  // (LAMMPS calls init_list() only for lists it makes anew: pointers to lists requested again
  // stay valid, those not requested are dropped here)
  if (hmode_ == HMode::GRADH) {
    // full list for the per-particle h iteration, half list for the pair forces (with prune
    // yes this style makes the half list itself, in the scan that prunes the full one)
    neighbor->add_request(this, NeighConst::REQ_FULL)->set_id(1);
    if (!prune_on_)
      neighbor->add_request(this)->set_id(2);
    else
      lammps_half_ = nullptr;
  } else {
    neighbor->add_request(this);
    listfull_ = nullptr;
  }
}

void PairSPHAstro::init_list(int id, NeighList *ptr)
{
  if (hmode_ == HMode::GRADH && id == 1) {
    listfull_ = ptr;
    if (prune_on_) list = ptr;    // Pair::list: the one LAMMPS list there is
  } else
    list = lammps_half_ = ptr;
}

double PairSPHAstro::init_one(int i, int j)
{
  if (setflag[i][j] == 0)
    error->all(FLERR, "pair_style sph/astro: pair_coeff for types {} {} is not set", i, j);
  // W(h_i) and W(h_j) (grad-h terms or the averaged kernel) reach R max(h_i, h_j)
  if (hmode_ == HMode::GRADH || symmetrise_kernel_)
    return kernel_radius_ * MAX(hcap_type_[i], hcap_type_[j]);
  return kernel_radius_ * 0.5 * (hcap_type_[i] + hcap_type_[j]);
}

/* ---------------------------------------------------------------------- */

// the density of the force evaluation: the summed d_rho, or with density continuity the
// prediction d_rhoest of fix sph/astro (d_rho then holds the integrated density)
double *PairSPHAstro::eval_density() const
{
  return density_continuity_ ? atom->dvector[continuity_index_.rhoest] : atom->dvector[state_.rho];
}

void PairSPHAstro::equation_of_state()
{
  const int nlocal = atom->nlocal;
  const double *rho = eval_density();
  const double *h = atom->dvector[state_.h];
  double *uest = atom->dvector[state_.uest];
  const tagint *tag = atom->tag;
  const int *type = atom->type;

  // entropy formulation: P = A rho^gamma (seed 000, "entropy equation"); A starts from u
  if (entropy_) {
    double *A = atom->dvector[entropy_index_.A];
    double *Aest = atom->dvector[entropy_index_.Aest];
    const double *u = atom->dvector[state_.u];
    const double g1 = eos_.gamma - 1.0;
    const bool init = integrator_->entropy_needs_init();
    for (int i = 0; i < nlocal; i++) {
      if (init) Aest[i] = A[i] = g1 * u[i] * std::pow(rho[i], -g1);
      uest[i] = Aest[i] * std::pow(rho[i], g1) / g1;
    }
    if (init) integrator_->entropy_initialised();
  }
  for (int i = 0; i < nlocal; i++) {
    if (!(rho[i] > 0.0) || !std::isfinite(rho[i]))
      error->one(FLERR, "pair_style sph/astro: atom {} has density {} ({}position not finite?)",
                 tag[i], rho[i],
                 density_continuity_ ? "density continuity: too large a timestep? " : "");
    if (h[i] > hcap_type_[type[i]])
      error->one(FLERR,
                 "pair_style sph/astro: atom {} has h = {} larger than the h = {} the neighbour "
                 "lists of its type were built for; h was changed during a run (fix "
                 "sph/astro/h keeps h below that cap)",
                 tag[i], h[i], hcap_type_[type[i]]);
    const double u = uest[i];
    if (eos_.uses_energy() && (!(u >= 0.0) || !std::isfinite(u)))
      error->one(FLERR,
                 "pair_style sph/astro: atom {} has specific internal energy u = {}; u must be "
                 "finite and >= 0",
                 tag[i], u);
    eos_.pressure_soundspeed(rho[i], u, pressure_[i], soundspeed_[i]);
  }
}

// du_i/dt so far holds the dissipative heating (viscosity, conductivity); add the P dV work
// P_i/(Omega_i rho_i^2) sum_j m_j v_ij . grad W (Omega = 1 without grad-h terms). With the
// entropy formulation dA_i/dt = (gamma-1) / rho_i^(gamma-1) x heating (seed 000). With
// pressure geometric the P dV work is already in du_i/dt (pdv_done; no entropy form then).
void PairSPHAstro::finish_thermal_rates(bool gradh, bool pdv_done)
{
  const int nlocal = atom->nlocal;
  const double *rho = eval_density();
  double *dudt = atom->dvector[state_.dudt];
  if (entropy_) {
    double *dAdt = atom->dvector[entropy_index_.dAdt];
    const double g1 = eos_.gamma - 1.0;
    for (int i = 0; i < nlocal; i++) dAdt[i] = g1 * std::pow(rho[i], -g1) * dudt[i];
  }
  if (pdv_done) return;
  for (int i = 0; i < nlocal; i++) {
    const double omega = gradh ? omega_[i] : 1.0;
    dudt[i] += pressure_[i] / (omega * rho[i] * rho[i]) * vdotgradw_[i];
  }
}

/* ----------------------------------------------------------------------
   density summation with fixed h or dh/dt, over the half list (seed 000, "density"; seed
   004 eq. 27):
     rho_i = sum_j m_j W_ij,  W_ij = W(r_ij, h_ij), h_ij = (h_i + h_j)/2          (hmean)
                              W_ij = (W(r_ij, h_i) + W(r_ij, h_j))/2             (KM: kernel)
   including the particle's own m_i W(0, h_i); N_i counts the partners inside the support.
   PE (formulation pressure-energy): the weights are m_j u_j, so d_rho holds the energy
   density sum_j m_j u_j W_ij = P_i/(gamma-1) until pressure_energy_density() divides by u_i.
------------------------------------------------------------------------- */

template <class KERNEL, int DIM, bool KM, bool PE> void PairSPHAstro::density_sum()
{
  using K = Kernel<KERNEL, DIM>;
  double **x = atom->x;
  const int *type = atom->type;
  const double *rmass = atom->rmass;
  const double *mass = atom->mass;
  double *rho = atom->dvector[state_.rho];
  const double *h = atom->dvector[state_.h];
  const double *uest = atom->dvector[state_.uest];    // PE: owned and ghost (Stage::ENERGY)
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
  const double w0 = K::w(0.0);

  for (int i = 0; i < nzero; i++) {
    rho[i] = 0.0;
    nneigh_[i] = 0.0;
  }
  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    const double xi = x[i][0], yi = x[i][1], zi = x[i][2];
    const double hi = h[i];
    const double hinvi = 1.0 / hi;
    const double hR2i = R2 * hi * hi;
    const double mi = (rmass ? rmass[i] : mass[type[i]]) * (PE ? uest[i] : 1.0);
    double rhoi = mi * sigma * inv_h_pow_dim<DIM>(hinvi) * w0;
    double ni = 0.0;
    const int *jlist = firstneigh[i];
    const int jnum = numneigh[i];
    for (int jj = 0; jj < jnum; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      const double dx = xi - x[j][0], dy = yi - x[j][1], dz = zi - x[j][2];
      const double r2 = dx * dx + dy * dy + dz * dz;
      double wij;
      if (KM) {
        const double hj = h[j];
        const double hR2j = R2 * hj * hj;
        if (r2 >= hR2i && r2 >= hR2j) continue;
        const double r = std::sqrt(r2);
        const double hinvj = 1.0 / hj;
        const double wi = r2 < hR2i ? inv_h_pow_dim<DIM>(hinvi) * K::w(r * hinvi) : 0.0;
        const double wj = r2 < hR2j ? inv_h_pow_dim<DIM>(hinvj) * K::w(r * hinvj) : 0.0;
        wij = 0.5 * sigma * (wi + wj);
      } else {
        const double hij = 0.5 * (hi + h[j]);
        if (r2 >= R2 * hij * hij) continue;
        const double hinv = 1.0 / hij;
        wij = sigma * inv_h_pow_dim<DIM>(hinv) * K::w(std::sqrt(r2) * hinv);
      }
      const double mj = (rmass ? rmass[j] : mass[type[j]]) * (PE ? uest[j] : 1.0);
      rhoi += mj * wij;
      ni += 1.0;
      if (newton_pair || j < nlocal) {
        rho[j] += mi * wij;
        nneigh_[j] += 1.0;
      }
    }
    rho[i] += rhoi;
    nneigh_[i] += ni;
  }
  if (newton_pair) {
    comm_stage_ = Stage::DENSITY;
    comm->reverse_comm(this);
  }
}

// formulation pressure-energy: rho_i = (sum_j m_j u_j W_ij) / u_i, the density that makes the
// ideal-gas pressure (gamma-1) rho_i u_i equal the smoothed one (Saitoh & Makino 2013, the
// volume element m_i u_i / sum_j m_j u_j W_ij)
void PairSPHAstro::pressure_energy_density(const double *energy_sum)
{
  const int nlocal = atom->nlocal;
  double *rho = atom->dvector[state_.rho];
  const double *uest = atom->dvector[state_.uest];
  for (int i = 0; i < nlocal; i++) {
    if (!(uest[i] > 0.0) || !std::isfinite(uest[i]))
      error->one(FLERR,
                 "pair_style sph/astro formulation pressure-energy: atom {} has specific internal "
                 "energy u = {}; this formulation needs u > 0 (rho = P/((gamma-1) u))",
                 atom->tag[i], uest[i]);
    rho[i] = energy_sum[i] / uest[i];
  }
}

// density continuity without a summation: the neighbour counts of compute sph/astro/atom
// (partners inside R h_ij, or R max(h_i, h_j) with the averaged kernel), a pass only for them,
// run when they are asked for (x, h and the lists are still those of the force evaluation)
const double *PairSPHAstro::neighbour_counts()
{
  if (counts_step_ != computed_step_ && computed_step_ >= 0) {
    count_neighbours();
    counts_step_ = computed_step_;
  }
  return nneigh_;
}

void PairSPHAstro::count_neighbours()
{
  double **x = atom->x;
  const double *h = atom->dvector[state_.h];
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const int newton_pair = force->newton_pair;
  const double R2 = kernel_radius_ * kernel_radius_;
  const bool km = symmetrise_kernel_;
  for (int i = 0; i < (newton_pair ? nall : nlocal); i++) nneigh_[i] = 0.0;
  const SPHAstro::NeighView nl = half_view();
  for (int ii = 0; ii < nl.inum; ii++) {
    const int i = nl.ilist[ii];
    const double hi = h[i];
    const int *jlist = nl.firstneigh[i];
    const int jnum = nl.numneigh[i];
    double ni = 0.0;
    for (int jj = 0; jj < jnum; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      const double dx = x[i][0] - x[j][0], dy = x[i][1] - x[j][1], dz = x[i][2] - x[j][2];
      const double r2 = dx * dx + dy * dy + dz * dz;
      const double hk = km ? MAX(hi, h[j]) : 0.5 * (hi + h[j]);
      if (r2 >= R2 * hk * hk) continue;
      ni += 1.0;
      if (newton_pair || j < nlocal) nneigh_[j] += 1.0;
    }
    nneigh_[i] += ni;
  }
  if (newton_pair) {
    comm_stage_ = Stage::COUNT;
    comm->reverse_comm(this, 1);
  }
}

/* ----------------------------------------------------------------------
   variable h with grad-h terms (Springel & Hernquist 2002, MNRAS 333, 649; Price 2012,
   J. Comput. Phys. 231, 759, sec. 2.4 and eqs. 101-107):
     rho_i = sum_j m_j W(r_ij, h_i),  h_i = hfact (m_i / rho_i)^(1/d)
     Omega_i = 1 - (dh_i/drho_i) sum_j m_j dW(r_ij, h_i)/dh_i,  dh/drho = -h / (d rho)
     dv_i/dt = -sum_j m_j [P_i/(Omega_i rho_i^2) grad_i W_ij(h_i)
                           + P_j/(Omega_j rho_j^2) grad_i W_ij(h_j) + Pi_ij gradbar_i W_ij]
     du_i/dt = P_i/(Omega_i rho_i^2) sum_j m_j v_ij . grad_i W_ij(h_i)
               + 1/2 sum_j m_j Pi_ij v_ij . gradbar_i W_ij
   with gradbar W_ij = (grad W(h_i) + grad W(h_j))/2 (seed 000, "average of the kernel
   contributions"). dW/dh = -sigma/h^(d+1) (d w(q) + q w'(q)). VSUMS_CURL: the same loop also
   sums m_j v_ij . grad_i W(h_i) and m_j v_ij x grad_i W(h_i) for div v and curl v
   (velocity_curl); VSUMS_GRADIENT: the sums M and G of the linearly exact grad v
   (sph_astro_reconstruction.h), from which div v and curl v follow as well.
------------------------------------------------------------------------- */

template <class KERNEL, int DIM, int VSUMS, bool PE> void PairSPHAstro::density_gradh()
{
  constexpr bool CURL = VSUMS == VSUMS_CURL;
  constexpr bool GRADIENT = VSUMS == VSUMS_GRADIENT;
  using K = Kernel<KERNEL, DIM>;
  double **x = atom->x;
  const int *type = atom->type;
  const double *rmass = atom->rmass;
  const double *mass = atom->mass;
  double *rho = atom->dvector[state_.rho];
  double *h = atom->dvector[state_.h];
  const tagint *tag = atom->tag;
  double **vest = (CURL || GRADIENT) ? atom->darray[state_.vest] : nullptr;

  // the pruned full list while h stays within its limit, else LAMMPS' list for that atom
  const bool pruned = pruned_full_.built();
  const SPHAstro::NeighView nl = pruned ? pruned_full_.view() : SPHAstro::view_of(listfull_);
  const int inum = nl.inum;
  const int *ilist = nl.ilist;
  const int *numneigh = nl.numneigh;
  int *const *firstneigh = nl.firstneigh;
  bigint atom_fallbacks = 0;

  const double sigma = K::sigma();
  const double R2 = K::radius * K::radius;
  const double w0 = K::w(0.0);
  const double hfact_d = std::pow(hfix_->hfact(), DIM);
  const double *uest = PE ? atom->dvector[state_.uest] : nullptr;    // owned and ghost
  const double gm1 = eos_.gamma - 1.0;
  const double tol = hfix_->tolerance();
  const int maxiter = hfix_->max_iterations();

  double iter_sum = 0.0;
  int iter_max = 0, failures = 0, capped = 0;

  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    const double xi = x[i][0], yi = x[i][1], zi = x[i][2];
    const double mi = rmass ? rmass[i] : mass[type[i]];
    const double cap = h_limit(i);
    const int *jlist = firstneigh[i];
    int jnum = numneigh[i];
    double hlist = pruned ? hprune_[i] : INFINITY;    // the largest h jlist serves

    double hi = MIN(h[i], cap);
    double hlo = 0.0, hhi = INFINITY;    // f(h) = rho(h) - rho_target(h) rises with h
    double h_evaluated = hi;             // rho, Omega and the count belong to this h
    double rhoi = 0.0, dsum = 0.0, ni = 0.0;
    double esum = 0.0, desum = 0.0;    // PE: sum_j m_j u_j W and its d/dh at h_evaluated
    // CURL: sum_j m_j v_ij . grad_i W and sum_j m_j v_ij x grad_i W at h_evaluated
    double curl_sum[4] = {0.0, 0.0, 0.0, 0.0};
    double grad_sum[VGRAD_SUMS] = {};    // GRADIENT: M and G at h_evaluated
    bool converged = false, at_cap = false;
    int it = 0;
    while (it < maxiter) {
      it++;
      if (hi > hlist) {
        jlist = listfull_->firstneigh[i];
        jnum = listfull_->numneigh[i];
        hlist = INFINITY;
        atom_fallbacks++;
      }
      // rho(h) and sum_j m_j dW/dh at the current h
      const double hinv = 1.0 / hi;
      const double norm = sigma * inv_h_pow_dim<DIM>(hinv);
      const double hR2 = R2 * hi * hi;
      double w_sum = mi * w0, dwh_sum = -mi * DIM * w0;    // self term
      const double ei = PE ? mi * uest[i] : 0.0;
      double we_sum = ei * w0, dweh_sum = -ei * DIM * w0;
      double vgrad[4] = {0.0, 0.0, 0.0, 0.0};    // the same sums over w'(q) / r, at this h
      double gsum[VGRAD_SUMS];
      if (GRADIENT)
        for (int k = 0; k < VGRAD_SUMS; k++) gsum[k] = 0.0;
      ni = 0.0;
      for (int jj = 0; jj < jnum; jj++) {
        const int j = jlist[jj] & NEIGHMASK;
        const double dx = xi - x[j][0], dy = yi - x[j][1], dz = zi - x[j][2];
        const double r2 = dx * dx + dy * dy + dz * dz;
        if (r2 >= hR2) continue;
        const double r = std::sqrt(r2);
        const double q = r * hinv;
        const double mj = rmass ? rmass[j] : mass[type[j]];
        const double w = K::w(q);
        const double dw = K::dw(q);
        w_sum += mj * w;
        dwh_sum -= mj * (DIM * w + q * dw);
        if (PE) {
          const double ej = mj * uest[j];
          we_sum += ej * w;
          dweh_sum -= ej * (DIM * w + q * dw);
        }
        ni += 1.0;
        if (CURL && r2 > 0.0) {
          const double dwr = mj * dw / r;
          const double dvx = vest[i][0] - vest[j][0], dvy = vest[i][1] - vest[j][1],
                       dvz = vest[i][2] - vest[j][2];
          vgrad[0] += (dvx * dx + dvy * dy + dvz * dz) * dwr;
          vgrad[1] += (dvy * dz - dvz * dy) * dwr;
          vgrad[2] += (dvz * dx - dvx * dz) * dwr;
          vgrad[3] += (dvx * dy - dvy * dx) * dwr;
        }
        if (GRADIENT && r2 > 0.0)
          velocity_gradient_add(gsum, mj * dw / r, vest[i][0] - vest[j][0], vest[i][1] - vest[j][1],
                                vest[i][2] - vest[j][2], dx, dy, dz);
      }
      if (CURL)    // grad_i W = sigma h^-(d+1) w'(q) r_ij / r
        for (int k = 0; k < 4; k++) curl_sum[k] = norm * hinv * vgrad[k];
      if (GRADIENT)
        for (int k = 0; k < VGRAD_SUMS; k++) grad_sum[k] = norm * hinv * gsum[k];
      rhoi = norm * w_sum;
      dsum = norm * hinv * dwh_sum;    // sum_j m_j dW/dh
      if (PE) {
        esum = norm * we_sum;
        desum = norm * hinv * dweh_sum;
      }
      h_evaluated = hi;
      const double rho_target = mi * hfact_d * inv_h_pow_dim<DIM>(hinv);
      const double f = rhoi - rho_target;
      const double fprime = dsum + DIM * rho_target * hinv;
      if (f < 0.0)
        hlo = hi;
      else
        hhi = hi;
      double hnew = hi - f / fprime;
      if (!(fprime > 0.0) || !(hnew > hlo) || !(hnew < hhi))
        hnew = std::isfinite(hhi) ? 0.5 * (hlo + hhi) : 2.0 * hi;    // bisection fallback
      if (hnew >= cap && hi >= cap) {    // wants to grow past the cap: stay there
        at_cap = true;
        converged = true;
        break;
      }
      hnew = MIN(hnew, cap);
      if (std::fabs(hnew - hi) < tol * hi) {
        converged = true;
        break;
      }
      hi = hnew;
    }
    if (!converged) failures++;
    if (at_cap) capped++;
    hi = h_evaluated;
    iter_sum += it;
    iter_max = MAX(iter_max, it);
    if (!(rhoi > 0.0) || !std::isfinite(rhoi) || !std::isfinite(hi))
      error->one(FLERR, "pair_style sph/astro: atom {} has density {} at h = {}", tag[i], rhoi, hi);
    h[i] = hi;
    rho[i] = rhoi;
    nneigh_[i] = ni;
    if (CURL)
      for (int k = 0; k < 4; k++) dcurl_[i][k] = curl_sum[k];
    if (GRADIENT)
      for (int k = 0; k < VGRAD_SUMS; k++) vgsum_[i][k] = grad_sum[k];
    // h held at the cap does not follow rho: Omega = 1
    omega_[i] = at_cap ? 1.0 : 1.0 + hi / (DIM * rhoi) * dsum;
    bool follows_rho = !at_cap;
    if (!(omega_[i] > 0.0)) {
      omega_[i] = 1.0;
      follows_rho = false;
    }
    if (PE) {    // P_i / (gamma-1) and C_i = h_i dP_i/dh_i / (d rho^m_i Omega_i)
      pgeo_[i] = esum;
      pe_gradh_[i] = follows_rho ? gm1 * hi * desum / (DIM * rhoi * omega_[i]) : 0.0;
    }
  }
  prune_atom_fallbacks_ += atom_fallbacks;
  hfix_->record(iter_sum, iter_max, inum, failures, capped);
}

int PairSPHAstro::pair_form() const
{
  if (hmode_ == HMode::GRADH) return pressure_energy_ ? GRADH_PRESSURE_ENERGY : GRADH;
  if (pressure_energy_) return HMEAN_PRESSURE_ENERGY;
  if (symmetrise_kernel_) return pressure_geometric_ ? KMEAN_GEOMETRIC : KMEAN;
  return pressure_geometric_ ? HMEAN_GEOMETRIC : HMEAN;
}

// the force pass for this scene's EOS, conductivity and viscosity, in pair form FORM

// the option forms are instantiated in pair_sph_astro_forms.cpp
SPH_ASTRO_OPTION_FORMS(extern)

/* ----------------------------------------------------------------------
   one force evaluation: pass 1 density (summation, h iteration, or none with density
   continuity after its first summation), EOS, optional curl v pass, forward communication,
   pass 2 forces in the pair form of this scene
------------------------------------------------------------------------- */

template <class KERNEL, int DIM> void PairSPHAstro::dispatch_physics()
{
  const int form = pair_form();
  const int nlocal = atom->nlocal;
  if (hmode_ == HMode::DHDT) {    // the ghosts need this step's h
    comm_stage_ = Stage::SMOOTHING_LENGTH;
    comm->forward_comm(this, 1);
  }
  counts_step_ = update->ntimestep;    // a density pass counts the neighbours
  const bool gradh = form_gradh(form);
  if (form_pressure_energy(form)) {    // the ghosts' u of this step
    comm_stage_ = Stage::ENERGY;
    comm->forward_comm(this, 1);
  }
  // the velocity sums ride on the h iteration's last sum
  if (form == GRADH && reconstruction()) {
    forward_predicted_velocities();
    density_gradh<KERNEL, DIM, VSUMS_GRADIENT, false>();
  } else if (form == GRADH && curl_on_) {
    forward_predicted_velocities();
    density_gradh<KERNEL, DIM, VSUMS_CURL, false>();
  } else if (form == GRADH)
    density_gradh<KERNEL, DIM, VSUMS_NONE, false>();
  else if (form == GRADH_PRESSURE_ENERGY && reconstruction()) {
    forward_predicted_velocities();
    density_gradh<KERNEL, DIM, VSUMS_GRADIENT, true>();
  } else if (form == GRADH_PRESSURE_ENERGY && curl_on_) {
    forward_predicted_velocities();
    density_gradh<KERNEL, DIM, VSUMS_CURL, true>();
  } else if (form == GRADH_PRESSURE_ENERGY)
    density_gradh<KERNEL, DIM, VSUMS_NONE, true>();
  else if (form == HMEAN_PRESSURE_ENERGY) {
    density_sum<KERNEL, DIM, false, true>();
    pressure_energy_density(atom->dvector[state_.rho]);
  } else if (!density_continuity_ || integrator_->density_needs_init()) {
    if (symmetrise_kernel_)
      density_sum<KERNEL, DIM, true, false>();
    else
      density_sum<KERNEL, DIM, false, false>();
    if (density_continuity_) {    // the integrated density starts from one summation
      const double *rho = atom->dvector[state_.rho];
      double *rhoest = atom->dvector[continuity_index_.rhoest];
      for (int i = 0; i < nlocal; i++) rhoest[i] = rho[i];
      integrator_->density_initialised();
    }
  } else
    counts_step_ = -1;    // counted only if asked for (neighbour_counts)
  equation_of_state();
  if (reconstruction()) {    // grad v (and from it div v and curl v)
    if (!gradh) {
      if (symmetrise_kernel_)
        velocity_curl<KERNEL, DIM, KMEAN, VSUMS_GRADIENT>();
      else
        velocity_curl<KERNEL, DIM, HMEAN, VSUMS_GRADIENT>();
    }
    velocity_gradient_finish<DIM>(gradh);
  } else if (curl_on_) {
    if (gradh)
      velocity_curl_finish(true);    // sums from density_gradh
    else if (symmetrise_kernel_)
      velocity_curl<KERNEL, DIM, KMEAN, VSUMS_CURL>();
    else
      velocity_curl<KERNEL, DIM, HMEAN, VSUMS_CURL>();
  }
  // pressure-energy with grad-h terms: div v and curl v above are those of the mass density
  // and Omega; now rho_i = P_i / ((gamma-1) u_i) and the EOS again (P = (gamma-1) rho u)
  if (form == GRADH_PRESSURE_ENERGY) {
    pressure_energy_density(pgeo_);
    equation_of_state();
  }
  comm_stage_ = Stage::DENSITY;
  comm->forward_comm(this);
  if (pressure_geometric_) {    // g = sqrt(P)/rho of owned and ghost atoms
    const double *rho = eval_density();
    const int nall = nlocal + atom->nghost;
    for (int i = 0; i < nall; i++) pgeo_[i] = pressure_geometric_factor(pressure_[i], rho[i]);
  } else if (pressure_energy_) {    // (gamma-1) u = P/rho of owned and ghost atoms
    const double *rho = eval_density();
    const int nall = nlocal + atom->nghost;
    for (int i = 0; i < nall; i++) pgeo_[i] = pressure_[i] / rho[i];
  }
  switch (form) {
    case GRADH:
      dispatch_force<KERNEL, DIM, GRADH>();
      break;
    case GRADH_PRESSURE_ENERGY:
      dispatch_force<KERNEL, DIM, GRADH_PRESSURE_ENERGY>();
      break;
    case KMEAN:
      dispatch_force<KERNEL, DIM, KMEAN>();
      break;
    case HMEAN_GEOMETRIC:
      dispatch_force<KERNEL, DIM, HMEAN_GEOMETRIC>();
      break;
    case HMEAN_PRESSURE_ENERGY:
      dispatch_force<KERNEL, DIM, HMEAN_PRESSURE_ENERGY>();
      break;
    case KMEAN_GEOMETRIC:
      dispatch_force<KERNEL, DIM, KMEAN_GEOMETRIC>();
      break;
    default:
      dispatch_force<KERNEL, DIM, HMEAN>();
  }
  // drho_i/dt = sum_j m_j v_ij . grad_i W_ij (seed 004 eq. 33), integrated by fix sph/astro
  if (density_continuity_) {
    double *drhodt = atom->dvector[continuity_index_.drhodt];
    for (int i = 0; i < nlocal; i++) drhodt[i] = vdotgradw_[i];
  }
}

/* ----------------------------------------------------------------------
   curl v for the Balsara (1995) shear limiter and the Cullen-Dehnen switch, from this step's
   predicted velocities (seed 000):
     div v_i = -1/(Omega_i rho_i) sum_j m_j v_ij . grad_i W_ij
     curl v_i = 1/(Omega_i rho_i) sum_j m_j v_ij x grad_i W_ij      (Omega = 1 without GRADH)
     Balsara: f_i = |div v|_i / (|div v|_i + |curl v|_i + 0.0001 c_i / h_i)
   with W(h_i) (GRADH: the sums are taken in density_gradh's last evaluation, at the h it keeps,
   over the same full list; no pass of their own) or over the half list with W(h_ij) (HMEAN) or
   the averaged (W(h_i) + W(h_j))/2 (KMEAN: one neighbour loop and a reverse communication).
   Only when balsara is on or fix sph/astro/switch needs curl v. VSUMS_GRADIENT (keyword
   reconstruct): the same loop takes the sums M and G of grad v instead (velocity_gradient_finish
   derives the div and curl sums from G).
------------------------------------------------------------------------- */

template <class KERNEL, int DIM, int KFORM, int VSUMS> void PairSPHAstro::velocity_curl()
{
  using K = Kernel<KERNEL, DIM>;
  static_assert(KFORM == HMEAN || KFORM == KMEAN, "grad-h: the sums come from density_gradh");
  static_assert(VSUMS == VSUMS_CURL || VSUMS == VSUMS_GRADIENT, "a pass needs sums to take");
  constexpr bool KM = KFORM == KMEAN;
  constexpr bool GRADIENT = VSUMS == VSUMS_GRADIENT;
  constexpr int NS = GRADIENT ? VGRAD_SUMS : 4;
  double **sums = GRADIENT ? vgsum_ : dcurl_;
  double **x = atom->x;
  const int *type = atom->type;
  const double *rmass = atom->rmass;
  const double *mass = atom->mass;
  const double *h = atom->dvector[state_.h];
  double **vest = atom->darray[state_.vest];
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const int newton_pair = force->newton_pair;
  const double sigma = K::sigma();
  const double R2 = K::radius * K::radius;

  forward_predicted_velocities();

  const SPHAstro::NeighView nl = half_view();
  const int nzero = newton_pair ? nall : nlocal;
  for (int i = 0; i < nzero; i++)
    for (int k = 0; k < NS; k++) sums[i][k] = 0.0;
  for (int ii = 0; ii < nl.inum; ii++) {
    const int i = nl.ilist[ii];
    const double xi = x[i][0], yi = x[i][1], zi = x[i][2];
    const double hi = h[i];
    const double mi = rmass ? rmass[i] : mass[type[i]];
    const int *jlist = nl.firstneigh[i];
    const int jnum = nl.numneigh[i];
    double acc[NS];    // sum v.gradW, sum v x gradW; or the grad v sums M and G
    for (int k = 0; k < NS; k++) acc[k] = 0.0;
    for (int jj = 0; jj < jnum; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      const double dx = xi - x[j][0], dy = yi - x[j][1], dz = zi - x[j][2];
      const double r2 = dx * dx + dy * dy + dz * dz;
      double dw;    // (dW/dr) / r
      if (KM) {
        const double hj = h[j];
        const double hR2i = R2 * hi * hi, hR2j = R2 * hj * hj;
        if ((r2 >= hR2i && r2 >= hR2j) || r2 == 0.0) continue;
        const double r = std::sqrt(r2);
        const double hinvi = 1.0 / hi, hinvj = 1.0 / hj;
        const double dwi = r2 < hR2i ? inv_h_pow_dim<DIM>(hinvi) * hinvi * K::dw(r * hinvi) : 0.0;
        const double dwj = r2 < hR2j ? inv_h_pow_dim<DIM>(hinvj) * hinvj * K::dw(r * hinvj) : 0.0;
        dw = 0.5 * sigma * (dwi + dwj) / r;
      } else {
        const double hk = 0.5 * (hi + h[j]);
        if (r2 >= R2 * hk * hk || r2 == 0.0) continue;
        const double r = std::sqrt(r2);
        const double hinv = 1.0 / hk;
        dw = sigma * inv_h_pow_dim<DIM>(hinv) * hinv * K::dw(r * hinv) / r;
      }
      const double mj = rmass ? rmass[j] : mass[type[j]];
      const double dvx = vest[i][0] - vest[j][0], dvy = vest[i][1] - vest[j][1],
                   dvz = vest[i][2] - vest[j][2];
      if (GRADIENT) {
        // M and G take the same sign from both ends of the pair (sph_astro_reconstruction.h)
        velocity_gradient_add(acc, mj * dw, dvx, dvy, dvz, dx, dy, dz);
        if (newton_pair || j < nlocal)
          velocity_gradient_add(sums[j], mi * dw, dvx, dvy, dvz, dx, dy, dz);
        continue;
      }
      const double pair[4] = {(dvx * dx + dvy * dy + dvz * dz) * dw, (dvy * dz - dvz * dy) * dw,
                              (dvz * dx - dvx * dz) * dw, (dvx * dy - dvy * dx) * dw};
      for (int k = 0; k < 4; k++) acc[k] += mj * pair[k];
      // the same pair seen from j: v_ji . grad_j W_ji = v_ij . grad_i W_ij, likewise for x
      if (newton_pair || j < nlocal)
        for (int k = 0; k < 4; k++) sums[j][k] += mi * pair[k];
    }
    for (int k = 0; k < NS; k++) sums[i][k] += acc[k];
  }
  if (newton_pair) {
    comm_stage_ = GRADIENT ? Stage::VGRAD : Stage::CURL;
    comm->reverse_comm(this, NS);
  }
  if (!GRADIENT) velocity_curl_finish(false);
}

/* ----------------------------------------------------------------------
   reconstruction: per owned particle the symmetric part of grad v = G M^-1 and the spacing
   Delta = (m/rho)^(1/d) (sph_astro_reconstruction.h), sent to the ghosts with the density;
   where curl v is needed too, its sums and those of div v are the antisymmetric part and the
   trace of G (the same sums velocity_curl takes)
------------------------------------------------------------------------- */

template <int DIM> void PairSPHAstro::velocity_gradient_finish(bool gradh)
{
  const double *rho = eval_density();
  const int *type = atom->type;
  const double *rmass = atom->rmass;
  const double *mass = atom->mass;
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++) {
    const double *g = vgsum_[i];
    velocity_gradient_symmetric<DIM>(g, vgrad_[i]);    // 0 where M is singular
    const double mi = rmass ? rmass[i] : mass[type[i]];
    vgrad_[i][6] = recon_trigger_ * (DIM == 2 ? std::sqrt(mi / rho[i]) : std::cbrt(mi / rho[i]));
    if (curl_on_) {    // G[3 a + k] = sum_j w_j v_ij,a r_ij,k at sums index 6 + 3 a + k
      dcurl_[i][0] = g[6] + g[10] + g[14];
      dcurl_[i][1] = g[11] - g[13];
      dcurl_[i][2] = g[12] - g[8];
      dcurl_[i][3] = g[7] - g[9];
    }
  }
  if (curl_on_) velocity_curl_finish(gradh);
}

// div v, |curl v| and the Balsara factor of the owned particles from the sums in dcurl_
void PairSPHAstro::velocity_curl_finish(bool gradh)
{
  const double *rho = eval_density();
  const double *h = atom->dvector[state_.h];
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++) {
    const double norm = 1.0 / ((gradh ? omega_[i] : 1.0) * rho[i]);
    const double divv = -dcurl_[i][0] * norm;
    const double curlv = norm *
        std::sqrt(dcurl_[i][1] * dcurl_[i][1] + dcurl_[i][2] * dcurl_[i][2] +
                  dcurl_[i][3] * dcurl_[i][3]);
    curlv_[i] = curlv;
    if (balsara_on_) balsara_[i] = balsara_factor(divv, curlv, soundspeed_[i], h[i]);
  }
}

// the ghosts' predicted velocities of this step (curl v sums)
void PairSPHAstro::forward_predicted_velocities()
{
  comm_stage_ = Stage::VELOCITY;
  comm->forward_comm(this, 3);
}

template <class KERNEL> void PairSPHAstro::dispatch_dimension()
{
  if (domain->dimension == 2)
    dispatch_physics<KERNEL, 2>();
  else
    dispatch_physics<KERNEL, 3>();
}

/* ----------------------------------------------------------------------
   pruned lists (sph_astro_pruned_list.h), made when LAMMPS has just built its lists: the
   atoms sit where the build saw them, so a pair that comes within a kernel support before the
   next build is now closer than that support plus the skin. hprune_ = growth x h, at most
   the type's cap (fixed h: growth 1, h does not change during a run).
------------------------------------------------------------------------- */

void PairSPHAstro::prune_lists()
{
  double **x = atom->x;
  const int *type = atom->type;
  const double *h = atom->dvector[state_.h];
  const int nall = atom->nlocal + atom->nghost;
  const double growth = hmode_ == HMode::FIXED ? 1.0 : PRUNE_GROWTH;
  for (int i = 0; i < nall; i++) hprune_[i] = MIN(growth * h[i], hcap_type_[type[i]]);
  const double skin = neighbor->skin;
  const double R = kernel_radius_;
  const double *hl = hprune_;
  const SPHAstro::HalfFromFull half_rule = half_from_full();
  fallback_half_.clear();
  if (!listfull_ && nothing_to_prune()) {    // LAMMPS' half list is used as it is
    pruned_half_.clear();
    prune_lengths_[0] = prune_lengths_[1] = 0.0;
    return;
  }

  // one scan of LAMMPS' full list (grad-h) or half list: r_ij < R max(hl_i, hl_j) + skin for
  // the half list, r_ij < R hl_i + skin for the full list of the h iteration
  NeighList *src = listfull_ ? listfull_ : lammps_half_;
  begin_pruned(pruned_half_, src);
  if (listfull_) {
    begin_pruned(pruned_full_, src);
    // LAMMPS' half-from-full rule compares positions: taken now, at the build, for every entry
    const std::size_t entries = SPHAstro::list_entries(src);
    if (half_keep_.size() < entries) half_keep_.resize(entries + entries / 4);
  }
  std::size_t offset = 0;
  for (int ii = 0; ii < src->inum; ii++) {
    const int i = src->ilist[ii];
    const double xi = x[i][0], yi = x[i][1], zi = x[i][2];
    const double hli = hl[i];
    const double reach_full = R * hli + skin;
    const double reach_full2 = reach_full * reach_full;
    const int *jlist = src->firstneigh[i];
    const int jnum = src->numneigh[i];
    int *half = pruned_row(pruned_half_, i);
    int *full = listfull_ ? pruned_row(pruned_full_, i) : nullptr;
    int nhalf = 0, nfull = 0;
    // branch-free compaction: every entry is written at the next free place of its row and
    // kept by advancing the count (a row has room for neigh_modify one >= jnum entries)
    if (listfull_) {
      unsigned char *keep = half_keep_.data() + offset;
      for (int jj = 0; jj < jnum; jj++) {
        const int j = jlist[jj] & NEIGHMASK;
        const bool in_half = half_rule.keeps(x, i, j);
        keep[jj] = in_half;
        const double dx = xi - x[j][0], dy = yi - x[j][1], dz = zi - x[j][2];
        const double r2 = dx * dx + dy * dy + dz * dz;
        const double reach = R * MAX(hli, hl[j]) + skin;
        const bool within = r2 < reach * reach;    // reach >= reach_full
        half[nhalf] = jlist[jj];
        nhalf += in_half & within;
        full[nfull] = jlist[jj];
        nfull += within & (r2 < reach_full2);
      }
    } else {
      for (int jj = 0; jj < jnum; jj++) {
        const int j = jlist[jj] & NEIGHMASK;
        const double dx = xi - x[j][0], dy = yi - x[j][1], dz = zi - x[j][2];
        const double r2 = dx * dx + dy * dy + dz * dz;
        const double reach = R * MAX(hli, hl[j]) + skin;
        half[nhalf] = jlist[jj];
        nhalf += r2 < reach * reach;
      }
    }
    offset += jnum;
    pruned_half_.close(i, nhalf);
    if (listfull_) pruned_full_.close(i, nfull);
  }
  const double inum = MAX(src->inum, 1);
  prune_lengths_[0] = pruned_half_.entries() / inum;
  prune_lengths_[1] = listfull_ ? pruned_full_.entries() / inum : 0.0;
}

// whether the pruned half list would keep every entry of LAMMPS' half list: LAMMPS keeps the
// pairs of types (a, b) closer than its cutoff + skin, the pruned list those closer than
// R max(hl_i, hl_j) + skin, so nothing goes where R max(hl_a^min, hl_b^min) reaches the
// cutoff for every type pair (a gas of one h per type, fixed h: the benchmark box). Using
// LAMMPS' list then saves the scan and the memory; it gives the same sums either way (the
// entries outside every support add nothing), and LAMMPS' list holds for any h up to the cap.
bool PairSPHAstro::nothing_to_prune() const
{
  const int ntypes = atom->ntypes;
  const int nall = atom->nlocal + atom->nghost;
  const int *type = atom->type;
  std::vector<double> hlmin(ntypes + 1, INFINITY);
  for (int i = 0; i < nall; i++) hlmin[type[i]] = MIN(hlmin[type[i]], hprune_[i]);
  for (int a = 1; a <= ntypes; a++)
    for (int b = a; b <= ntypes; b++) {
      if (hlmin[a] == INFINITY || hlmin[b] == INFINITY) continue;    // no such atoms here
      const double reach = kernel_radius_ * MAX(hlmin[a], hlmin[b]);
      if (reach * reach < cutsq[a][b]) return false;
    }
  return true;
}

// a list made from the LAMMPS list src: rows of at most neigh_modify one entries, in LAMMPS'
// page size
void PairSPHAstro::begin_pruned(SPHAstro::PrunedList &list, const NeighList *src)
{
  if (!list.begin(src->inum, src->ilist, atom->nmax, neighbor->oneatom, neighbor->pgsize))
    error->one(FLERR,
               "pair_style sph/astro prune: cannot set up list pages (neigh_modify one {}, page "
               "{})",
               neighbor->oneatom, neighbor->pgsize);
}

int *PairSPHAstro::pruned_row(SPHAstro::PrunedList &list, int i)
{
  int *row = list.row(i);
  if (!row)
    error->one(FLERR,
               "pair_style sph/astro prune: out of memory for the pruned neighbour lists; use "
               "prune no");
  return row;
}

SPHAstro::HalfFromFull PairSPHAstro::half_from_full() const
{
  return {atom->nlocal, force->newton_pair != 0, domain->triclinic != 0, 0.01 * force->angstrom};
}

// LAMMPS' half list, or with prune yes in grad-h mode (no LAMMPS half list) the half list made
// from LAMMPS' full list by LAMMPS' own rule (decided at the build), when a pass first needs it
// after a build
SPHAstro::NeighView PairSPHAstro::unpruned_half_view()
{
  if (lammps_half_) return SPHAstro::view_of(lammps_half_);
  if (!pruned_half_.built())    // (a run's setup builds the lists, and they are pruned there)
    error->all(FLERR,
               "pair_style sph/astro prune yes: no neighbour list was built in this run's setup; "
               "run with pre yes after changing the pair style");
  if (!fallback_half_.built()) {
    // the entries LAMMPS' rule kept at the build (half_keep_, set by prune_lists)
    begin_pruned(fallback_half_, listfull_);
    std::size_t offset = 0;
    for (int ii = 0; ii < listfull_->inum; ii++) {
      const int i = listfull_->ilist[ii];
      const int *jlist = listfull_->firstneigh[i];
      const int jnum = listfull_->numneigh[i];
      int *half = pruned_row(fallback_half_, i);
      int n = 0;
      for (int jj = 0; jj < jnum; jj++)
        if (half_keep_[offset + jj]) half[n++] = jlist[jj];
      fallback_half_.close(i, n);
      offset += jnum;
    }
  }
  return fallback_half_.view();
}

SPHAstro::NeighView PairSPHAstro::half_view()
{
  if (!pruned_half_.built()) return unpruned_half_view();
  const double *h = atom->dvector[state_.h];
  const int nall = atom->nlocal + atom->nghost;
  for (int i = 0; i < nall; i++)
    if (h[i] > hprune_[i]) {
      prune_fallbacks_++;
      return unpruned_half_view();
    }
  return pruned_half_.view();
}

double PairSPHAstro::prune_limit(int i) const
{
  return pruned_half_.built() ? hprune_[i] : INFINITY;
}

void PairSPHAstro::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  grow_work_arrays();
  if (!prune_on_) {
    pruned_half_.clear();
    pruned_full_.clear();
  } else if (neighbor->ago == 0)
    prune_lists();    // LAMMPS has built its lists in this step (or this run's setup)
  alpha_atom_ = switch_ ? switch_->alpha() : nullptr;
  switch (kernel_) {
    case KernelType::CUBIC:
      dispatch_dimension<KernelCubic>();
      break;
    case KernelType::QUINTIC:
      dispatch_dimension<KernelQuintic>();
      break;
    case KernelType::WENDLAND_C2:
      dispatch_dimension<KernelWendlandC2>();
      break;
    case KernelType::WENDLAND_C4:
      dispatch_dimension<KernelWendlandC4>();
      break;
    case KernelType::GAUSSIAN:
      dispatch_dimension<KernelGaussian>();
      break;
  }
  if (cond_kappa_ > 0.0) conduction_pass();    // physical heat conduction, its own pass
  if (vflag_fdotr) virial_fdotr_compute();
  computed_step_ = update->ntimestep;
  computed_nlocal_ = atom->nlocal;
}

/* ---------------------------------------------------------------------- */

int PairSPHAstro::pack_forward_comm(int n, int *list, double *buf, int /*pbc_flag*/, int * /*pbc*/)
{
  const double *rho = eval_density();
  const double *h = atom->dvector[state_.h];
  double **vest = atom->darray[state_.vest];
  int m = 0;
  if (comm_stage_ == Stage::SMOOTHING_LENGTH) {
    for (int k = 0; k < n; k++) buf[m++] = h[list[k]];
    return m;
  }
  if (comm_stage_ == Stage::ENERGY) {
    const double *uest = atom->dvector[state_.uest];
    for (int k = 0; k < n; k++) buf[m++] = uest[list[k]];
    return m;
  }
  if (comm_stage_ == Stage::VELOCITY) {
    for (int k = 0; k < n; k++) {
      buf[m++] = vest[list[k]][0];
      buf[m++] = vest[list[k]][1];
      buf[m++] = vest[list[k]][2];
    }
    return m;
  }
  const bool gradh = hmode_ == HMode::GRADH;
  const bool cond = ghosts_need_u();
  const bool recon = reconstruction();
  const double *uest = atom->dvector[state_.uest];
  for (int k = 0; k < n; k++) {
    const int j = list[k];
    buf[m++] = rho[j];
    buf[m++] = pressure_[j];
    buf[m++] = soundspeed_[j];
    buf[m++] = vest[j][0];
    buf[m++] = vest[j][1];
    buf[m++] = vest[j][2];
    if (gradh) {
      buf[m++] = h[j];
      buf[m++] = omega_[j];
      if (pressure_energy_) buf[m++] = pe_gradh_[j];
    }
    if (alpha_atom_) buf[m++] = alpha_atom_[j];
    if (cond) buf[m++] = uest[j];
    if (balsara_on_) buf[m++] = balsara_[j];
    if (recon)
      for (int c = 0; c < VGRAD_DATA; c++) buf[m++] = vgrad_[j][c];
  }
  return m;
}

void PairSPHAstro::unpack_forward_comm(int n, int first, double *buf)
{
  double *rho = eval_density();
  double *h = atom->dvector[state_.h];
  double **vest = atom->darray[state_.vest];
  int m = 0;
  if (comm_stage_ == Stage::SMOOTHING_LENGTH) {
    for (int i = first; i < first + n; i++) h[i] = buf[m++];
    return;
  }
  if (comm_stage_ == Stage::ENERGY) {
    double *uest = atom->dvector[state_.uest];
    for (int i = first; i < first + n; i++) uest[i] = buf[m++];
    return;
  }
  if (comm_stage_ == Stage::VELOCITY) {
    for (int i = first; i < first + n; i++) {
      vest[i][0] = buf[m++];
      vest[i][1] = buf[m++];
      vest[i][2] = buf[m++];
    }
    return;
  }
  const bool gradh = hmode_ == HMode::GRADH;
  const bool cond = ghosts_need_u();
  const bool recon = reconstruction();
  double *uest = atom->dvector[state_.uest];
  for (int i = first; i < first + n; i++) {
    rho[i] = buf[m++];
    pressure_[i] = buf[m++];
    soundspeed_[i] = buf[m++];
    vest[i][0] = buf[m++];
    vest[i][1] = buf[m++];
    vest[i][2] = buf[m++];
    if (gradh) {
      h[i] = buf[m++];
      omega_[i] = buf[m++];
      if (pressure_energy_) pe_gradh_[i] = buf[m++];
    }
    if (alpha_atom_) alpha_atom_[i] = buf[m++];
    if (cond) uest[i] = buf[m++];
    if (balsara_on_) balsara_[i] = buf[m++];
    if (recon)
      for (int c = 0; c < VGRAD_DATA; c++) vgrad_[i][c] = buf[m++];
  }
}

int PairSPHAstro::pack_reverse_comm(int n, int first, double *buf)
{
  int m = 0;
  if (comm_stage_ == Stage::CONDUCTION) {
    for (int i = first; i < first + n; i++) buf[m++] = conduct_[i];
    return m;
  }
  if (comm_stage_ == Stage::CURL) {
    for (int i = first; i < first + n; i++)
      for (int k = 0; k < 4; k++) buf[m++] = dcurl_[i][k];
    return m;
  }
  if (comm_stage_ == Stage::VGRAD) {
    for (int i = first; i < first + n; i++)
      for (int k = 0; k < VGRAD_SUMS; k++) buf[m++] = vgsum_[i][k];
    return m;
  }
  if (comm_stage_ == Stage::COUNT) {
    for (int i = first; i < first + n; i++) buf[m++] = nneigh_[i];
    return m;
  }
  if (comm_stage_ == Stage::DENSITY) {
    const double *rho = atom->dvector[state_.rho];
    for (int i = first; i < first + n; i++) {
      buf[m++] = rho[i];
      buf[m++] = nneigh_[i];
    }
  } else {
    const double *dudt = atom->dvector[state_.dudt];
    const bool vsig = signal_viscosity();
    const bool cond = artificial_conductivity();
    for (int i = first; i < first + n; i++) {
      buf[m++] = dudt[i];
      buf[m++] = vdotgradw_[i];
      if (vsig) buf[m++] = vsigmax_[i];
      if (cond) buf[m++] = condrate_[i];
    }
  }
  return m;
}

void PairSPHAstro::unpack_reverse_comm(int n, int *list, double *buf)
{
  int m = 0;
  if (comm_stage_ == Stage::CONDUCTION) {
    for (int k = 0; k < n; k++) conduct_[list[k]] += buf[m++];
    return;
  }
  if (comm_stage_ == Stage::CURL) {
    for (int k = 0; k < n; k++)
      for (int c = 0; c < 4; c++) dcurl_[list[k]][c] += buf[m++];
    return;
  }
  if (comm_stage_ == Stage::VGRAD) {
    for (int k = 0; k < n; k++)
      for (int c = 0; c < VGRAD_SUMS; c++) vgsum_[list[k]][c] += buf[m++];
    return;
  }
  if (comm_stage_ == Stage::COUNT) {
    for (int k = 0; k < n; k++) nneigh_[list[k]] += buf[m++];
    return;
  }
  if (comm_stage_ == Stage::DENSITY) {
    double *rho = atom->dvector[state_.rho];
    for (int k = 0; k < n; k++) {
      const int j = list[k];
      rho[j] += buf[m++];
      nneigh_[j] += buf[m++];
    }
  } else {
    double *dudt = atom->dvector[state_.dudt];
    const bool vsig = signal_viscosity();
    const bool cond = artificial_conductivity();
    for (int k = 0; k < n; k++) {
      const int j = list[k];
      dudt[j] += buf[m++];
      vdotgradw_[j] += buf[m++];
      if (vsig) {
        vsigmax_[j] = MAX(vsigmax_[j], buf[m]);
        m++;
      }
      if (cond) condrate_[j] += buf[m++];
    }
  }
}

/* ---------------------------------------------------------------------- */

void PairSPHAstro::write_restart(FILE *fp)
{
  write_restart_settings(fp);
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) fwrite(&setflag[i][j], sizeof(int), 1, fp);
}

void PairSPHAstro::read_restart(FILE *fp)
{
  read_restart_settings(fp);
  allocate();
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      if (comm->me == 0) utils::sfread(FLERR, &setflag[i][j], sizeof(int), 1, fp, nullptr, error);
      MPI_Bcast(&setflag[i][j], 1, MPI_INT, 0, world);
    }
}

void PairSPHAstro::write_restart_settings(FILE *fp)
{
  int ival[3] = {static_cast<int>(kernel_), static_cast<int>(eos_.type),
                 (visc_on_ ? 1 : 0) + (balsara_on_ ? 2 : 0) + (visc_signal_ ? 4 : 0) +
                     (recon_on_ ? 8 : 0)};
  double dval[7] = {eos_.gamma, eos_.cs, eos_.K, visc_alpha_, visc_beta_, visc_eps_, cond_alpha_};
  fwrite(ival, sizeof(int), 3, fp);
  fwrite(dval, sizeof(double), 7, fp);
  fwrite(&cond_kappa_, sizeof(double), 1, fp);    // physical heat conduction
  // the seeds' other choices: density continuity, symmetrise kernel, pressure geometric
  // 8: prune no (restart files from before the keyword read as prune yes); 16: formulation
  // pressure-energy (older files: density-energy)
  const int options = (density_continuity_ ? 1 : 0) + (symmetrise_kernel_ ? 2 : 0) +
      (pressure_geometric_ ? 4 : 0) + (prune_on_ ? 0 : 8) + (pressure_energy_ ? 16 : 0);
  fwrite(&options, sizeof(int), 1, fp);
  fwrite(&recon_trigger_, sizeof(double), 1, fp);
  fwrite(&recon_gate_, sizeof(int), 1, fp);
}

void PairSPHAstro::read_restart_settings(FILE *fp)
{
  int ival[3], options = 0;
  double dval[7];
  if (comm->me == 0) {
    utils::sfread(FLERR, ival, sizeof(int), 3, fp, nullptr, error);
    utils::sfread(FLERR, dval, sizeof(double), 7, fp, nullptr, error);
    utils::sfread(FLERR, &cond_kappa_, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &options, sizeof(int), 1, fp, nullptr, error);
    utils::sfread(FLERR, &recon_trigger_, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &recon_gate_, sizeof(int), 1, fp, nullptr, error);
  }
  MPI_Bcast(&recon_trigger_, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&recon_gate_, 1, MPI_INT, 0, world);
  MPI_Bcast(&cond_kappa_, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&options, 1, MPI_INT, 0, world);
  density_continuity_ = (options & 1) != 0;
  symmetrise_kernel_ = (options & 2) != 0;
  pressure_geometric_ = (options & 4) != 0;
  prune_on_ = (options & 8) == 0;
  pressure_energy_ = (options & 16) != 0;
  MPI_Bcast(ival, 3, MPI_INT, 0, world);
  MPI_Bcast(dval, 7, MPI_DOUBLE, 0, world);
  kernel_ = static_cast<KernelType>(ival[0]);
  eos_.type = static_cast<EOSType>(ival[1]);
  visc_on_ = (ival[2] & 1) != 0;
  balsara_on_ = (ival[2] & 2) != 0;
  visc_signal_ = (ival[2] & 4) != 0;
  recon_on_ = (ival[2] & 8) != 0;
  eos_.gamma = dval[0];
  eos_.cs = dval[1];
  eos_.K = dval[2];
  visc_alpha_ = dval[3];
  visc_beta_ = dval[4];
  visc_eps_ = dval[5];
  cond_alpha_ = dval[6];
  kernel_radius_ = SPHAstro::kernel_radius(kernel_);
}

/* ----------------------------------------------------------------------
   h collections: with neighbor multi and interval collections (set up by fix sph/astro/h
   collections, or neigh_modify collection/interval), LAMMPS bins every atom, owned or
   ghost, into the collection whose upper cutoff covers atom2cut(i), and searches collection
   pairs (a, b) out to radii2cut(cut_a/2, cut_b/2) + skin. Small-h particles then only scan
   stencils sized for small h, however large h is elsewhere; the per-type cutoff stays an
   upper bound. The pair kernels reach R max(h_i, h_j) (grad-h or symmetrise kernel: W(h_i),
   W(h_j)) or
   R (h_i + h_j)/2 (mean h_ij), R the kernel radius.
------------------------------------------------------------------------- */

double PairSPHAstro::atom2cut(int i)
{
  // the lists of a run's setup allow every h up to its type's cap: the setup's h iteration
  // may move h far from the start value; fix sph/astro/h has the lists rebuilt at step 1
  const double cap = hcap_type_[atom->type[i]];
  if (update->setupflag) return kernel_radius_ * cap;
  return kernel_radius_ * MIN(atom->dvector[state_.h][i] * COLLECTION_GROWTH, cap);
}

double PairSPHAstro::radii2cut(double ri, double rj)
{
  return (hmode_ == HMode::GRADH || symmetrise_kernel_) ? 2.0 * MAX(ri, rj) : ri + rj;
}

double PairSPHAstro::h_limit(int i) const
{
  const double cap = hcap_type_[atom->type[i]];
  if (neighbor->style != Neighbor::MULTI || !neighbor->finite_cut_flag || !neighbor->collection)
    return cap;
  return MIN(cap, neighbor->collection2cut[neighbor->collection[i]] / kernel_radius_);
}

/* ---------------------------------------------------------------------- */

void *PairSPHAstro::extract(const char *name, int &dim)
{
  dim = 0;
  if (strcmp(name, "kernel_radius") == 0) return (void *) &kernel_radius_;
  if (strcmp(name, "alpha") == 0) return (void *) &visc_alpha_;
  if (strcmp(name, "beta") == 0) return (void *) &visc_beta_;
  // entries per atom of this rank's latest pruned half and full lists (0: none)
  if (strcmp(name, "pruned_list_lengths") == 0) {
    dim = 1;
    return (void *) prune_lengths_;
  }
  return nullptr;
}

void *PairSPHAstro::extract_peratom(const char *name, int &ncol)
{
  ncol = 0;
  if (strcmp(name, "pressure") == 0) return (void *) pressure_;
  if (strcmp(name, "soundspeed") == 0) return (void *) soundspeed_;
  if (strcmp(name, "divv") == 0) return (void *) divv_;
  // current unless density continuity skipped the summation (see neighbour_counts())
  if (strcmp(name, "nneigh") == 0)
    return counts_step_ == computed_step_ ? (void *) nneigh_ : nullptr;
  if (strcmp(name, "omega") == 0) return (void *) omega_;
  if (strcmp(name, "curlv") == 0) return (void *) (curl_on_ ? curlv_ : nullptr);
  if (strcmp(name, "vsigmax") == 0) return (void *) (signal_viscosity() ? vsigmax_ : nullptr);
  if (strcmp(name, "balsara") == 0) return (void *) (balsara_on_ ? balsara_ : nullptr);
  if (strcmp(name, "condrate") == 0)
    return (void *) (artificial_conductivity() ? condrate_ : nullptr);
  // reconstruction: symmetric grad v (xx, yy, zz, xy, xz, yz) and the spacing Delta per atom
  if (strcmp(name, "vgrad") == 0) {
    ncol = VGRAD_DATA;
    return reconstruction() ? (void *) vgrad_ : nullptr;
  }
  // non-null when omega_ holds grad-h factors (variable h by iteration)
  if (strcmp(name, "omega_valid") == 0) return hmode_ == HMode::GRADH ? (void *) omega_ : nullptr;
  return nullptr;
}

double PairSPHAstro::memory_usage()
{
  return (6.0 + (pgeo_ ? 1.0 : 0.0) + (hprune_ ? 1.0 : 0.0) +
          (vgrad_ ? VGRAD_SUMS + VGRAD_DATA : 0)) *
      nmax_ * sizeof(double) +
      conduct_nmax_ * sizeof(double) + pruned_half_.memory_usage() + pruned_full_.memory_usage() +
      fallback_half_.memory_usage() + half_keep_.capacity() + Pair::memory_usage();
}
