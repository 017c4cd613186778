/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// What fix sph/astro/sink's accretion (fix_sph_astro_sink.cpp) and creation
// (fix_sph_astro_sink_creation.cpp) share: the layouts of the records every rank gathers, the
// gathering, and two vector products.

#ifndef LMP_SPH_ASTRO_SINK_RECORDS_H
#define LMP_SPH_ASTRO_SINK_RECORDS_H

#include <mpi.h>

#include <vector>

namespace SPHAstro {
namespace SinkRecords {

  inline constexpr int SINK_DOUBLES = 14;    // tag, x, v, m, spin, macc, nacc, mlow
  inline constexpr int RECORD_DOUBLES =
      9;    // accretion record: sink tag, gas tag, m, r (3), v (3)
  inline constexpr int MEMBER_DOUBLES = 10;    // creation group: tag, m, r (3), v (3), e_th, h

  inline void cross(const double *a, const double *b, double *c)
  {
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
  }

  inline double dot(const double *a, const double *b)
  {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  }

  // gather variable-length double buffers of all ranks onto all ranks
  inline std::vector<double> allgather(const std::vector<double> &mine, MPI_Comm world, int nprocs)
  {
    int n = static_cast<int>(mine.size());
    std::vector<int> counts(nprocs), displs(nprocs, 0);
    MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, world);
    int total = 0;
    for (int p = 0; p < nprocs; p++) {
      displs[p] = total;
      total += counts[p];
    }
    std::vector<double> all(total);
    MPI_Allgatherv(mine.data(), n, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE,
                   world);
    return all;
  }

}    // namespace SinkRecords
}    // namespace SPHAstro

#endif
