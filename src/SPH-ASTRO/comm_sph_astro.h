/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

#ifndef LMP_COMM_SPH_ASTRO_H
#define LMP_COMM_SPH_ASTRO_H

#include "comm_brick.h"

namespace LAMMPS_NS {

// What sets the ghost shell of each dimension (fix sph/astro/h): the width, in each dimension,
// that every pair of the run needs across a sub-domain face (collective). Returns false where
// the whole ghost cutoff is needed.
class GhostWidthSource {
 public:
  virtual bool ghost_widths(double *width) = 0;

 protected:
  ~GhostWidthSource() = default;    // (not deleted through this interface)
};

// LAMMPS' brick communication with a ghost shell as wide as each dimension needs: after
// CommBrick sets its swaps for the one ghost cutoff, the slab each swap sends in dimension d is
// cut to width[d] from the sub-domain face (never widened). A pair whose separation crosses a
// face in d is then still held by both ranks when width[d] covers the reach of every particle
// within its reach of such a face; the source computes that. With one cutoff for all atoms
// and all dimensions, a hot cavity's h would set the shell along every face of every rank
// (Sedov: 4 ghosts per owned particle on 2 ranks, 3/4 of them periodic images of cold gas).
// Orthogonal boxes and comm_modify mode single only; otherwise the shell is CommBrick's.
class CommSPHAstro : public CommBrick {
 public:
  CommSPHAstro(class LAMMPS *, class Comm *);

  void setup() override;

  // replace LAMMPS' brick communication by this one (between commands, as comm_style does);
  // nullptr where the communication is not brick (comm_style tiled)
  static CommSPHAstro *install(class LAMMPS *);
  // LAMMPS' own brick communication again, with the settings and decomposition of this one
  static void uninstall(class LAMMPS *);

  void set_source(GhostWidthSource *source) { source_ = source; }
  GhostWidthSource *source() const { return source_; }
  // the widths of the latest setup (the whole cutoff where not narrowed), whether dimension d
  // was narrowed, and whether any was
  const double *widths() const { return cutghost; }
  bool narrowed(int d) const { return narrowed_dim_[d] != 0; }
  bool narrowed() const { return narrowed_dim_[0] || narrowed_dim_[1] || narrowed_dim_[2]; }
  // also through LAMMPS' Comm interface: "sph/astro/widths" (3 doubles), "sph/astro/narrowed"
  // (3 ints)
  void *extract(const char *, int &) override;

 private:
  GhostWidthSource *source_ = nullptr;
  int narrowed_dim_[3] = {0, 0, 0};
};

}    // namespace LAMMPS_NS

#endif
