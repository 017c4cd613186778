/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The time line of individual (hierarchical block) timesteps (Springel 2005, MNRAS 364, 1105,
// sec. 4; Schaller et al. 2024, MNRAS 530, 2378, sec. 3): particle i steps dt_max / 2^b_i,
// b_i its bin. Times are integer ticks, dt_max = 2^MAX_BIN ticks, kept in doubles (exact up
// to 2^53). A step of bin b begins and ends on multiples of 2^(MAX_BIN - b) ticks, so at
// every multiple of dt_max all particles are synchronised. A particle moves to a longer step
// only where the longer step's grid passes (synchronised()), one bin at a time; to a shorter
// step at the end of any of its steps. The timestep limiter (Saitoh & Makino 2009, ApJ 697,
// L99; Durier & Dalla Vecchia 2012, MNRAS 419, 465) keeps each particle's bin within
// `levels` of its neighbours' and ends a sleeping neighbour's step early (wake_end()).

#ifndef LMP_SPH_ASTRO_TIME_BINS_H
#define LMP_SPH_ASTRO_TIME_BINS_H

#include <cmath>
#include <cstdint>

namespace SPHAstro {
namespace TimeBins {

  constexpr int MAX_BIN = 48;    // the shortest step is dt_max / 2^48

  // the length of a step of bin b in ticks
  inline double ticks(int bin)
  {
    return std::ldexp(1.0, MAX_BIN - bin);
  }
  inline double cycle()
  {
    return ticks(0);
  }

  // the bin of a particle whose criteria allow dt: the smallest b >= 0 with dt_max / 2^b <= dt
  // (0 for dt >= dt_max or no finite limit); may exceed MAX_BIN (the caller reports it)
  inline int bin_for(double dt_max, double dt)
  {
    if (!(dt < dt_max)) return 0;
    if (!(dt > 0.0)) return MAX_BIN + 1;
    int b = static_cast<int>(std::ceil(std::log2(dt_max / dt)));
    if (b < 0) b = 0;
    while (std::ldexp(dt_max, -b) > dt) b++;
    while (b > 0 && std::ldexp(dt_max, -(b - 1)) <= dt) b--;
    return b;
  }

  // is time ti (ticks) on the grid of bin b?
  inline bool synchronised(double ti, int bin)
  {
    return std::fmod(ti, ticks(bin)) == 0.0;
  }

  // the coarsest bin whose grid holds time ti (ticks, > 0): the next points after a time of
  // different bins' grids are told apart by it
  inline int coarsest_bin(double ti)
  {
    return MAX_BIN - __builtin_ctzll(static_cast<std::uint64_t>(ti));
  }

  // the bin of a particle that ends a step of bin old_bin at ti and whose criteria ask for
  // wanted: shorter at once, longer by one bin where that bin's grid passes through ti
  inline int next_bin(int old_bin, int wanted, double ti)
  {
    if (wanted >= old_bin) return wanted;
    if (old_bin > 0 && synchronised(ti, old_bin - 1)) return old_bin - 1;
    return old_bin;
  }

  // the first time after ti on the grid of bin b: where a woken particle's step now ends
  inline double wake_end(double ti, int bin)
  {
    const double L = ticks(bin);
    return (std::floor(ti / L) + 1.0) * L;
  }

}    // namespace TimeBins
}    // namespace SPHAstro

#endif
