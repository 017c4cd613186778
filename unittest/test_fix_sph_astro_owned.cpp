/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// LAMMPS-driven tests of fix sph/astro/owned (custom per-atom properties of the owned atoms
// only): no slots for ghosts, values that follow their atoms through exchanges between ranks,
// sorts, deletions and restarts, 0 for atoms created later, and the arguments it refuses. Run
// on 1 rank and on 3 (ctest fix_sph_astro_owned_mpi).

#include "lammps_fixture.h"

#include "comm.h"
#include "fix.h"

#include <cstdio>
#include <malloc.h>

using namespace sph_astro_test;

namespace {

constexpr int COLS = 3;
// bytes per owned atom: d_a, d2_b 3 (with its row pointer), i_c
constexpr double BYTES_PER_ATOM =
    sizeof(double) + COLS * sizeof(double) + sizeof(double *) + sizeof(int);

// an ideal gas (no forces) in a periodic box of 4 000 atoms moving a few box lengths across the
// ranks' sub-domains (3 ranks: 3 slabs); every atom's values are functions of its ID
void moving_gas(const std::unique_ptr<LAMMPS_NS::LAMMPS> &lmp)
{
  commands(lmp,
           {"units lj",
            "atom_style atomic",
            "atom_modify map array sort 5 1.0",
            "lattice fcc 0.8",
            "region box block 0 10 0 10 0 10",
            "create_box 1 box",
            "create_atoms 1 box",
            "mass 1 1.0",
            "pair_style zero 1.0",
            "pair_coeff * *",
            "velocity all create 3.0 4928459 loop geom",
            "fix move all nve",
            "fix p all sph/astro/owned d_a d2_b 3 i_c",
            "variable a atom 1.5*id",
            "variable c atom 2*id",
            "variable b1 atom id+0.25",
            "variable b2 atom id+0.5",
            "variable b3 atom -id",
            "set group all d_a v_a",
            "set group all i_c v_c",
            "set group all d2_b[1] v_b1",
            "set group all d2_b[2] v_b2",
            "set group all d2_b[3] v_b3"});
}

// the atoms whose values are not those of their ID (0 if all are)
int wrong_values(const std::unique_ptr<LAMMPS_NS::LAMMPS> &lmp, bool created_are_zero = false,
                 int first_created = 0)
{
  auto *atom = lmp->atom;
  int flag, cols;
  const double *a = atom->dvector[atom->find_custom("a", flag, cols)];
  double **b = atom->darray[atom->find_custom("b", flag, cols)];
  const int *c = atom->ivector[atom->find_custom("c", flag, cols)];
  int wrong = 0;
  for (int i = 0; i < atom->nlocal; i++) {
    const double id = static_cast<double>(atom->tag[i]);
    if (created_are_zero && atom->tag[i] >= first_created) {
      wrong += a[i] != 0.0 || b[i][0] != 0.0 || b[i][1] != 0.0 || b[i][2] != 0.0 || c[i] != 0;
      continue;
    }
    wrong += a[i] != 1.5 * id || b[i][0] != id + 0.25 || b[i][1] != id + 0.5 || b[i][2] != -id ||
        c[i] != 2 * atom->tag[i];
  }
  int all;
  MPI_Allreduce(&wrong, &all, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  return all;
}

// the rank that owns each atom ID (index: ID)
std::vector<int> owners(const std::unique_ptr<LAMMPS_NS::LAMMPS> &lmp)
{
  auto *atom = lmp->atom;
  std::vector<int> owner(atom->natoms + 1, 0), all(atom->natoms + 1, 0);
  for (int i = 0; i < atom->nlocal; i++) owner[atom->tag[i]] = lmp->comm->me;
  MPI_Allreduce(owner.data(), all.data(), static_cast<int>(all.size()), MPI_INT, MPI_SUM,
                MPI_COMM_WORLD);
  return all;
}

// the atoms that another rank owns now than at the start
int moved_away(const std::unique_ptr<LAMMPS_NS::LAMMPS> &lmp, const std::vector<int> &owner_then)
{
  const std::vector<int> now = owners(lmp);
  int moved = 0;
  for (std::size_t id = 1; id < now.size(); id++) moved += now[id] != owner_then[id];
  return moved;
}

}    // namespace

// a ghost cutoff of half the box: each rank holds several ghosts per owned atom, and the fix's
// arrays (their allocations, as the C library sees them) and its memory figure are those of the
// owned atoms (fix property/atom's arrays are LAMMPS' nmax long)
TEST(OwnedProperty, HoldsNoSlotsForGhosts)
{
  auto lmp = open_lammps();
  moving_gas(lmp);
  commands(lmp, {"comm_modify cutoff 5.0", "run 0"});
  auto *atom = lmp->atom;
  ASSERT_GT(atom->nghost, 2.5 * atom->nlocal);
  // (the fix grows its slots by a quarter as atoms arrive, and the C library may hand out more)
  const double most = 2.0 * atom->nlocal + 64;
  int flag, cols;
  const double a_slots = malloc_usable_size(atom->dvector[atom->find_custom("a", flag, cols)]) /
      static_cast<double>(sizeof(double));
  const double b_slots = malloc_usable_size(atom->darray[atom->find_custom("b", flag, cols)][0]) /
      static_cast<double>(COLS * sizeof(double));
  const double c_slots = malloc_usable_size(atom->ivector[atom->find_custom("c", flag, cols)]) /
      static_cast<double>(sizeof(int));
  for (double slots : {a_slots, b_slots, c_slots}) {
    EXPECT_GE(slots, atom->nlocal);
    EXPECT_LT(slots, most) << atom->nlocal << " owned, " << atom->nghost << " ghosts";
  }
  const double counted = lmp->modify->get_fix_by_id("p")->memory_usage() / BYTES_PER_ATOM;
  EXPECT_GE(counted, atom->nlocal);
  EXPECT_LT(counted, most);
  EXPECT_EQ(wrong_values(lmp), 0);
}

// exchanges between ranks (the atoms cross the sub-domains several times), LAMMPS' atom sort
// every 5 steps (through its spare slot), deleted atoms (the last one moves into their slots),
// created atoms (0) and a restart file
TEST(OwnedProperty, ValuesFollowTheirAtoms)
{
  const std::string restart = "test_fix_sph_astro_owned.restart";
  LAMMPS_NS::bigint natoms;
  {
    auto lmp = open_lammps();
    moving_gas(lmp);
    natoms = lmp->atom->natoms;
    const auto owner_then = owners(lmp);
    commands(lmp, {"run 1000"});
    if (lmp->comm->nprocs > 1) EXPECT_GT(moved_away(lmp, owner_then), natoms / 2);
    EXPECT_EQ(wrong_values(lmp), 0);
    commands(lmp,
             {"region corner block 0 2 0 2 0 2", "delete_atoms region corner compress no",
              "create_atoms 1 single 5.1 5.2 5.3", "create_atoms 1 single 1.1 8.2 3.3", "run 50"});
    EXPECT_LT(lmp->atom->natoms, natoms);
    EXPECT_EQ(wrong_values(lmp, true, natoms + 1), 0);
    commands(lmp, {"write_restart " + restart});
  }
  auto lmp = open_lammps();
  commands(lmp,
           {"read_restart " + restart, "pair_style zero 1.0", "pair_coeff * *", "fix move all nve",
            "fix p all sph/astro/owned d_a d2_b 3 i_c", "run 50"});
  EXPECT_EQ(wrong_values(lmp, true, natoms + 1), 0);
  MPI_Barrier(MPI_COMM_WORLD);
  if (lmp->comm->me == 0) std::remove(restart.c_str());
}

// write_data writes the values as fix property/atom does, and read_data reads them back into a
// box made first (the fix needs a box): create_box, the fix, read_data ... add append fix p NULL
// p. The atoms read_data creates get their slots (read_data sets no per-atom values of fixes; it
// stopped with a segmentation fault), also without the section: their values are 0 and can be set
TEST(OwnedProperty, DataFileRoundTrip)
{
  const std::string data = "test_fix_sph_astro_owned.data";
  const std::string plain = "test_fix_sph_astro_owned_nofix.data";
  LAMMPS_NS::bigint natoms;
  {
    auto lmp = open_lammps();
    moving_gas(lmp);
    commands(lmp, {"run 100", "write_data " + data, "write_data " + plain + " nofix"});
    natoms = lmp->atom->natoms;
  }
  for (const bool section : {true, false}) {
    auto lmp = open_lammps();
    commands(lmp,
             {"units lj", "atom_style atomic", "atom_modify map array", "lattice fcc 0.8",
              "region box block 0 10 0 10 0 10", "create_box 1 box", "pair_style zero 1.0",
              "fix p all sph/astro/owned d_a d2_b 3 i_c",
              section ? "read_data " + data + " add append fix p NULL p"
                      : "read_data " + plain + " add append"});
    ASSERT_EQ(lmp->atom->natoms, natoms);
    if (section) {
      EXPECT_EQ(wrong_values(lmp), 0);
    } else {
      EXPECT_EQ(wrong_values(lmp, true, 1), 0);    // all 0
      commands(lmp,
               {"variable a atom 1.5*id", "variable c atom 2*id", "variable b1 atom id+0.25",
                "variable b2 atom id+0.5", "variable b3 atom -id", "set group all d_a v_a",
                "set group all i_c v_c", "set group all d2_b[1] v_b1", "set group all d2_b[2] v_b2",
                "set group all d2_b[3] v_b3"});
      EXPECT_EQ(wrong_values(lmp), 0);
    }
    commands(lmp, {"fix move all nve", "run 100"});
    EXPECT_EQ(wrong_values(lmp), 0) << (section ? "with" : "without") << " the section";
  }
  int me;
  MPI_Comm_rank(MPI_COMM_WORLD, &me);
  MPI_Barrier(MPI_COMM_WORLD);
  if (me == 0) {
    std::remove(data.c_str());
    std::remove(plain.c_str());
  }
}

TEST_F(BadInputTest, OwnedPropertyArguments)
{
  expect_error("fix p all sph/astro/owned", "expected one or more of d_NAME");
  expect_error("fix p all sph/astro/owned d_a q", "'q' is not one of d_NAME");
  expect_error("fix p all sph/astro/owned d_a ghost yes", "'ghost' is not one of d_NAME");
  expect_error("fix p all sph/astro/owned rmass", "'rmass' is not one of d_NAME");
  // an array without its number of columns, and writedata without yes or no
  expect_error("fix p all sph/astro/owned d2_b",
               "fix sph/astro/owned: d2_b needs its number of columns (d2_NAME N, an integer N "
               ">= 1); nothing follows it");
  expect_error("fix p all sph/astro/owned i2_b d_a",
               "fix sph/astro/owned: i2_b needs its number of columns (i2_NAME N, an integer N "
               ">= 1); got 'd_a'");
  expect_error("fix p all sph/astro/owned d2_b 0", "d2_b needs its number of columns");
  expect_error("fix p all sph/astro/owned d_a writedata",
               "fix sph/astro/owned: writedata needs yes or no; nothing follows it");
  expect_error("fix p all sph/astro/owned d_a writedata d_b",
               "fix sph/astro/owned: writedata needs yes or no; got 'd_b'");
  for (const char *flag : {"yes", "no"})
    EXPECT_EQ(error_of(lmp, std::string("fix p all sph/astro/owned d_a d2_b 3 writedata ") + flag),
              "");
}
