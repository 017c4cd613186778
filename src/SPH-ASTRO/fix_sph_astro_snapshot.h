/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(sph/astro/snapshot,FixSPHAstroSnapshot);
// clang-format on
#else

#ifndef LMP_FIX_SPH_ASTRO_SNAPSHOT_H
#define LMP_FIX_SPH_ASTRO_SNAPSHOT_H

#include "fix.h"

#include <string>

namespace LAMMPS_NS {

// HDF5 snapshots in the layout of SWIFT (Schaller et al. 2024, MNRAS 530, 2378) and GADGET
// (Springel 2005, MNRAS 364, 1105): every N steps the particles of the group, gathered by rank
// to rank 0, which writes one file with the HDF5 C library. LAMMPS plugins cannot add dump
// styles, hence a fix.
class FixSPHAstroSnapshot : public Fix {
 public:
  FixSPHAstroSnapshot(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void setup(int) override;
  void end_of_step() override;
  void write_restart(FILE *) override;
  void restart(char *) override;

  // the file name of the snapshot of a step
  std::string filename(bigint step) const;
  // the file name pattern as given ('*' for the step)
  const std::string &pattern() const { return pattern_; }

 private:
  std::string pattern_;    // file name with '*' for the step
  int pad_;                // digits of the step in the file name (0: as many as it has)
  bool single_;            // precision float: all but coordinates and IDs in 32-bit floats
  double unit_[3];         // length, mass, time unit in cgs
  bool unit_given_;        // keyword units
  bigint last_written_;    // step of the last snapshot (-1: none)
  class PairSPHAstro *pair_;
  int rho_, h_, u_;    // columns of the state in atom->dvector

  void write();
  int pack(double *buf, const double *origin);
};

}    // namespace LAMMPS_NS

#endif
#endif
