/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// LAMMPS-driven tests of fix sph/astro/snapshot: the snapshot read back with the HDF5 C API
// against LAMMPS' per-atom state (x, v, mass, rho, h, u, ID) and its header (time, box, count,
// units); the steps written, the restart of the output schedule, a group, float precision, a
// 2d box, the unit systems and bad input. Runs on any number of ranks: the state of every
// rank is gathered to rank 0 and compared with the file by atom ID (ctest runs it on 1 rank
// and on 3).

#include "styles_fixture.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "group.h"

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <string>
#include <vector>

using namespace sph_astro_test;

namespace {

bool file_exists(const std::string &name)
{
  FILE *fp = fopen(name.c_str(), "rb");
  if (fp) fclose(fp);
  return fp != nullptr;
}

int rank()
{
  int me;
  MPI_Comm_rank(MPI_COMM_WORLD, &me);
  return me;
}

// a snapshot file read with the HDF5 C API (rank 0)
class Snapshot {
 public:
  explicit Snapshot(const std::string &name)
  {
    file_ = H5Fopen(name.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  }
  ~Snapshot()
  {
    if (file_ >= 0) H5Fclose(file_);
  }
  bool ok() const { return file_ >= 0; }
  bool has(const char *path) const { return H5Lexists(file_, path, H5P_DEFAULT) > 0; }
  // a dataset as doubles (HDF5 converts floats and integers), rows x columns
  std::vector<double> data(const char *path, int *columns = nullptr) const
  {
    const hid_t set = H5Dopen2(file_, path, H5P_DEFAULT);
    if (set < 0) return {};
    const hid_t space = H5Dget_space(set);
    hsize_t dims[2] = {0, 1};
    const int rank = H5Sget_simple_extent_dims(space, dims, nullptr);
    if (columns) *columns = rank == 2 ? static_cast<int>(dims[1]) : 1;
    std::vector<double> out(dims[0] * (rank == 2 ? dims[1] : 1));
    if (!out.empty()) H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data());
    H5Sclose(space);
    H5Dclose(set);
    return out;
  }
  // bytes per element of a dataset in the file
  size_t element_size(const char *path) const
  {
    const hid_t set = H5Dopen2(file_, path, H5P_DEFAULT);
    const hid_t type = H5Dget_type(set);
    const size_t size = H5Tget_size(type);
    H5Tclose(type);
    H5Dclose(set);
    return size;
  }
  // a numeric attribute of a group or dataset as doubles
  std::vector<double> attr(const char *object, const char *name) const
  {
    const hid_t attr = H5Aopen_by_name(file_, object, name, H5P_DEFAULT, H5P_DEFAULT);
    if (attr < 0) return {};
    const hid_t space = H5Aget_space(attr);
    std::vector<double> out(std::max<hssize_t>(H5Sget_simple_extent_npoints(space), 1));
    H5Aread(attr, H5T_NATIVE_DOUBLE, out.data());
    H5Sclose(space);
    H5Aclose(attr);
    return out;
  }
  std::string text(const char *object, const char *name) const
  {
    const hid_t attr = H5Aopen_by_name(file_, object, name, H5P_DEFAULT, H5P_DEFAULT);
    if (attr < 0) return "";
    const hid_t type = H5Aget_type(attr);
    std::string out(H5Tget_size(type), '\0');
    H5Aread(attr, type, &out[0]);
    H5Tclose(type);
    H5Aclose(attr);
    return out.substr(0, out.find('\0'));
  }

 private:
  hid_t file_;
};

// LAMMPS' state of the atoms of a group, gathered to rank 0 by atom ID
struct Particle {
  double x[3], v[3], mass, rho, h, u;
};
std::map<long, Particle> gather_state(const std::unique_ptr<LAMMPS_NS::LAMMPS> &lmp,
                                      const std::string &group = "all")
{
  auto *atom = lmp->atom;
  int flag, cols;
  const double *rho = atom->dvector[atom->find_custom("rho", flag, cols)];
  const double *h = atom->dvector[atom->find_custom("h", flag, cols)];
  const double *u = atom->dvector[atom->find_custom("u", flag, cols)];
  const int groupbit = lmp->group->bitmask[lmp->group->find(group)];
  std::vector<double> mine;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    const double m = atom->rmass ? atom->rmass[i] : atom->mass[atom->type[i]];
    for (double value :
         {static_cast<double>(atom->tag[i]), atom->x[i][0], atom->x[i][1], atom->x[i][2],
          atom->v[i][0], atom->v[i][1], atom->v[i][2], m, rho[i], h[i], u[i]})
      mine.push_back(value);
  }
  int nprocs, n = static_cast<int>(mine.size());
  MPI_Comm_size(MPI_COMM_WORLD, &nprocs);
  std::vector<int> counts(nprocs), offsets(nprocs, 0);
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  for (int p = 1; p < nprocs; p++) offsets[p] = offsets[p - 1] + counts[p - 1];
  std::vector<double> all(offsets[nprocs - 1] + counts[nprocs - 1]);
  MPI_Allgatherv(mine.data(), n, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE,
                 MPI_COMM_WORLD);
  std::map<long, Particle> out;
  for (size_t k = 0; k < all.size(); k += 11) {
    Particle p;
    for (int d = 0; d < 3; d++) p.x[d] = all[k + 1 + d], p.v[d] = all[k + 4 + d];
    p.mass = all[k + 7], p.rho = all[k + 8], p.h = all[k + 9], p.u = all[k + 10];
    out[static_cast<long>(all[k])] = p;
  }
  return out;
}

// a per-atom vector of a compute on every rank, by atom ID (all ranks learn every value)
std::map<long, double> gather_compute(const std::unique_ptr<LAMMPS_NS::LAMMPS> &lmp, const char *id)
{
  auto *values =
      static_cast<double *>(lammps_extract_compute(lmp.get(), id, LMP_STYLE_ATOM, LMP_TYPE_VECTOR));
  const int nlocal = lmp->atom->nlocal;
  std::vector<double> mine(values, values + nlocal);
  std::vector<long> tags(lmp->atom->tag, lmp->atom->tag + nlocal);
  int nprocs;
  MPI_Comm_size(MPI_COMM_WORLD, &nprocs);
  std::map<long, double> out;
  for (int p = 0; p < nprocs; p++) {
    int n = p == rank() ? nlocal : 0;
    MPI_Bcast(&n, 1, MPI_INT, p, MPI_COMM_WORLD);
    std::vector<double> vals = p == rank() ? mine : std::vector<double>(n);
    std::vector<long> ids = p == rank() ? tags : std::vector<long>(n);
    MPI_Bcast(vals.data(), n, MPI_DOUBLE, p, MPI_COMM_WORLD);
    MPI_Bcast(ids.data(), n, MPI_LONG, p, MPI_COMM_WORLD);
    for (int k = 0; k < n; k++) out[ids[k]] = vals[k];
  }
  return out;
}

// a jittered fcc box of 4^3 cells (256 particles) whose box does not start at 0
void scene(const std::unique_ptr<LAMMPS_NS::LAMMPS> &lmp, const std::string &snapshot)
{
  const double h = 1.2 * std::cbrt(0.25);
  commands(lmp,
           {"units lj",
            "atom_style atomic",
            "atom_modify map array",
            "boundary p p p",
            "lattice fcc 4.0",
            "region box block -1.5 2.5 -3 1 0.25 4.25",
            "create_box 1 box",
            "create_atoms 1 box",
            "displace_atoms all random 0.04 0.04 0.04 4711 units box",
            "mass 1 0.25",
            "velocity all create 1.0 8675309 dist gaussian",
            "pair_style " + std::string(PAIR),
            "pair_coeff * *",
            "fix gas all sph/astro dt fixed",
            "set group all d_h " + num(h),
            "variable urand atom 1.0*(1.0+0.2*random(-1,1,991))",
            "set group all d_u v_urand",
            "neighbor " + num(0.3 * h) + " bin",
            "timestep 0.002",
            "compute atom all sph/astro/atom pressure",
            snapshot});
}

// every dataset of the snapshot against the gathered state, and the header
void expect_snapshot_matches(const std::string &name, const std::map<long, Particle> &state,
                             const LAMMPS_NS::Domain *domain, double time, size_t width = 8)
{
  Snapshot snap(name);
  ASSERT_TRUE(snap.ok()) << name;
  const size_t n = state.size();
  EXPECT_EQ(snap.attr("Header", "NumPart_Total")[0], static_cast<double>(n));
  EXPECT_EQ(snap.attr("Header", "NumPart_ThisFile")[0], static_cast<double>(n));
  EXPECT_EQ(snap.attr("Header", "NumPart_Total_HighWord")[0], 0.0);
  EXPECT_EQ(snap.attr("Header", "Dimension")[0], static_cast<double>(domain->dimension));
  EXPECT_NEAR(snap.attr("Header", "Time")[0], time, 1e-14);
  EXPECT_EQ(snap.text("Header", "Code"), "SWIFT");
  EXPECT_EQ(snap.attr("RuntimePars", "PeriodicBoundariesOn")[0], 1.0);
  const auto box = snap.attr("Header", "BoxSize");
  const auto origin = snap.attr("Header", "LAMMPS box origin");
  ASSERT_EQ(box.size(), 3u);
  ASSERT_EQ(origin.size(), 3u);
  for (int d = 0; d < 3; d++) {
    EXPECT_DOUBLE_EQ(box[d], domain->prd[d]);
    EXPECT_DOUBLE_EQ(origin[d], domain->boxlo[d]);
  }
  int columns = 0;
  const auto ids = snap.data("PartType0/ParticleIDs");
  const auto x = snap.data("PartType0/Coordinates", &columns);
  EXPECT_EQ(columns, 3);
  const auto v = snap.data("PartType0/Velocities");
  const auto m = snap.data("PartType0/Masses");
  const auto rho = snap.data("PartType0/Densities");
  const auto rho_gadget = snap.data("PartType0/Density");
  const auto h = snap.data("PartType0/SmoothingLengths");
  const auto support = snap.data("PartType0/SmoothingLength");
  const auto u = snap.data("PartType0/InternalEnergies");
  const auto u_gadget = snap.data("PartType0/InternalEnergy");
  ASSERT_EQ(ids.size(), n);
  for (const auto *column : {&m, &rho, &rho_gadget, &h, &support, &u, &u_gadget})
    ASSERT_EQ(column->size(), n);
  ASSERT_EQ(x.size(), 3 * n);
  ASSERT_EQ(v.size(), 3 * n);
  // float precision: the values rounded to float
  auto same = [width](double file, double lammps) {
    return width == 8 ? file == lammps : file == static_cast<double>(static_cast<float>(lammps));
  };
  std::set<long> seen;
  for (size_t k = 0; k < n; k++) {
    const long id = std::lround(ids[k]);
    EXPECT_TRUE(seen.insert(id).second) << "particle " << id << " written twice";
    const auto it = state.find(id);
    ASSERT_NE(it, state.end()) << "particle " << id << " is not in the group";
    const Particle &p = it->second;
    for (int d = 0; d < 3; d++) {
      // wrapped into [0, L) from LAMMPS' coordinate relative to boxlo
      double expect = std::fmod(p.x[d] - domain->boxlo[d], domain->prd[d]);
      if (expect < 0.0) expect += domain->prd[d];
      if (expect >= domain->prd[d]) expect -= domain->prd[d];
      EXPECT_NEAR(x[3 * k + d], expect, 1e-12) << "particle " << id;
      EXPECT_GE(x[3 * k + d], 0.0);
      EXPECT_LT(x[3 * k + d], box[d]);
      EXPECT_TRUE(same(v[3 * k + d], p.v[d])) << "particle " << id;
    }
    EXPECT_TRUE(same(m[k], p.mass)) << "particle " << id;
    EXPECT_TRUE(same(rho[k], p.rho)) << "particle " << id;
    EXPECT_EQ(rho_gadget[k], rho[k]);
    EXPECT_TRUE(same(h[k], p.h)) << "particle " << id;
    // the M4 kernel extends to 2h: the GADGET smoothing length is the support radius
    EXPECT_TRUE(same(support[k], 2.0 * p.h)) << "particle " << id;
    EXPECT_TRUE(same(u[k], p.u)) << "particle " << id;
    EXPECT_EQ(u_gadget[k], u[k]);
  }
  EXPECT_EQ(seen.size(), n);
  for (const char *field : {"Velocities", "Masses", "Densities", "InternalEnergies"})
    EXPECT_EQ(snap.element_size(("PartType0/" + std::string(field)).c_str()), width) << field;
  EXPECT_EQ(snap.element_size("PartType0/Coordinates"), 8u);
}

}    // namespace

// snapshots at steps 0, 5, 10 of a 10-step run; the last one against the state after the run
TEST(Snapshot, EveryDatasetMatchesTheLammpsState)
{
  auto lmp = open_lammps();
  const std::string stem = "test_snapshot_state_";
  scene(lmp, "fix snap all sph/astro/snapshot 5 " + stem + "*.hdf5");
  commands(lmp, {"run 10"});
  const auto state = gather_state(lmp);
  ASSERT_EQ(state.size(), 256u);
  // the pressures of the last force evaluation, as compute sph/astro/atom gives them
  const auto pressure = gather_compute(lmp, "atom");
  if (rank() != 0) return;
  EXPECT_TRUE(file_exists(stem + "0.hdf5"));
  EXPECT_TRUE(file_exists(stem + "5.hdf5"));
  EXPECT_FALSE(file_exists(stem + "4.hdf5"));
  expect_snapshot_matches(stem + "10.hdf5", state, lmp->domain, 10 * 0.002);
  Snapshot last(stem + "10.hdf5");
  const auto ids = last.data("PartType0/ParticleIDs");
  const auto p = last.data("PartType0/Pressures");
  ASSERT_EQ(p.size(), ids.size());
  for (size_t k = 0; k < ids.size(); k++) EXPECT_EQ(p[k], pressure.at(std::lround(ids[k])));
  // at setup u has not moved: P = (gamma - 1) rho u of the file's own columns
  Snapshot first(stem + "0.hdf5");
  const auto rho0 = first.data("PartType0/Densities");
  const auto u0 = first.data("PartType0/InternalEnergies");
  const auto p0 = first.data("PartType0/Pressures");
  ASSERT_EQ(p0.size(), 256u);
  for (size_t k = 0; k < p0.size(); k++)
    EXPECT_NEAR(p0[k], (5.0 / 3.0 - 1.0) * rho0[k] * u0[k], 1e-13 * p0[k]);
  EXPECT_EQ(first.attr("Header", "Time")[0], 0.0);
  EXPECT_EQ(first.attr("Header", "LAMMPS step")[0], 0.0);
  // lj units: every unit 1; the conversion factor of a density is 1
  for (const char *unit : {"Unit length in cgs (U_L)", "Unit mass in cgs (U_M)",
                           "Unit time in cgs (U_t)", "Unit temperature in cgs (U_T)"})
    EXPECT_EQ(last.attr("Units", unit)[0], 1.0) << unit;
  EXPECT_EQ(last.attr("PartType0/Densities", "U_L exponent")[0], -3.0);
  EXPECT_EQ(last.attr("PartType0/Densities", "U_M exponent")[0], 1.0);
  EXPECT_EQ(last.text("HydroScheme", "Kernel function"), "m4");
  EXPECT_FALSE(last.has("PartType0/ViscosityParameters"));    // there is no fix sph/astro/switch
  for (const char *step : {"0", "5", "10"}) std::remove((stem + step + ".hdf5").c_str());
}

// a group: only its particles, each once; float precision rounds all but x and IDs
TEST(Snapshot, GroupAndFloatPrecision)
{
  auto lmp = open_lammps();
  const std::string name = "test_snapshot_group_00003.hdf5";
  scene(lmp, "region low block INF INF INF INF INF 2.0 units box");
  commands(lmp,
           {"group low region low",
            "fix snap low sph/astro/snapshot 3 test_snapshot_group_*.hdf5 precision float "
            "pad 5",
            "run 3"});
  const auto state = gather_state(lmp, "low");
  ASSERT_GT(state.size(), 50u);
  ASSERT_LT(state.size(), 200u);
  if (rank() != 0) return;
  expect_snapshot_matches(name, state, lmp->domain, 3 * 0.002, 4);
  std::remove(name.c_str());
  std::remove("test_snapshot_group_00000.hdf5");
}

// the step of the last snapshot comes back from a restart file: the continued run does not
// write the restart step again, and goes on at the next multiple of N
TEST(Snapshot, RestartKeepsTheSchedule)
{
  const std::string stem = "test_snapshot_restart_", restart = "test_snapshot.restart";
  {
    auto lmp = open_lammps();
    scene(lmp, "fix snap all sph/astro/snapshot 4 " + stem + "*.hdf5");
    commands(lmp, {"run 8", "write_restart " + restart});
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank() == 0) {
    EXPECT_TRUE(file_exists(stem + "8.hdf5"));
    std::remove((stem + "8.hdf5").c_str());
  }
  MPI_Barrier(MPI_COMM_WORLD);
  auto lmp = open_lammps();
  commands(lmp,
           {"read_restart " + restart, "pair_coeff * *", "fix gas all sph/astro dt fixed",
            "neighbor " + num(0.3 * 1.2 * std::cbrt(0.25)) + " bin",
            "fix snap all sph/astro/snapshot 4 " + stem + "*.hdf5", "run 4"});
  if (rank() == 0) {
    EXPECT_FALSE(file_exists(stem + "8.hdf5")) << "the restart step was written again";
    EXPECT_TRUE(file_exists(stem + "12.hdf5"));
    EXPECT_EQ(Snapshot(stem + "12.hdf5").attr("Header", "LAMMPS step")[0], 12.0);
    for (const char *step : {"0", "4", "12"}) std::remove((stem + step + ".hdf5").c_str());
    std::remove(restart.c_str());
  }
}

// with fix sph/astro/switch: ViscosityParameters are the alpha of the last force evaluation
TEST(Snapshot, ViscosityParameters)
{
  auto lmp = open_lammps();
  scene(lmp, "fix av all sph/astro/switch morris-monaghan 0.1 1.0 0.2");
  commands(lmp,
           {"compute alpha all sph/astro/atom alpha",
            "fix snap all sph/astro/snapshot 3 test_snapshot_alpha_*.hdf5", "run 3"});
  const auto alpha = gather_compute(lmp, "alpha");
  if (rank() != 0) return;
  Snapshot snap("test_snapshot_alpha_3.hdf5");
  const auto ids = snap.data("PartType0/ParticleIDs");
  const auto a = snap.data("PartType0/ViscosityParameters");
  ASSERT_EQ(a.size(), 256u);
  ASSERT_EQ(ids.size(), 256u);
  double lo = 1.0;
  for (size_t k = 0; k < a.size(); k++) {
    EXPECT_EQ(a[k], alpha.at(std::lround(ids[k])));
    lo = std::min(lo, a[k]);
  }
  EXPECT_LT(lo, 1.0);    // the switch has moved alpha from alpha_max
  std::remove("test_snapshot_alpha_0.hdf5");
  std::remove("test_snapshot_alpha_3.hdf5");
}

// a 2d box: Dimension 2, three coordinates (z relative to zlo) as SWIFT writes them
TEST(Snapshot, TwoDimensions)
{
  auto lmp = open_lammps();
  commands(lmp,
           {"units lj", "dimension 2", "atom_style atomic", "atom_modify map array",
            "boundary p p p", "lattice sq 1.0", "region box block 0 8 0 8 -0.5 0.5",
            "create_box 1 box", "create_atoms 1 box", "mass 1 1.0",
            "pair_style " + std::string(PAIR), "pair_coeff * *", "fix gas all sph/astro",
            "set group all d_h 1.2", "set group all d_u 1.0", "neighbor 0.3 bin",
            "fix snap all sph/astro/snapshot 1 test_snapshot_2d_*.hdf5", "run 0"});
  const auto state = gather_state(lmp);
  if (rank() != 0) return;
  Snapshot snap("test_snapshot_2d_0.hdf5");
  ASSERT_TRUE(snap.ok());
  EXPECT_EQ(snap.attr("Header", "Dimension")[0], 2.0);
  EXPECT_EQ(snap.attr("HydroScheme", "Dimension")[0], 2.0);
  const auto x = snap.data("PartType0/Coordinates");
  ASSERT_EQ(x.size(), 3 * state.size());
  for (size_t k = 0; k < state.size(); k++) EXPECT_DOUBLE_EQ(x[3 * k + 2], 0.5);
  // a uniform square lattice of unit spacing and mass: rho close to 1
  const auto rho = snap.data("PartType0/Densities");
  for (double r : rho) EXPECT_NEAR(r, 1.0, 0.05);
  std::remove("test_snapshot_2d_0.hdf5");
}

// open (shrink-wrapped) boundaries: the written box starts at the lower of boxlo and the lowest
// particle and holds every particle; coordinates + origin give LAMMPS' x back
TEST(Snapshot, OpenBoundaries)
{
  auto lmp = open_lammps();
  gas(lmp, "ball", 4, PAIR, "sph/astro");
  commands(lmp,
           {"velocity all create 2.0 4711",
            "fix snap all sph/astro/snapshot 6 "
            "test_snapshot_open_*.hdf5",
            "neigh_modify every 10 delay 10 check no", "run 6"});
  const auto state = gather_state(lmp);
  if (rank() != 0) return;
  Snapshot snap("test_snapshot_open_6.hdf5");
  ASSERT_TRUE(snap.ok());
  EXPECT_EQ(snap.attr("RuntimePars", "PeriodicBoundariesOn")[0], 0.0);
  const auto box = snap.attr("Header", "BoxSize");
  const auto origin = snap.attr("Header", "LAMMPS box origin");
  const auto ids = snap.data("PartType0/ParticleIDs");
  const auto x = snap.data("PartType0/Coordinates");
  ASSERT_EQ(ids.size(), state.size());
  // the extent of the particles and the box
  double lo[3], hi[3];
  for (int d = 0; d < 3; d++) lo[d] = lmp->domain->boxlo[d], hi[d] = lmp->domain->boxhi[d];
  for (const auto &[id, p] : state)
    for (int d = 0; d < 3; d++) lo[d] = std::min(lo[d], p.x[d]), hi[d] = std::max(hi[d], p.x[d]);
  // particles left the shrink-wrapped box since the last reneighbouring (no reneighbouring in
  // the 6 steps): the written box is wider than LAMMPS'
  int outside = 0;
  for (int d = 0; d < 3; d++)
    outside += (lo[d] < lmp->domain->boxlo[d]) + (hi[d] > lmp->domain->boxhi[d]);
  EXPECT_GT(outside, 0);
  for (int d = 0; d < 3; d++) {
    EXPECT_EQ(origin[d], lo[d]);
    EXPECT_NEAR(box[d], hi[d] - lo[d], 1e-14 * (hi[d] - lo[d]));
  }
  for (size_t k = 0; k < ids.size(); k++)
    for (int d = 0; d < 3; d++) {
      EXPECT_GE(x[3 * k + d], 0.0);
      EXPECT_LE(x[3 * k + d], box[d]);
      EXPECT_NEAR(x[3 * k + d] + origin[d], state.at(std::lround(ids[k])).x[d], 1e-12);
    }
  std::remove("test_snapshot_open_0.hdf5");
  std::remove("test_snapshot_open_6.hdf5");
}

// SI units: U_L = 100 cm, U_M = 1000 g, U_t = 1 s; the keyword units overrides them
TEST(Snapshot, Units)
{
  for (const std::string keyword : {"", " units 3.0857e21 1.989e43 3.0857e16"}) {
    auto lmp = open_lammps();
    commands(lmp,
             {"units si", "atom_style atomic", "atom_modify map array", "boundary p p p",
              "lattice fcc 1.0", "region box block 0 3 0 3 0 3", "create_box 1 box",
              "create_atoms 1 box", "mass 1 0.25", "pair_style " + std::string(PAIR),
              "pair_coeff * *", "fix gas all sph/astro", "set group all d_h 0.76",
              "set group all d_u 1.0", "neighbor 0.2 bin",
              "fix snap all sph/astro/snapshot 1 test_snapshot_si_*.hdf5" + keyword, "run 0"});
    if (rank() != 0) continue;
    Snapshot snap("test_snapshot_si_0.hdf5");
    ASSERT_TRUE(snap.ok());
    const double L = keyword.empty() ? 100.0 : 3.0857e21, M = keyword.empty() ? 1000.0 : 1.989e43,
                 T = keyword.empty() ? 1.0 : 3.0857e16;
    EXPECT_EQ(snap.attr("Units", "Unit length in cgs (U_L)")[0], L);
    EXPECT_EQ(snap.attr("Units", "Unit mass in cgs (U_M)")[0], M);
    EXPECT_EQ(snap.attr("Units", "Unit time in cgs (U_t)")[0], T);
    const char *factor = "Conversion factor to CGS (not including cosmological corrections)";
    EXPECT_NEAR(snap.attr("PartType0/Densities", factor)[0], M / (L * L * L),
                1e-12 * M / (L * L * L));
    EXPECT_NEAR(snap.attr("PartType0/InternalEnergies", factor)[0], L * L / (T * T),
                1e-12 * L * L / (T * T));
    EXPECT_EQ(snap.text("Header", "LAMMPS units"), "si");
    std::remove("test_snapshot_si_0.hdf5");
  }
}

// precision float: a value beyond the float range (3.4e38) is written as inf; the snapshot
// warns, naming the fields, the first atom and its value (it wrote inf silently)
TEST(Snapshot, FloatOverflowIsWarned)
{
  const std::string log = "test_snapshot_overflow.log", name = "test_snapshot_overflow_0.hdf5";
  for (const char *precision : {"float", "double"}) {
    auto lmp = open_lammps();
    scene(lmp,
          std::string("fix snap all sph/astro/snapshot 5 test_snapshot_overflow_*.hdf5 "
                      "precision ") +
              precision);
    commands(lmp, {"set atom 7 d_u 1e40", "log " + log, "run 0", "log none"});
    if (rank() != 0) continue;
    std::ifstream in(log);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const bool is_float = std::string(precision) == "float";
    EXPECT_EQ(text.find("fix sph/astro/snapshot precision float: step 0, "
                        "test_snapshot_overflow_0.hdf5: values beyond the float range") !=
                  std::string::npos,
              is_float)
        << text;
    if (is_float) {
      EXPECT_NE(text.find("InternalEnergies (1 value, first: atom 7, 1e+40)"), std::string::npos)
          << text;
      EXPECT_NE(text.find("Pressures (1 value, first: atom 7"), std::string::npos) << text;
    }
    Snapshot snap(name);
    const auto ids = snap.data("PartType0/ParticleIDs");
    const auto u = snap.data("PartType0/InternalEnergies");
    for (size_t k = 0; k < ids.size(); k++)
      if (std::lround(ids[k]) == 7) EXPECT_EQ(std::isinf(u[k]), is_float) << precision;
    std::remove(name.c_str());
  }
  std::remove(log.c_str());
}

// two snapshot fixes writing the same files: an error naming both fix IDs and the file name
TEST(Snapshot, TwoFixesWithOneFileNameAreRefused)
{
  for (const char *other : {"test_snapshot_twice_*.hdf5", "./test_snapshot_twice_*.hdf5"}) {
    auto lmp = open_lammps();
    scene(lmp, "fix snap all sph/astro/snapshot 5 test_snapshot_twice_*.hdf5");
    commands(lmp, {std::string("fix again all sph/astro/snapshot 2 ") + other});
    const std::string message = error_of(lmp, "run 0");
    EXPECT_NE(message.find("fix sph/astro/snapshot: fixes snap and again both write "),
              std::string::npos)
        << message;
    std::remove("test_snapshot_twice_0.hdf5");
  }
  // other names: both written
  auto lmp = open_lammps();
  scene(lmp, "fix snap all sph/astro/snapshot 5 test_snapshot_twice_a_*.hdf5");
  commands(lmp, {"fix again all sph/astro/snapshot 5 test_snapshot_twice_b_*.hdf5"});
  EXPECT_EQ(error_of(lmp, "run 0"), "");
  if (rank() == 0) {
    EXPECT_TRUE(file_exists("test_snapshot_twice_a_0.hdf5"));
    EXPECT_TRUE(file_exists("test_snapshot_twice_b_0.hdf5"));
  }
  std::remove("test_snapshot_twice_a_0.hdf5");
  std::remove("test_snapshot_twice_b_0.hdf5");
}

TEST_F(BadInputTest, SnapshotArguments)
{
  commands(lmp, {"pair_style " + std::string(PAIR), "pair_coeff * *", "fix gas all sph/astro"});
  expect_error("fix s all sph/astro/snapshot 0 a_*.hdf5", "every N = 0 must be a positive");
  expect_error("fix s all sph/astro/snapshot 5 a.hdf5", "file name a.hdf5 needs a '*'");
  expect_error("fix s all sph/astro/snapshot 5 a_*.hdf5 precision half",
               "precision half is not one of: float, double");
  expect_error("fix s all sph/astro/snapshot 5 a_*.hdf5 units 1 0 1", "units M = 0 must be > 0");
  expect_error("fix s all sph/astro/snapshot 5 a_*.hdf5 colour red",
               "unknown keyword 'colour'; allowed: precision, units, pad");
}
