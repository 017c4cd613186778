/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The keywords of pair_style sph/astro, each with its default in one place: parsed from the
// pair_style arguments, checked for consistency among themselves, written to and read from
// restart files. Checks that need the fixes (h mode, thermal variable, switch) are in
// PairSPHAstro::init_style().

#ifndef LMP_SPH_ASTRO_OPTIONS_H
#define LMP_SPH_ASTRO_OPTIONS_H

#include "sph_astro_eos.h"
#include "sph_astro_kernel.h"

#include <cstdio>

namespace LAMMPS_NS {
class LAMMPS;
}

namespace SPHAstro {

enum class ViscosityForm { NONE, CLASSIC, SIGNAL };

struct PairOptions {
  KernelType kernel = KernelType::CUBIC;
  EOS eos;
  // artificial viscosity: classic (Monaghan 1992) or signal velocity (Monaghan 1997)
  ViscosityForm viscosity = ViscosityForm::CLASSIC;
  double alpha = 1.0, beta = 2.0;
  double epsilon = 0.01;              // eps in mu_ij = h v.r / (r^2 + eps h^2)
  bool balsara = false;               // Balsara (1995) shear limiter
  bool reconstruct = false;           // viscosity on velocities reconstructed to the pair midpoint
  double recon_trigger = 1.0;         // noise trigger radius in particle spacings
  int recon_gate = 16;                // smoothness gate exponent (0: off)
  double conductivity = 0.0;          // artificial conductivity alpha_u (Price 2008; 0: off)
  double conduction = 0.0;            // physical heat conduction kappa = k / c_v (0: off)
  bool density_continuity = false;    // rho integrated by fix sph/astro instead of summed
  bool symmetrise_kernel = false;     // (W(h_i) + W(h_j))/2 instead of W(h_ij)
  bool pressure_geometric = false;    // 2 sqrt(P_i P_j)/(rho_i rho_j)
  bool pressure_energy = false;       // formulation pressure-energy (Hopkins 2013)
  // set by fix sph/astro vsig pairs, not by pair_style: the Courant criterion takes
  // max_j v_sig,ij also with classic or no viscosity
  bool courant_pairs = false;

  // parse pair_style arguments (a repeated pair_style starts from the defaults); errors name
  // the keyword, the value and what is allowed
  void parse(LAMMPS_NS::LAMMPS *lmp, int narg, char **arg);
  // errors (and warnings) for options that do not fit the rest of the scheme
  void check_scheme(LAMMPS_NS::LAMMPS *lmp, bool gradh, bool entropy, bool has_switch) const;
  // variable_h: the writing run had fix sph/astro/h (returned by read_restart)
  void write_restart(FILE *fp, bool variable_h) const;
  // rank 0 reads, every rank receives
  bool read_restart(LAMMPS_NS::LAMMPS *lmp, FILE *fp);

  bool has_viscosity() const { return viscosity != ViscosityForm::NONE; }
  bool signal_viscosity() const { return viscosity == ViscosityForm::SIGNAL; }
  // max_j v_sig,ij = max_j (c_i + c_j - beta w_ij) kept per particle, with the beta of the
  // signal viscosity, else 3 (Springel 2005, MNRAS 364, 1105, eqs. 13 and 16)
  bool tracks_signal() const { return signal_viscosity() || courant_pairs; }
  double signal_beta() const { return signal_viscosity() ? beta : 3.0; }
  bool reconstruction() const { return has_viscosity() && reconstruct; }
  // the artificial conductivity acts only where u is evolved (ideal gas)
  bool artificial_conductivity() const { return conductivity > 0.0 && eos.uses_energy(); }
  bool physical_conduction() const { return conduction > 0.0; }
  double kernel_radius() const { return SPHAstro::kernel_radius(kernel); }
  double beta_factor() const { return alpha > 0.0 ? beta / alpha : 0.0; }
};

}    // namespace SPHAstro

#endif
