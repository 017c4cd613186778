/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The pairs that the force pass evaluates with individual timesteps, kept by rows, so that
// fix sph/astro can apply the timestep limiter over them and kick both atoms of a pair with
// the same impulse (momentum conserved to round-off; sph_astro_individual_steps.h).

#ifndef LMP_SPH_ASTRO_EVALUATED_PAIRS_H
#define LMP_SPH_ASTRO_EVALUATED_PAIRS_H

#include <algorithm>
#include <cstddef>
#include <vector>

namespace SPHAstro {

// Row r: atom rows[r].i with the partners partner[rows[r-1].end .. rows[r].end). A partner
// j < 0 stands for ~j, a ghost this rank does not update (newton off: the pair is recorded on
// both ranks, each for its own atom). With forces, fpair[k] gives the pressure and viscous
// force of pair k: F_ij = fpair (x_i - x_j) on i (the positions of the force evaluation),
// -F_ij on j. With heats, heat[2k] and heat[2k+1] give the pair's terms of du_i/dt and du_j/dt
// (pressure work and dissipation: m_i heat[2k] + m_j heat[2k+1] = -F_ij . v_ij).
struct EvaluatedPairs {
  struct Row {
    int i, end;
  };
  std::vector<Row> rows;
  std::vector<int> partner;
  std::vector<double> fpair, heat;
  bool forces = false;    // fpair is recorded
  bool heats = false;     // heat is recorded (with the forces)

  void clear(bool with_forces, bool with_heats)
  {
    rows.clear();
    partner.clear();
    fpair.clear();
    heat.clear();
    forces = with_forces;
    heats = with_forces && with_heats;
  }
  // room for the pairs of a list of n entries in nrows rows before the pass (growing within
  // it would copy the records, pair by pair doubling); grows by at least half
  void reserve(std::size_t nrows, std::size_t n)
  {
    auto room = [](auto &v, std::size_t want) {
      if (v.capacity() < want) v.reserve(std::max(want, v.capacity() + v.capacity() / 2));
    };
    room(rows, nrows);
    room(partner, n);
    if (forces) room(fpair, n);
    if (heats) room(heat, 2 * n);
  }
  // the force pass: one pair of the row of i, then the row's end
  void add(int j, bool update_j, double f, double heat_i, double heat_j)
  {
    partner.push_back(update_j ? j : ~j);
    if (forces) fpair.push_back(f);
    if (heats) {
      heat.push_back(heat_i);
      heat.push_back(heat_j);
    }
  }
  void end_row(int i, int begin)
  {
    if (static_cast<int>(partner.size()) > begin)
      rows.push_back({i, static_cast<int>(partner.size())});
  }
  // each pair: visit(i, j, update_j, k) with k its index into fpair
  template <class VISIT> void for_each(VISIT &&visit) const
  {
    int k = 0;
    for (const Row &row : rows)
      for (; k < row.end; k++) {
        const int j = partner[k];
        visit(row.i, j >= 0 ? j : ~j, j >= 0, k);
      }
  }
  double memory_usage() const
  {
    return static_cast<double>(rows.capacity() * sizeof(Row) + partner.capacity() * sizeof(int) +
                               (fpair.capacity() + heat.capacity()) * sizeof(double));
  }
};

}    // namespace SPHAstro

#endif
