/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The package's neighbour lists (sph_astro_neighbour_lists.h, compiled into this test) over
// LAMMPS' owned and ghost atoms: lists extended inside a step for the few atoms whose h grew
// hold every pair inside the grown kernel supports once, and their gather rows every
// neighbour, against brute force over the periodic box.

#include "lammps_fixture.h"

#include "sph_astro_neighbour_lists.h"

#include "force.h"

#include <cmath>
#include <map>
#include <vector>

using namespace sph_astro_test;

TEST(NeighbourLists, AnExtensionAddsEveryPairTheGrownSupportsReach)
{
  for (const std::string newton : {"on", "off"}) {
    auto lmp = open_lammps();
    commands(lmp,
             {"units lj", "atom_style atomic", "atom_modify map array sort 0 0.0",
              "newton " + newton, "boundary p p p", "lattice fcc 4.0",
              "region box block 0 5 0 5 0 5", "create_box 1 box", "create_atoms 1 box",
              "displace_atoms all random 0.05 0.05 0.05 4711 units box", "mass 1 1.0",
              "pair_style zero 2.0", "pair_coeff * *", "neighbor 0.1 bin", "comm_modify cutoff 3.0",
              "run 0"});
    auto *atom = lmp->atom;
    const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
    const double R = 2.0, L = lmp->domain->prd[0];
    // h 0.5 .. 0.6; atoms 1..6 grow by 1.3 (their ghost images with them)
    std::vector<double> h(nall);
    auto h_of = [](int tag) {
      return 0.5 + 0.1 * ((tag * 37) % 11) / 10.0;
    };
    for (int i = 0; i < nall; i++) h[i] = h_of(atom->tag[i]);
    SPHAstro::NeighbourLists lists(lmp.get());
    int sph_type[2] = {0, 1};
    const SPHAstro::SearchSettings settings{R, 1.1, 1.4, true, newton == "on", sph_type};
    lists.update(h.data(), settings);
    for (int i = 0; i < nall; i++)
      if (atom->tag[i] <= 6) h[i] *= 1.3;
    const SPHAstro::NeighView half = lists.half(h.data());
    const auto &stats = lists.statistics();
    EXPECT_EQ(stats.extensions, 1);
    EXPECT_EQ(stats.step_builds, 0);
    EXPECT_GT(stats.extension_pairs, 0);
    // each owned atom's pairs inside a support, counted from the half list as the passes add
    // them (j's side only where j is owned, or with newton on, where the ghost's part goes back
    // to its owner)
    std::map<int, int> listed, brute, gathered, brute_gather;
    const bool newton_on = newton == "on";
    for (int ii = 0; ii < half.inum; ii++) {
      const int i = half.ilist[ii];
      for (int k = 0; k < half.numneigh[i]; k++) {
        const int j = half.firstneigh[i][k];
        double r2 = 0.0;
        for (int d = 0; d < 3; d++) r2 += std::pow(atom->x[i][d] - atom->x[j][d], 2);
        if (r2 >= std::pow(R * std::max(h[i], h[j]), 2)) continue;
        listed[atom->tag[i]]++;
        if (newton_on || j < nlocal) listed[atom->tag[j]]++;
      }
    }
    const SPHAstro::NeighView full = lists.full();
    for (int ii = 0; ii < full.inum; ii++) {
      const int i = full.ilist[ii];
      for (int k = 0; k < full.numneigh[i]; k++) {
        const int j = full.firstneigh[i][k];
        double r2 = 0.0;
        for (int d = 0; d < 3; d++) r2 += std::pow(atom->x[i][d] - atom->x[j][d], 2);
        if (r2 < std::pow(R * h[i], 2)) gathered[atom->tag[i]]++;
      }
    }
    for (int i = 0; i < nlocal; i++)
      for (int j = 0; j < nlocal; j++) {
        if (j == i) continue;
        double r2 = 0.0;
        for (int d = 0; d < 3; d++) {
          double dx = atom->x[i][d] - atom->x[j][d];
          dx -= L * std::round(dx / L);
          r2 += dx * dx;
        }
        if (r2 < std::pow(R * std::max(h[i], h[j]), 2)) brute[atom->tag[i]]++;
        if (r2 < std::pow(R * h[i], 2)) brute_gather[atom->tag[i]]++;
      }
    int grown_checked = 0;
    for (const auto &[tag, count] : brute) {
      EXPECT_EQ(listed[tag], count) << "newton " << newton << ", atom " << tag;
      EXPECT_EQ(gathered[tag], brute_gather[tag]) << "newton " << newton << ", atom " << tag;
      grown_checked += tag <= 6;
    }
    EXPECT_EQ(grown_checked, 6);
  }
}
