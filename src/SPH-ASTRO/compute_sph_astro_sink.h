/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(sph/astro/sink,ComputeSPHAstroSink);
// clang-format on
#else

#ifndef LMP_COMPUTE_SPH_ASTRO_SINK_H
#define LMP_COMPUTE_SPH_ASTRO_SINK_H

#include "compute.h"

#include <map>
#include <string>

namespace LAMMPS_NS {

// the sinks of a fix sph/astro/sink, one row per sink in ID order: ID, mass, spin (3), accreted
// mass, accretion rate since the compute's previous evaluation
class ComputeSPHAstroSink : public Compute {
 public:
  ComputeSPHAstroSink(class LAMMPS *, int, char **);
  ~ComputeSPHAstroSink() override;
  void init() override;
  void compute_array() override;
  double memory_usage() override;

 protected:
  std::string fix_id_;
  class FixSPHAstroSink *fix_ = nullptr;
  int nrows_ = 0;
  struct Sample {
    double time, macc, rate;
  };
  std::map<tagint, Sample> previous_;
};

}    // namespace LAMMPS_NS

#endif
#endif
