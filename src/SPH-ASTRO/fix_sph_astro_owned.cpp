/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

#include "fix_sph_astro_owned.h"

#include "atom.h"
#include "error.h"
#include "memory.h"
#include "utils.h"

#include <algorithm>
#include <cstring>

using namespace LAMMPS_NS;

namespace {
// the arguments fix property/atom takes that this fix does too: custom vectors and arrays (not
// mol, q, rmass, temperature, heatflow: LAMMPS reads those of ghosts) and writedata, no ghost
char **owned_arguments(LAMMPS *lmp, int narg, char **arg)
{
  if (narg < 4)
    lmp->error->all(FLERR,
                    "fix sph/astro/owned: expected one or more of d_NAME, i_NAME, "
                    "d2_NAME N, i2_NAME N");
  for (int iarg = 3; iarg < narg; iarg++) {
    const char *a = arg[iarg];
    if (utils::strmatch(a, "^[id]_.")) continue;
    if (utils::strmatch(a, "^[id]2_.") || strcmp(a, "writedata") == 0) {
      iarg++;    // (its number of columns or yes/no: fix property/atom checks it)
      continue;
    }
    lmp->error->all(FLERR,
                    "fix sph/astro/owned: '{}' is not one of d_NAME, i_NAME, d2_NAME N, "
                    "i2_NAME N, writedata yes/no (per-atom properties of the owned atoms; fix "
                    "property/atom holds mol, q, rmass, temperature, heatflow and ghost values)",
                    a);
  }
  return arg;
}
}    // namespace

FixSPHAstroOwned::FixSPHAstroOwned(LAMMPS *lmp, int narg, char **arg) :
    FixPropertyAtom(lmp, narg, owned_arguments(lmp, narg, arg)), capacity_(0)
{
  create_attribute = 1;    // set_arrays(): atoms created later start at 0 in their slot
}

// LAMMPS grows its per-atom arrays for owned and ghost atoms alike (nmax): only the owned
// atoms get slots here
void FixSPHAstroOwned::grow_arrays(int)
{
  reserve(atom->nlocal);
}

void FixSPHAstroOwned::reserve(int n)
{
  if (n <= capacity_) return;
  // (in steps: atoms arrive one by one from exchanges)
  const int grown = std::max(n, capacity_ + capacity_ / 4 + 64);
  for (int nv = 0; nv < nvalue; nv++) {
    const int k = index[nv];
    if (styles[nv] == IVEC) {
      memory->grow(atom->ivector[k], grown, "sph/astro/owned:ivector");
      std::fill(atom->ivector[k] + capacity_, atom->ivector[k] + grown, 0);
    } else if (styles[nv] == DVEC) {
      memory->grow(atom->dvector[k], grown, "sph/astro/owned:dvector");
      std::fill(atom->dvector[k] + capacity_, atom->dvector[k] + grown, 0.0);
    } else if (styles[nv] == IARRAY) {
      memory->grow(atom->iarray[k], grown, cols[nv], "sph/astro/owned:iarray");
      std::fill(&atom->iarray[k][capacity_][0], &atom->iarray[k][0][0] + grown * cols[nv], 0);
    } else if (styles[nv] == DARRAY) {
      memory->grow(atom->darray[k], grown, cols[nv], "sph/astro/owned:darray");
      std::fill(&atom->darray[k][capacity_][0], &atom->darray[k][0][0] + grown * cols[nv], 0.0);
    }
  }
  capacity_ = grown;
}

void FixSPHAstroOwned::copy_arrays(int i, int j, int delflag)
{
  reserve(std::max(i, j) + 1);    // (j = nlocal: the spare slot of LAMMPS' atom sort)
  FixPropertyAtom::copy_arrays(i, j, delflag);
}

void FixSPHAstroOwned::set_arrays(int i)
{
  reserve(i + 1);
  for (int nv = 0; nv < nvalue; nv++) {
    const int k = index[nv];
    if (styles[nv] == IVEC)
      atom->ivector[k][i] = 0;
    else if (styles[nv] == DVEC)
      atom->dvector[k][i] = 0.0;
    else if (styles[nv] == IARRAY)
      std::fill_n(atom->iarray[k][i], cols[nv], 0);
    else if (styles[nv] == DARRAY)
      std::fill_n(atom->darray[k][i], cols[nv], 0.0);
  }
}

int FixSPHAstroOwned::unpack_exchange(int nlocal, double *buf)
{
  reserve(nlocal + 1);
  return FixPropertyAtom::unpack_exchange(nlocal, buf);
}

void FixSPHAstroOwned::unpack_restart(int nlocal, int nth)
{
  reserve(nlocal + 1);
  FixPropertyAtom::unpack_restart(nlocal, nth);
}

double FixSPHAstroOwned::memory_usage()
{
  double bytes = 0.0;
  for (int nv = 0; nv < nvalue; nv++) {
    if (styles[nv] == IVEC)
      bytes += sizeof(int);
    else if (styles[nv] == DVEC)
      bytes += sizeof(double);
    else if (styles[nv] == IARRAY)
      bytes += cols[nv] * sizeof(int) + sizeof(int *);
    else if (styles[nv] == DARRAY)
      bytes += cols[nv] * sizeof(double) + sizeof(double *);
  }
  return bytes * capacity_;
}
