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

namespace {
// 500 atoms of a jittered fcc lattice in a periodic box of side 5 with ghosts out to 3 (one
// rank: periodic images), no pair forces
std::unique_ptr<LAMMPS_NS::LAMMPS> jittered_box(const std::string &newton)
{
  auto lmp = open_lammps();
  commands(lmp,
           {"units lj", "atom_style atomic", "atom_modify map array sort 0 0.0", "newton " + newton,
            "boundary p p p", "lattice fcc 4.0", "region box block 0 5 0 5 0 5", "create_box 1 box",
            "create_atoms 1 box", "displace_atoms all random 0.05 0.05 0.05 4711 units box",
            "mass 1 1.0", "pair_style zero 2.0", "pair_coeff * *", "neighbor 0.1 bin",
            "comm_modify cutoff 3.0", "run 0"});
  return lmp;
}

// h from 0.5 to 0.6 by atom ID (owned and ghost atoms)
std::vector<double> spread_h(const std::unique_ptr<LAMMPS_NS::LAMMPS> &lmp)
{
  const auto *atom = lmp->atom;
  std::vector<double> h(atom->nlocal + atom->nghost);
  for (std::size_t i = 0; i < h.size(); i++) h[i] = 0.5 + 0.1 * ((atom->tag[i] * 37) % 11) / 10.0;
  return h;
}
}    // namespace

TEST(NeighbourLists, AnExtensionAddsEveryPairTheGrownSupportsReach)
{
  for (const std::string newton : {"on", "off"}) {
    auto lmp = jittered_box(newton);
    auto *atom = lmp->atom;
    const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
    const double R = 2.0, L = lmp->domain->prd[0];
    // atoms 1..6 grow by 1.3 below (their ghost images with them)
    std::vector<double> h = spread_h(lmp);
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

// individual steps with newton on: rows made only for the leaves of active atoms, and the pairs
// of a step taken from them. Over several steps (other active atoms, an extension for grown h
// between them) each pair inside a support with an active end is evaluated exactly once, the
// gather rows of the active atoms hold every neighbour, and with every atom active the pairs
// and their order are those of the half list. With newton off the lists are made whole.
TEST(NeighbourLists, RowsMadeForTheActiveAtomsGiveEachDuePairOnce)
{
  for (const std::string newton : {"on", "off"}) {
    auto lmp = jittered_box(newton);
    auto *atom = lmp->atom;
    const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
    const double R = 2.0, L = lmp->domain->prd[0];
    std::vector<double> h = spread_h(lmp);
    int sph_type[2] = {0, 1};
    SPHAstro::SearchSettings settings{R, 1.1, 1.4, true, newton == "on", sph_type};
    settings.active_only = true;
    SPHAstro::NeighbourLists lists(lmp.get());
    lists.update(h.data(), settings);

    auto distance2 = [&](int i, int j, bool periodic) {
      double r2 = 0.0;
      for (int d = 0; d < 3; d++) {
        double dx = atom->x[i][d] - atom->x[j][d];
        if (periodic) dx -= L * std::round(dx / L);
        r2 += dx * dx;
      }
      return r2;
    };
    // steps: few active, a third, then (after atoms 1..6 grew by 1.3) a tenth, then all
    const std::vector<int> every = {97, 3, 10, 1};
    for (std::size_t step = 0; step < every.size(); step++) {
      if (step == 2)
        for (int i = 0; i < nall; i++)
          if (atom->tag[i] <= 6) h[i] *= 1.3;
      std::vector<char> active(nall);
      for (int i = 0; i < nall; i++)
        active[i] = (atom->tag[i] * 7919 + static_cast<int>(step)) % every[step] == 0;
      lists.prepare(active.data());
      const SPHAstro::NeighView due = lists.due(h.data(), active.data());
      const std::string what = "newton " + newton + ", step " + std::to_string(step);
      std::map<int, int> listed, brute, gathered, brute_gather;
      for (int ii = 0; ii < due.inum; ii++) {
        const int i = due.ilist[ii];
        for (int k = 0; k < due.numneigh[i]; k++) {
          const int j = due.firstneigh[i][k];
          if (distance2(i, j, false) >= std::pow(R * std::max(h[i], h[j]), 2)) continue;
          listed[atom->tag[i]]++;
          if (newton == "on" || j < nlocal) listed[atom->tag[j]]++;
        }
      }
      const SPHAstro::NeighView full = lists.full();
      for (int ii = 0; ii < full.inum; ii++) {
        const int i = full.ilist[ii];
        if (!active[i]) continue;
        for (int k = 0; k < full.numneigh[i]; k++) {
          const int j = full.firstneigh[i][k];
          if (distance2(i, j, false) < std::pow(R * h[i], 2)) gathered[atom->tag[i]]++;
        }
      }
      for (int i = 0; i < nlocal; i++)
        for (int j = 0; j < nlocal; j++) {
          if (j == i) continue;
          const double r2 = distance2(i, j, true);
          if ((active[i] || active[j]) && r2 < std::pow(R * std::max(h[i], h[j]), 2))
            brute[atom->tag[i]]++;
          if (active[i] && r2 < std::pow(R * h[i], 2)) brute_gather[atom->tag[i]]++;
        }
      int checked = 0;
      for (int i = 0; i < nlocal; i++) {
        const int tag = atom->tag[i];
        // (newton off: an inactive atom's pairs with active ghosts are also evaluated here)
        if (newton == "on" || active[i])
          EXPECT_EQ(listed[tag], brute[tag]) << what << ", atom " << tag;
        EXPECT_EQ(gathered[tag], brute_gather[tag]) << what << ", atom " << tag;
        checked += brute[tag] > 0;
      }
      EXPECT_GT(checked, 0) << what;
      if (step == 0 && newton == "on")    // the leaves of the few active atoms only
        EXPECT_LT(lists.statistics().rows_made, nlocal / 2) << what;
      if (step + 1 < every.size()) continue;
      // all active, before any growth in the whole lists: their half list, pair for pair
      SPHAstro::NeighbourLists fresh(lmp.get()), fresh_whole(lmp.get());
      settings.active_only = true;
      fresh.update(h.data(), settings);
      settings.active_only = false;
      fresh_whole.update(h.data(), settings);
      const SPHAstro::NeighView a = fresh.due(h.data(), active.data());
      const SPHAstro::NeighView b = fresh_whole.half(h.data());
      ASSERT_EQ(a.inum, b.inum) << what;
      for (int ii = 0; ii < a.inum; ii++) {
        ASSERT_EQ(a.ilist[ii], b.ilist[ii]) << what;
        const int i = a.ilist[ii];
        EXPECT_EQ(std::vector<int>(a.firstneigh[i], a.firstneigh[i] + a.numneigh[i]),
                  std::vector<int>(b.firstneigh[i], b.firstneigh[i] + b.numneigh[i]))
            << what << ", row " << i;
      }
    }
    const auto &stats = lists.statistics();
    EXPECT_EQ(stats.extensions, 1) << newton;
    if (newton == "on")
      EXPECT_EQ(stats.rows_made, nlocal);    // all at the last step
    else
      EXPECT_EQ(stats.rows_eager, 0);
  }
}
