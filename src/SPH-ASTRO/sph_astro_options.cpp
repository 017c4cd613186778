/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

#include "sph_astro_options.h"

#include "comm.h"
#include "error.h"
#include "lammps.h"
#include "utils.h"

#include <cmath>
#include <cstring>
#include <string>

using namespace LAMMPS_NS;

namespace SPHAstro {

/* ----------------------------------------------------------------------
   pair_style sph/astro [kernel NAME] [eos ideal GAMMA | isothermal CS | polytropic K GAMMA |
                                              barotropic CS RHOCRIT GAMMA]
                        [viscosity classic ALPHA BETA | signal ALPHA [BETA] | none]
                        [balsara yes|no] [reconstruct yes|no [trigger T] [gate P]]
                        [conductivity ALPHA_U] [conduction KAPPA] [epsilon EPS]
                        [density summation|continuity] [symmetrise hmean|kernel]
                        [pressure standard|geometric]
                        [formulation density-energy|pressure-energy]
------------------------------------------------------------------------- */

void PairOptions::parse(LAMMPS *lmp, int narg, char **arg)
{
  Error *error = lmp->error;
  *this = PairOptions();
  auto choice = [&](const std::string &key, const char *value, const char *no, const char *yes) {
    if (strcmp(value, no) == 0) return false;
    if (strcmp(value, yes) == 0) return true;
    error->all(FLERR, "pair_style sph/astro: unknown {} '{}'; allowed: {}, {}", key, value, no,
               yes);
    return false;
  };
  int iarg = 0;
  while (iarg < narg) {
    const std::string key = arg[iarg];
    const auto need = [&](int n, const std::string &what) {
      if (iarg + n > narg) utils::missing_cmd_args(FLERR, "pair_style sph/astro " + what, error);
    };
    if (key == "kernel") {
      need(2, key);
      if (!kernel_from_name(arg[iarg + 1], kernel))
        error->all(FLERR,
                   "pair_style sph/astro: unknown kernel '{}'; allowed: m4 (cubic), m6 "
                   "(quintic), wendland/c2, wendland/c4, gaussian",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (key == "eos") {
      need(2, key);
      const std::string model = arg[iarg + 1];
      if (model == "ideal") {
        need(3, "eos ideal");
        eos.type = EOSType::IDEAL;
        eos.gamma = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
        if (!(eos.gamma > 1.0))
          error->all(FLERR, "pair_style sph/astro eos ideal: gamma = {} must be > 1",
                     arg[iarg + 2]);
        iarg += 3;
      } else if (model == "isothermal") {
        need(3, "eos isothermal");
        eos.type = EOSType::ISOTHERMAL;
        eos.cs = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
        if (!(eos.cs > 0.0))
          error->all(FLERR, "pair_style sph/astro eos isothermal: sound speed {} must be > 0",
                     arg[iarg + 2]);
        iarg += 3;
      } else if (model == "polytropic") {
        need(4, "eos polytropic");
        eos.type = EOSType::POLYTROPIC;
        eos.K = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
        eos.gamma = utils::numeric(FLERR, arg[iarg + 3], false, lmp);
        if (!(eos.K > 0.0))
          error->all(FLERR, "pair_style sph/astro eos polytropic: K = {} must be > 0",
                     arg[iarg + 2]);
        if (!(eos.gamma > 1.0))
          error->all(FLERR, "pair_style sph/astro eos polytropic: gamma = {} must be > 1",
                     arg[iarg + 3]);
        iarg += 4;
      } else if (model == "barotropic") {
        // P = c_s^2 rho [1 + (rho/rho_crit)^(gamma-1)] (sph_astro_eos.h)
        need(5, "eos barotropic");
        eos.type = EOSType::BAROTROPIC;
        eos.cs = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
        eos.rho_crit = utils::numeric(FLERR, arg[iarg + 3], false, lmp);
        eos.gamma = utils::numeric(FLERR, arg[iarg + 4], false, lmp);
        if (!(eos.cs > 0.0) || !std::isfinite(eos.cs))
          error->all(FLERR,
                     "pair_style sph/astro eos barotropic: sound speed {} must be finite and > 0",
                     arg[iarg + 2]);
        if (!(eos.rho_crit > 0.0) || !std::isfinite(eos.rho_crit))
          error->all(FLERR,
                     "pair_style sph/astro eos barotropic: critical density {} must be finite and "
                     "> 0",
                     arg[iarg + 3]);
        if (!(eos.gamma > 1.0) || !std::isfinite(eos.gamma))
          error->all(FLERR,
                     "pair_style sph/astro eos barotropic: gamma = {} must be finite and > 1 (the "
                     "adiabatic exponent above the critical density, e.g. 1.4)",
                     arg[iarg + 4]);
        iarg += 5;
      } else
        error->all(FLERR,
                   "pair_style sph/astro: unknown eos '{}'; allowed: ideal GAMMA, isothermal CS, "
                   "polytropic K GAMMA, barotropic CS RHOCRIT GAMMA",
                   model);
    } else if (key == "viscosity") {
      need(2, key);
      const std::string form = arg[iarg + 1];
      if (form == "none") {
        viscosity = ViscosityForm::NONE;
        alpha = beta = 0.0;
        iarg += 2;
      } else if (form == "classic") {
        need(4, "viscosity classic");
        alpha = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
        beta = utils::numeric(FLERR, arg[iarg + 3], false, lmp);
        if (alpha < 0.0 || beta < 0.0)
          error->all(FLERR,
                     "pair_style sph/astro viscosity classic: alpha = {} and beta = {} must be "
                     ">= 0",
                     arg[iarg + 2], arg[iarg + 3]);
        viscosity = (alpha > 0.0 || beta > 0.0) ? ViscosityForm::CLASSIC : ViscosityForm::NONE;
        iarg += 4;
      } else if (form == "signal") {
        // viscosity signal ALPHA [BETA]: BETA (default 3) is a number only if one follows
        need(3, "viscosity signal");
        alpha = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
        beta = 3.0;
        iarg += 3;
        if (iarg < narg && utils::is_double(arg[iarg])) {
          beta = utils::numeric(FLERR, arg[iarg], false, lmp);
          iarg++;
        }
        if (!(alpha > 0.0) || beta < 0.0)
          error->all(FLERR,
                     "pair_style sph/astro viscosity signal: alpha = {} must be > 0 and beta = "
                     "{} >= 0",
                     alpha, beta);
        viscosity = ViscosityForm::SIGNAL;
      } else
        error->all(FLERR,
                   "pair_style sph/astro: unknown viscosity '{}'; allowed: classic ALPHA BETA, "
                   "signal ALPHA [BETA], none",
                   form);
    } else if (key == "balsara") {
      need(2, key);
      balsara = utils::logical(FLERR, arg[iarg + 1], false, lmp) == 1;
      iarg += 2;
    } else if (key == "reconstruct") {
      need(2, key);
      reconstruct = utils::logical(FLERR, arg[iarg + 1], false, lmp) == 1;
      iarg += 2;
      // optional: trigger T (noise trigger radius, spacings), gate P (smoothness gate)
      while (iarg < narg && (strcmp(arg[iarg], "trigger") == 0 || strcmp(arg[iarg], "gate") == 0)) {
        const std::string sub = arg[iarg];
        need(2, "reconstruct " + sub);
        if (sub == "trigger") {
          recon_trigger = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
          if (!(recon_trigger >= 0.0) || !std::isfinite(recon_trigger))
            error->all(FLERR,
                       "pair_style sph/astro reconstruct trigger {} must be >= 0 (pairs closer "
                       "than this many particle spacings get the plain viscosity back; 0: never)",
                       arg[iarg + 1]);
        } else {
          recon_gate = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
          if (recon_gate < 0 || recon_gate > 64)
            error->all(FLERR,
                       "pair_style sph/astro reconstruct gate {} must be an integer in 0-64 (the "
                       "exponent of the smoothness gate; 0: off, default 16)",
                       arg[iarg + 1]);
        }
        iarg += 2;
      }
    } else if (key == "conductivity") {
      need(2, key);
      conductivity = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (conductivity < 0.0)
        error->all(FLERR, "pair_style sph/astro: conductivity alpha_u = {} must be >= 0",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (key == "conduction") {
      need(2, key);
      conduction = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(conduction >= 0.0) || !std::isfinite(conduction))
        error->all(FLERR,
                   "pair_style sph/astro: conduction kappa = {} must be finite and >= 0 (0: no "
                   "heat conduction)",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (key == "epsilon") {
      need(2, key);
      epsilon = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(epsilon > 0.0))
        error->all(FLERR, "pair_style sph/astro: epsilon = {} must be > 0", arg[iarg + 1]);
      iarg += 2;
    } else if (key == "density") {
      need(2, key);
      density_continuity = choice(key, arg[iarg + 1], "summation", "continuity");
      iarg += 2;
    } else if (key == "symmetrise") {
      need(2, key);
      symmetrise_kernel = choice(key, arg[iarg + 1], "hmean", "kernel");
      iarg += 2;
    } else if (key == "pressure") {
      need(2, key);
      pressure_geometric = choice(key, arg[iarg + 1], "standard", "geometric");
      iarg += 2;
    } else if (key == "formulation") {
      need(2, key);
      pressure_energy = choice(key, arg[iarg + 1], "density-energy", "pressure-energy");
      iarg += 2;
    } else
      error->all(FLERR,
                 "pair_style sph/astro: unknown keyword '{}'; allowed: kernel, eos, viscosity, "
                 "balsara, reconstruct, conductivity, conduction, epsilon, density, symmetrise, "
                 "pressure, formulation",
                 key);
  }
  if (balsara && !has_viscosity())
    error->all(FLERR, "pair_style sph/astro: balsara yes needs viscosity classic or signal");
  if (reconstruct && !has_viscosity())
    error->all(FLERR, "pair_style sph/astro: reconstruct yes needs viscosity classic or signal");
  if (reconstruct && balsara)
    error->all(FLERR,
               "pair_style sph/astro: reconstruct yes and balsara yes cannot be combined (the "
               "reconstruction removes the viscosity of a linear shear flow already); use one");
}

// the options against the rest of the scheme: h iterated with grad-h terms, the thermal variable
// entropy, a viscosity switch
void PairOptions::check_scheme(LAMMPS *lmp, bool gradh, bool entropy, bool has_switch) const
{
  Error *error = lmp->error;
  const char *eos_name = eos.type == EOSType::ISOTHERMAL ? "isothermal"
      : eos.type == EOSType::BAROTROPIC                  ? "barotropic"
                                                         : "polytropic";
  if (conductivity > 0.0 && !eos.uses_energy() && lmp->comm->me == 0)
    error->warning(FLERR,
                   "pair_style sph/astro: conductivity {} has no effect with eos {} (only the "
                   "ideal gas evolves u)",
                   conductivity, eos_name);
  if (conduction > 0.0 && !eos.uses_energy())
    error->all(FLERR,
               "pair_style sph/astro: conduction {} needs eos ideal (the energy equation); eos {} "
               "does not evolve u",
               conduction, eos_name);

  if (has_switch && !(has_viscosity() && alpha > 0.0))
    error->all(FLERR,
               "fix sph/astro/switch needs pair_style sph/astro viscosity classic or signal with "
               "alpha > 0 (classic: beta scales with the particle's alpha as beta/alpha)");

  // the alternatives of the fixed-h equations; with grad-h terms the density, its kernels and
  // the pressure term follow from the h-rho relation
  if (gradh) {
    if (density_continuity)
      error->all(FLERR,
                 "pair_style sph/astro density continuity needs fixed h or fix sph/astro/h dhdt: "
                 "with fix sph/astro/h iterate h follows from the summed density");
    if (symmetrise_kernel)
      error->all(FLERR,
                 "pair_style sph/astro symmetrise kernel needs fixed h or fix sph/astro/h dhdt: "
                 "with fix sph/astro/h iterate the grad-h equations use W(h_i) and W(h_j) "
                 "already");
    if (pressure_geometric)
      error->all(FLERR,
                 "pair_style sph/astro pressure geometric needs fixed h or fix sph/astro/h dhdt: "
                 "the grad-h equations (fix sph/astro/h iterate) have their own pressure term");
  }
  if (pressure_geometric && entropy)
    error->all(FLERR,
               "pair_style sph/astro pressure geometric needs fix sph/astro thermal energy: with "
               "thermal entropy the P dV work is P_i/rho_i^2 drho_i/dt, which does not match the "
               "geometric-mean force");
  if (pressure_energy) {
    const char *what = nullptr;
    if (eos.type != EOSType::IDEAL)
      what = "eos ideal (the smoothed pressure is (gamma-1) sum_j m_j u_j W_ij)";
    else if (entropy)
      what = "fix sph/astro thermal energy (it evolves u; thermal entropy is not supported)";
    else if (density_continuity)
      what = "density summation (its density follows from the smoothed pressure)";
    else if (symmetrise_kernel)
      what = "symmetrise hmean";
    else if (pressure_geometric)
      what = "pressure standard (it has a pressure term of its own)";
    if (what) error->all(FLERR, "pair_style sph/astro formulation pressure-energy needs {}", what);
  }
}

// layout: 3 ints (kernel, eos, viscosity bits), 7 doubles, kappa, option bits (8: variable h),
// trigger, gate; the third double is K, or rho_crit of eos barotropic (which has no K)
void PairOptions::write_restart(FILE *fp, bool variable_h) const
{
  const int ival[3] = {static_cast<int>(kernel), static_cast<int>(eos.type),
                       (has_viscosity() ? 1 : 0) + (balsara ? 2 : 0) +
                           (signal_viscosity() ? 4 : 0) + (reconstruct ? 8 : 0)};
  const double third = eos.type == EOSType::BAROTROPIC ? eos.rho_crit : eos.K;
  const double dval[7] = {eos.gamma, eos.cs, third, alpha, beta, epsilon, conductivity};
  fwrite(ival, sizeof(int), 3, fp);
  fwrite(dval, sizeof(double), 7, fp);
  fwrite(&conduction, sizeof(double), 1, fp);
  const int options = (density_continuity ? 1 : 0) + (symmetrise_kernel ? 2 : 0) +
      (pressure_geometric ? 4 : 0) + (variable_h ? 8 : 0) + (pressure_energy ? 16 : 0);
  fwrite(&options, sizeof(int), 1, fp);
  fwrite(&recon_trigger, sizeof(double), 1, fp);
  fwrite(&recon_gate, sizeof(int), 1, fp);
}

bool PairOptions::read_restart(LAMMPS *lmp, FILE *fp)
{
  int ival[3] = {0, 0, 0}, options = 0, gate = 16;
  double dval[7] = {}, kappa = 0.0, trigger = 1.0;
  if (lmp->comm->me == 0) {
    Error *error = lmp->error;
    utils::sfread(FLERR, ival, sizeof(int), 3, fp, nullptr, error);
    utils::sfread(FLERR, dval, sizeof(double), 7, fp, nullptr, error);
    utils::sfread(FLERR, &kappa, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &options, sizeof(int), 1, fp, nullptr, error);
    utils::sfread(FLERR, &trigger, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &gate, sizeof(int), 1, fp, nullptr, error);
  }
  MPI_Comm world = lmp->world;
  MPI_Bcast(ival, 3, MPI_INT, 0, world);
  MPI_Bcast(dval, 7, MPI_DOUBLE, 0, world);
  MPI_Bcast(&kappa, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&options, 1, MPI_INT, 0, world);
  MPI_Bcast(&trigger, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&gate, 1, MPI_INT, 0, world);
  *this = PairOptions();
  kernel = static_cast<KernelType>(ival[0]);
  eos.type = static_cast<EOSType>(ival[1]);
  viscosity = !(ival[2] & 1) ? ViscosityForm::NONE
      : (ival[2] & 4)        ? ViscosityForm::SIGNAL
                             : ViscosityForm::CLASSIC;
  balsara = (ival[2] & 2) != 0;
  reconstruct = (ival[2] & 8) != 0;
  eos.gamma = dval[0];
  eos.cs = dval[1];
  if (eos.type == EOSType::BAROTROPIC)
    eos.rho_crit = dval[2];
  else
    eos.K = dval[2];
  alpha = dval[3];
  beta = dval[4];
  epsilon = dval[5];
  conductivity = dval[6];
  conduction = kappa;
  density_continuity = (options & 1) != 0;
  symmetrise_kernel = (options & 2) != 0;
  pressure_geometric = (options & 4) != 0;
  pressure_energy = (options & 16) != 0;
  recon_trigger = trigger;
  recon_gate = gate;
  return (options & 8) != 0;
}

}    // namespace SPHAstro
