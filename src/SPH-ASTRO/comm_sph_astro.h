/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

#ifndef LMP_COMM_SPH_ASTRO_H
#define LMP_COMM_SPH_ASTRO_H

#include "comm_brick.h"

namespace LAMMPS_NS {

// What sets the ghost shells (fix sph/astro/h): reach[2 d + side] is the largest distance,
// among this rank's particles near its lower (side 0) or upper (side 1) sub-domain face in
// dimension d, at which a particle needs its partners across that face (0 where none needs
// any); floor is what other interactions need across every face. Returns false where the whole
// ghost cutoff is needed (the same answer on every rank).
class GhostWidthSource {
 public:
  virtual bool ghost_reaches(double *reach, double &floor) = 0;

 protected:
  ~GhostWidthSource() = default;    // (not deleted through this interface)
};

// LAMMPS' brick communication with a ghost shell at each sub-domain face as wide as the
// particles on both sides of that face reach: after CommBrick sets its swaps for the one ghost
// cutoff, the slab each swap sends across a face is cut to that face's width (never widened).
// A pair whose separation crosses a face is then held by both ranks when the width covers the
// reach of every particle within its reach of the face, on either side; the source gives each
// rank's reaches, and the two ranks of a face take the larger (MPI_Sendrecv with the
// neighbours CommBrick swaps with; a dimension whose cutoff spans more than one sub-domain
// takes the largest over all ranks). With one cutoff for all atoms and all dimensions, a hot
// cavity's h would set the shell along every face of every rank (Sedov: 4 ghosts per owned
// particle on 2 ranks, most of them periodic images of cold gas). Orthogonal boxes and
// comm_modify mode single only; otherwise the shells are CommBrick's.
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
  // the shells of the latest setup: the width at the lower (side 0) or upper (side 1) face in
  // dimension d (the whole cutoff where not narrowed), and whether it was narrowed
  double width(int d, int side) const { return width_[2 * d + side]; }
  bool narrowed(int d, int side) const { return narrowed_[2 * d + side] != 0; }
  bool narrowed() const;
  // also through LAMMPS' Comm interface: "sph/astro/widths" and "sph/astro/narrowed" (6 doubles
  // and 6 ints, lower and upper face of x, y, z)
  void *extract(const char *, int &) override;

 private:
  GhostWidthSource *source_ = nullptr;
  double width_[6] = {0, 0, 0, 0, 0, 0};
  int narrowed_[6] = {0, 0, 0, 0, 0, 0};
};

}    // namespace LAMMPS_NS

#endif
