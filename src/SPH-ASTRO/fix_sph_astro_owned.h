/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(sph/astro/owned,FixSPHAstroOwned);
// clang-format on
#else

#ifndef LMP_FIX_SPH_ASTRO_OWNED_H
#define LMP_FIX_SPH_ASTRO_OWNED_H

#include "fix_property_atom.h"

#include <unordered_set>

namespace LAMMPS_NS {

// fix ID group-ID sph/astro/owned name1 [name2 ...] [writedata yes/no]
//   name = d_NAME | i_NAME | d2_NAME N | i2_NAME N   (custom per-atom properties, as for
//   fix property/atom; d_NAME etc. in variables, dumps, compute property/atom and set)
//
// Custom per-atom properties of the owned atoms only. Fix property/atom sizes its arrays for
// the owned and the ghost atoms (LAMMPS' nmax) and zeroes every slot it grows; this fix holds
// slots for the owned atoms (and the spare slot through which LAMMPS' atom sort copies), so a
// property that no ghost needs costs no memory per ghost. Ghost atoms have no values here
// (there is no ghost keyword): the slots from nlocal on must not be read. Values travel with
// their atoms between ranks, go into restart files and (writedata yes, the default) data
// files, and are 0 for atoms created later (create_atoms, read_data, fix deposit, ...).
class FixSPHAstroOwned : public FixPropertyAtom {
 public:
  FixSPHAstroOwned(class LAMMPS *, int, char **);

  void init() override;
  void read_data_section(char *, int, char *, tagint) override;
  void write_data_section_keyword(int, FILE *) override;
  void write_data_section(int, FILE *, int, double **, int) override;
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int unpack_exchange(int, double *) override;
  void unpack_restart(int, int) override;
  double memory_usage() override;

  // slots for the atoms [0, n) at least; new slots hold 0
  void reserve(int n);

 private:
  int capacity_;
  // atoms (IDs) whose values a data file section gave (read_data then calls set_arrays())
  std::unordered_set<tagint> from_data_;
  std::size_t longest_line_ = 0;    // of the data file section being written
  void resize(int n);
};

}    // namespace LAMMPS_NS

#endif
#endif
