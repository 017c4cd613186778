/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

#include "fix_sph_astro_owned.h"

#include "atom.h"
#include "error.h"
#include "memory.h"
#include "update.h"
#include "utils.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <string>

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
    // what follows an array or writedata (fix property/atom would say only "Illegal fix
    // property/atom command" of a missing one)
    const char *next = iarg + 1 < narg ? arg[iarg + 1] : nullptr;
    const std::string got = next ? fmt::format("got '{}'", next) : "nothing follows it";
    if (utils::strmatch(a, "^[id]2_.")) {
      if (!next || !utils::is_integer(next) || std::atoi(next) < 1)
        lmp->error->all(FLERR,
                        "fix sph/astro/owned: {} needs its number of columns ({}2_NAME N, an "
                        "integer N >= 1); {}",
                        a, a[0], got);
      iarg++;
      continue;
    }
    if (strcmp(a, "writedata") == 0) {
      bool known = false;
      for (const char *flag : {"yes", "no", "on", "off", "true", "false"})
        known = known || (next && strcmp(next, flag) == 0);
      if (!known) lmp->error->all(FLERR, "fix sph/astro/owned: writedata needs yes or no; {}", got);
      iarg++;
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
// atoms get slots here. Atoms added outside a run come with no ghosts (read_data, create_atoms
// and read_dump set nghost = 0 first), and read_data gives fixes no set_arrays() call for them:
// such a growth reserves the whole length, and init() gives back what they did not take
void FixSPHAstroOwned::grow_arrays(int nmax)
{
  reserve(update->whichflag == 0 && atom->nghost == 0 ? nmax : atom->nlocal);
}

void FixSPHAstroOwned::init()
{
  FixPropertyAtom::init();
  const int keep = atom->nlocal + atom->nlocal / 4 + 64;
  if (capacity_ > 2 * keep) resize(keep);
  from_data_.clear();
}

// read_data calls set_arrays() for the atoms it created after it has read the sections: the
// atoms whose values a section gave keep them
void FixSPHAstroOwned::read_data_section(char *keyword, int n, char *buf, tagint id_offset)
{
  reserve(atom->nlocal);
  const char *line = buf;
  for (int k = 0; k < n && line; k++) {
    const tagint tag = static_cast<tagint>(std::strtoll(line, nullptr, 10)) + id_offset;
    if (atom->map(tag) >= 0) from_data_.insert(tag);
    line = strchr(line, '\n');
    if (line) line++;
  }
  FixPropertyAtom::read_data_section(keyword, n, buf, id_offset);
}

void FixSPHAstroOwned::write_data_section_keyword(int mth, FILE *fp)
{
  longest_line_ = 0;
  FixPropertyAtom::write_data_section_keyword(mth, fp);
}

// the lines of fix property/atom's format; read_data reads only the first 255 characters of a
// line (its MAXLINE), so a longer one cannot come back: said once per section (rank 0 writes)
void FixSPHAstroOwned::write_data_section(int /*mth*/, FILE *fp, int n, double **buf, int /*index*/)
{
  constexpr std::size_t READ_DATA_LINE = 255;
  for (int i = 0; i < n; i++) {
    std::string line = fmt::format("{}", static_cast<tagint>(ubuf(buf[i][0]).i));
    int icol = 1;
    for (int nv = 0; nv < nvalue; nv++) {
      const int ncol = (styles[nv] == IARRAY || styles[nv] == DARRAY) ? cols[nv] : 1;
      for (int k = 0; k < ncol; k++, icol++) {
        if (styles[nv] == IVEC || styles[nv] == IARRAY)
          line += fmt::format(" {}", static_cast<int>(ubuf(buf[i][icol]).i));
        else
          line += fmt::format(" {}", buf[i][icol]);
      }
    }
    utils::print(fp, line + "\n");
    if (line.size() > longest_line_) {
      if (longest_line_ <= READ_DATA_LINE && line.size() > READ_DATA_LINE)
        error->warning(FLERR,
                       "fix {} sph/astro/owned: write_data writes lines of {} values and more "
                       "than {} characters in section {}; read_data reads {} characters of a "
                       "line and cannot read it back (restart files keep the values; writedata "
                       "no leaves the section out)",
                       id, values_peratom, READ_DATA_LINE, id, READ_DATA_LINE);
      longest_line_ = line.size();
    }
  }
}

void FixSPHAstroOwned::reserve(int n)
{
  if (n <= capacity_) return;
  // (in steps: atoms arrive one by one from exchanges)
  resize(std::max(n, capacity_ + capacity_ / 4 + 64));
}

// slots for [0, n): the first min(n, capacity_) keep their values, new ones hold 0
void FixSPHAstroOwned::resize(int n)
{
  const int kept = std::min(n, capacity_);
  for (int nv = 0; nv < nvalue; nv++) {
    const int k = index[nv];
    if (styles[nv] == IVEC) {
      memory->grow(atom->ivector[k], n, "sph/astro/owned:ivector");
      std::fill(atom->ivector[k] + kept, atom->ivector[k] + n, 0);
    } else if (styles[nv] == DVEC) {
      memory->grow(atom->dvector[k], n, "sph/astro/owned:dvector");
      std::fill(atom->dvector[k] + kept, atom->dvector[k] + n, 0.0);
    } else if (styles[nv] == IARRAY) {
      memory->grow(atom->iarray[k], n, cols[nv], "sph/astro/owned:iarray");
      std::fill(&atom->iarray[k][0][0] + kept * cols[nv], &atom->iarray[k][0][0] + n * cols[nv], 0);
    } else if (styles[nv] == DARRAY) {
      memory->grow(atom->darray[k], n, cols[nv], "sph/astro/owned:darray");
      std::fill(&atom->darray[k][0][0] + kept * cols[nv], &atom->darray[k][0][0] + n * cols[nv],
                0.0);
    }
  }
  capacity_ = n;
}

void FixSPHAstroOwned::copy_arrays(int i, int j, int delflag)
{
  reserve(std::max(i, j) + 1);    // (j = nlocal: the spare slot of LAMMPS' atom sort)
  FixPropertyAtom::copy_arrays(i, j, delflag);
}

void FixSPHAstroOwned::set_arrays(int i)
{
  reserve(i + 1);
  if (!from_data_.empty() && from_data_.erase(atom->tag[i]) > 0) return;
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
