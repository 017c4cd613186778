/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

#include "sph_astro_scheme.h"

#include "domain.h"
#include "error.h"
#include "fix.h"
#include "lammps.h"
#include "modify.h"
#include "sph_astro_options.h"

#include <cmath>

using namespace LAMMPS_NS;

namespace SPHAstro {

// an integer or double setting a fix offers through Fix::extract() (dim 1: double)
static double fix_setting(Fix *fix, const char *name)
{
  int dim = 0;
  void *p = fix->extract(name, dim);
  if (!p) return 0.0;
  return dim == 1 ? *static_cast<double *>(p) : *static_cast<int *>(p);
}

Scheme read_scheme(LAMMPS *lmp, const PairOptions &options)
{
  Scheme scheme;
  Modify *modify = lmp->modify;
  auto integrators = modify->get_fix_by_style("^sph/astro$");
  if (integrators.empty())
    lmp->error->all(FLERR,
                    "pair_style sph/astro requires fix sph/astro: it integrates u and predicts "
                    "the velocities the viscosity uses");
  scheme.entropy = fix_setting(integrators.front(), "entropy") != 0.0;

  auto hfixes = modify->get_fix_by_style("^sph/astro/h$");
  if (!hfixes.empty()) {
    Fix *hfix = hfixes.front();
    scheme.hmode = fix_setting(hfix, "iterate") != 0.0 ? Scheme::HMode::GRADH : Scheme::HMode::DHDT;
    scheme.hfact = fix_setting(hfix, "hfact");
    scheme.tolerance = fix_setting(hfix, "tolerance");
    scheme.max_iterations = static_cast<int>(fix_setting(hfix, "maxiter"));
    scheme.margin = fix_setting(hfix, "margin");
    scheme.h_max = fix_setting(hfix, "hmax");
    scheme.carried_cap_start = fix_setting(hfix, "carried_cap_start");
    scheme.carried_cap = fix_setting(hfix, "carried_cap");
  }

  auto switches = modify->get_fix_by_style("^sph/astro/switch$");
  scheme.has_switch = !switches.empty();
  scheme.curl = options.balsara ||
      (scheme.has_switch && fix_setting(switches.front(), "needs_curl") != 0.0);
  options.check_scheme(lmp, scheme.gradh(), scheme.entropy, scheme.has_switch);
  return scheme;
}

double box_h_cap(LAMMPS *lmp, double kernel_radius, double skin, int &axis)
{
  const Domain *domain = lmp->domain;
  double cap = INFINITY, diagonal2 = 0.0;
  axis = -1;
  for (int d = 0; d < domain->dimension; d++) {
    diagonal2 += domain->prd[d] * domain->prd[d];
    if (domain->periodicity[d] && (0.5 * domain->prd[d] - skin) / kernel_radius < cap) {
      cap = (0.5 * domain->prd[d] - skin) / kernel_radius;
      axis = d;
    }
  }
  return axis >= 0 ? cap : std::sqrt(diagonal2) / kernel_radius;
}

}    // namespace SPHAstro
