/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The run configuration of pair sph/astro besides its own options: what the package's fixes
// ask for (read at init through Fix::extract(): the smoothing-length mode and its settings, the
// thermal variable, a viscosity switch), and what follows from it.

#ifndef LMP_SPH_ASTRO_SCHEME_H
#define LMP_SPH_ASTRO_SCHEME_H

#include <cmath>

namespace LAMMPS_NS {
class LAMMPS;
}

namespace SPHAstro {

struct PairOptions;

// fix sph/astro/h margin: its default
constexpr double DEFAULT_MARGIN = 1.5;

struct Scheme {
  // smoothing length: fixed, evolved by dh/dt (both with h_ij = (h_i + h_j)/2 in every pair
  // term; fix sph/astro/h dhdt), or iterated with rho (W(h_i) and W(h_j), grad-h factor
  // Omega; fix sph/astro/h iterate)
  enum class HMode { FIXED, DHDT, GRADH };
  HMode hmode = HMode::FIXED;
  double hfact = 1.2, tolerance = 1e-4, margin = 1.0;
  double h_max = INFINITY;    // fix sph/astro/h hmax: no h beyond it
  // fix sph/astro/h: the h cap at the start of the run before and at its end (from its restart
  // file or the run before in this instance; 0: none)
  double carried_cap_start = 0.0, carried_cap = 0.0;
  int max_iterations = 30;
  bool entropy = false;       // fix sph/astro thermal entropy: P = A rho^gamma
  bool has_switch = false;    // fix sph/astro/switch: per-particle alpha (d_alpha)
  bool curl = false;          // curl v needed (Balsara or the Cullen-Dehnen switch)
  bool gradh() const { return hmode == HMode::GRADH; }
};

// the scheme of this run from the package's fixes (fix sph/astro must exist: an error says
// so), checked against the options (PairOptions::check_scheme)
Scheme read_scheme(LAMMPS_NS::LAMMPS *lmp, const PairOptions &options);

// the largest h the ghost cutoff serves in this box, the bound of the h cap: with a periodic
// dimension what half its shortest length L serves, (L/2 - skin)/R (a wider kernel meets its
// particle's own images); periodic in none, what the box diagonal D serves, D/R (that support
// reaches every atom in the box; one of 1e10 made LAMMPS' ghost exchange overflow its count of
// swaps). axis: the periodic dimension that bounds it, -1 for the diagonal
double box_h_cap(LAMMPS_NS::LAMMPS *lmp, double kernel_radius, double skin, int &axis);

}    // namespace SPHAstro

#endif
