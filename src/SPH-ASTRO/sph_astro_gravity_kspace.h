/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: what the gravity kspace styles share
------------------------------------------------------------------------- */

// Self-gravity through LAMMPS' Coulomb solvers (PPPM, MSM): masses act as charges and the
// prefactor -G replaces the Coulomb constant qqrd2e, so that like "charges" attract:
//   E = -G sum_{i<j} m_i m_j / r_ij   instead of   qqrd2e sum_{i<j} q_i q_j / r_ij.
// The solvers read atom->q. A plugin cannot add it to an atom style, so the package adds q as
// a custom property (fix SPH_ASTRO_GRAVITY_Q all property/atom q ghost yes; ghost
// values are not used, the option only keeps LAMMPS from warning) when the atom style has
// none, and copies the masses into it before every long-range evaluation.
//
// The solvers' accuracy estimates (g_ewald, grid size) need a positive prefactor and a
// reference force. During their init() the Coulomb constants of Force are swapped for the
// gravitational ones (ScopedGravityConstants): qqrd2e = G, and the "two unit charges at one
// length unit" force that makes the accuracy relative becomes F_ref = G M m_mean / V^(2/3),
// the pull of the whole mass M on a mean-mass particle at the box size. After init the solver's
// own prefactor is set to -G.

#ifndef LMP_SPH_ASTRO_GRAVITY_KSPACE_H
#define LMP_SPH_ASTRO_GRAVITY_KSPACE_H

#include <string>

namespace LAMMPS_NS {
class LAMMPS;
class Force;
}    // namespace LAMMPS_NS

namespace SPHAstro {

constexpr const char *GRAVITY_Q_FIX_ID = "SPH_ASTRO_GRAVITY_Q";

// add q as a custom property if the atom style has none; caller names the command
void ensure_mass_charge(LAMMPS_NS::LAMMPS *lmp, const char *caller);

// q_i = m_i for the owned atoms
void masses_to_charges(LAMMPS_NS::LAMMPS *lmp);

// G from pair_style sph/astro/gravity (also as a hybrid sub-style); error naming caller if absent
double gravity_constant(LAMMPS_NS::LAMMPS *lmp, const char *caller);

// F_ref = G M m_mean / V^(2/3) (G if there are no atoms)
double gravity_reference_force(LAMMPS_NS::LAMMPS *lmp, double G);

// the box's boundary command, e.g. "p p f" or "ss mm f"
std::string boundary_string(LAMMPS_NS::LAMMPS *lmp);

// kspace_style ... accuracy: a relative force error > 0 (LAMMPS' PPPM and MSM would take its
// absolute value, or fail later without naming it)
void check_accuracy(LAMMPS_NS::LAMMPS *lmp, const char *caller, int narg, char **arg);

// swaps the Coulomb constants of Force for the gravitational ones while it lives
class ScopedGravityConstants {
 public:
  ScopedGravityConstants(LAMMPS_NS::Force *force, double G, double fref);
  ~ScopedGravityConstants();

 private:
  LAMMPS_NS::Force *force_;
  double qqr2e_, qqrd2e_, qelectron_, angstrom_;
};

}    // namespace SPHAstro

#endif
