/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: equations of state
------------------------------------------------------------------------- */

// Pressure P(rho, u) and sound speed c_s for the gas models of the package.
//   ideal:      P = (gamma - 1) rho u,  c_s^2 = gamma P / rho       (Monaghan 1992, ARA&A 30, 543;
//               Springel & Hernquist 2002, MNRAS 333, 649; u is the specific internal energy)
//   isothermal: P = c_s^2 rho, c_s constant                         (Monaghan 1992)
//   polytropic: P = K rho^gamma, c_s^2 = gamma P / rho              (Monaghan & Price 2006,
//               MNRAS 365, 991; Monaghan 1992)
//   barotropic: P = c_s^2 rho [1 + (rho/rho_crit)^(gamma-1)]         (Bate, Bonnell & Price 1995,
//               MNRAS 277, 362; Bate & Burkert 1997, MNRAS 288, 1060, with gamma = 7/5):
//               isothermal (sound speed c_s) below the critical density rho_crit, adiabatic
//               (P ~ rho^gamma) above it, the gas of a collapsing cloud core that becomes optically
//               thick; the sound speed is the derivative of this P(rho),
//               c^2 = dP/drho = c_s^2 [1 + gamma (rho/rho_crit)^(gamma-1)]
// Only the ideal gas depends on u, so only it needs (and integrates) the energy equation.

#ifndef LMP_SPH_ASTRO_EOS_H
#define LMP_SPH_ASTRO_EOS_H

#include <cmath>

namespace SPHAstro {

enum class EOSType { IDEAL, ISOTHERMAL, POLYTROPIC, BAROTROPIC };

struct EOS {
  EOSType type = EOSType::IDEAL;
  double gamma = 5.0 / 3.0;    // ideal and polytropic
  double cs = 1.0;             // isothermal sound speed (isothermal, barotropic)
  double K = 1.0;              // polytropic constant
  double rho_crit = 1.0;       // barotropic: density of the isothermal-adiabatic transition

  bool uses_energy() const { return type == EOSType::IDEAL; }

  // pressure and sound speed from density and specific internal energy
  inline void pressure_soundspeed(double rho, double u, double &P, double &c) const
  {
    switch (type) {
      case EOSType::IDEAL:
        P = (gamma - 1.0) * rho * u;
        c = std::sqrt(gamma * (gamma - 1.0) * (u > 0.0 ? u : 0.0));
        return;
      case EOSType::ISOTHERMAL:
        P = cs * cs * rho;
        c = cs;
        return;
      case EOSType::POLYTROPIC:
        P = K * std::pow(rho, gamma);
        c = std::sqrt(gamma * P / rho);
        return;
      case EOSType::BAROTROPIC: {
        // s = (rho/rho_crit)^(gamma-1); P = c_s^2 rho (1 + s), dP/drho = c_s^2 (1 + gamma s)
        const double s = std::pow(rho / rho_crit, gamma - 1.0);
        P = cs * cs * rho * (1.0 + s);
        c = cs * std::sqrt(1.0 + gamma * s);
        return;
      }
    }
  }

  // specific internal energy consistent with the EOS (for energy bookkeeping of the
  // barotropic models: u = P / ((gamma-1) rho) for a polytrope, 0 for the isothermal gas
  // whose thermal energy is not a conserved quantity; for the barotropic gas the energy of its
  // adiabatic part, u = int P_ad / rho^2 drho = c_s^2 (rho/rho_crit)^(gamma-1) / (gamma-1) with
  // P_ad = c_s^2 rho (rho/rho_crit)^(gamma-1), and 0 for its isothermal part as above)
  inline double energy_of(double rho, double u) const
  {
    switch (type) {
      case EOSType::IDEAL:
        return u;
      case EOSType::ISOTHERMAL:
        return 0.0;
      case EOSType::POLYTROPIC:
        return K * std::pow(rho, gamma - 1.0) / (gamma - 1.0);
      case EOSType::BAROTROPIC:
        return cs * cs * std::pow(rho / rho_crit, gamma - 1.0) / (gamma - 1.0);
    }
    return u;
  }
};

}    // namespace SPHAstro

#endif
