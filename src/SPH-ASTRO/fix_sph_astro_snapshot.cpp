/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// fix ID group sph/astro/snapshot N FILE [precision float|double] [units L M T] [pad P]
//
// Every N steps (and at the setup of a run on a multiple of N, as dump does) the particles of
// the group go to FILE with '*' replaced by the step, in the HDF5 layout of SWIFT snapshots
// (Schaller et al. 2024, MNRAS 530, 2378) that the SWIFT frontend of yt reads; PartType0 holds
// the gas, with GADGET-2's names (Springel 2005, MNRAS 364, 1105) beside SWIFT's where yt asks
// for them (Density, InternalEnergy, SmoothingLength = kernel support radius). Coordinates are
// shifted so that the box starts at 0 (the shift is the Header attribute "LAMMPS box origin")
// and wrapped into periodic boxes. Each rank packs its particles; rank 0 receives them rank by
// rank and writes each rank's rows into the datasets (serial HDF5, only rank 0 opens the file).

#include "fix_sph_astro_snapshot.h"

#include "pair_sph_astro.h"
#include "sph_astro_fields.h"
#include "sph_astro_kernel.h"
#include "sph_astro_options.h"
#include "sph_astro_state.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "lammps.h"
#include "memory.h"
#include "modify.h"
#include "update.h"
#include "utils.h"

#include <hdf5.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <vector>

using namespace LAMMPS_NS;
using namespace FixConst;

namespace {

// columns of a packed particle row
enum { X = 0, V = 3, MASS = 6, RHO, H, U, ID, PRESSURE, ALPHA, NCOL };

// unit exponents (length, mass, time) of a dataset, as SWIFT writes them per dataset
struct Dimension {
  double L, M, t;
};

// SWIFT's five units (U_L, U_M, U_t in cgs; current and temperature 1: A and K)
double unit_factor(const double *unit, const Dimension &d)
{
  return std::pow(unit[0], d.L) * std::pow(unit[1], d.M) * std::pow(unit[2], d.t);
}

// HDF5 calls return a negative value on failure
hid_t check(hid_t id, Error *error, const char *what)
{
  if (id < 0) error->one(FLERR, "fix sph/astro/snapshot: HDF5 failed to {}", what);
  return id;
}

void attribute(hid_t loc, const char *name, hid_t type, int n, const void *data, Error *error)
{
  const hsize_t dims[1] = {static_cast<hsize_t>(n)};
  const hid_t space = H5Screate_simple(1, dims, nullptr);
  const hid_t attr =
      check(H5Acreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT), error, name);
  check(H5Awrite(attr, type, data), error, name);
  H5Aclose(attr);
  H5Sclose(space);
}

void attribute(hid_t loc, const char *name, double value, Error *error)
{
  attribute(loc, name, H5T_NATIVE_DOUBLE, 1, &value, error);
}

void attribute(hid_t loc, const char *name, int value, Error *error)
{
  attribute(loc, name, H5T_NATIVE_INT, 1, &value, error);
}

// fixed-length string (h5py gives it as bytes, as yt's SWIFT frontend expects for Code)
void attribute(hid_t loc, const char *name, const std::string &value, Error *error)
{
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, value.size() > 0 ? value.size() : 1);
  H5Tset_strpad(type, H5T_STR_NULLPAD);
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attr =
      check(H5Acreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT), error, name);
  check(H5Awrite(attr, type, value.c_str()), error, name);
  H5Aclose(attr);
  H5Sclose(space);
  H5Tclose(type);
}

hid_t make_group(hid_t file, const char *name, Error *error)
{
  return check(H5Gcreate2(file, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), error, name);
}

// a dataset of n rows and width columns (width 1: one-dimensional) with SWIFT's unit
// attributes
hid_t dataset(hid_t loc, const char *name, hid_t type, hsize_t n, int width, const Dimension &d,
              const double *unit, const char *description, Error *error)
{
  const hsize_t dims[2] = {n, static_cast<hsize_t>(width)};
  const hid_t space = H5Screate_simple(width == 1 ? 1 : 2, dims, nullptr);
  const hid_t set =
      check(H5Dcreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), error, name);
  H5Sclose(space);
  const float exponents[3] = {static_cast<float>(d.L), static_cast<float>(d.M),
                              static_cast<float>(d.t)};
  const float zero = 0.0f;
  attribute(set, "U_L exponent", H5T_NATIVE_FLOAT, 1, &exponents[0], error);
  attribute(set, "U_M exponent", H5T_NATIVE_FLOAT, 1, &exponents[1], error);
  attribute(set, "U_t exponent", H5T_NATIVE_FLOAT, 1, &exponents[2], error);
  attribute(set, "U_I exponent", H5T_NATIVE_FLOAT, 1, &zero, error);
  attribute(set, "U_T exponent", H5T_NATIVE_FLOAT, 1, &zero, error);
  attribute(set, "a-scale exponent", H5T_NATIVE_FLOAT, 1, &zero, error);
  attribute(set, "h-scale exponent", H5T_NATIVE_FLOAT, 1, &zero, error);
  const double factor = unit_factor(unit, d);
  attribute(set, "Conversion factor to CGS (not including cosmological corrections)", factor,
            error);
  attribute(set, "Conversion factor to physical CGS (including cosmological corrections)", factor,
            error);
  attribute(set, "Description", std::string(description), error);
  return set;
}

}    // namespace

FixSPHAstroSnapshot::FixSPHAstroSnapshot(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), pad_(0), single_(false), unit_given_(false), last_written_(-1),
    pair_(nullptr), rho_(-1), h_(-1), u_(-1)
{
  if (narg < 5) utils::missing_cmd_args(FLERR, "fix sph/astro/snapshot", error);
  nevery = utils::inumeric(FLERR, arg[3], false, lmp);
  if (nevery <= 0)
    error->all(FLERR, "fix sph/astro/snapshot: every N = {} must be a positive integer", arg[3]);
  pattern_ = arg[4];
  if (pattern_.find('*') == std::string::npos)
    error->all(FLERR,
               "fix sph/astro/snapshot: file name {} needs a '*' (replaced by the step: one "
               "file per snapshot)",
               pattern_);
  unit_[0] = unit_[1] = unit_[2] = 1.0;
  int iarg = 5;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "precision") == 0) {
      if (iarg + 2 > narg)
        utils::missing_cmd_args(FLERR, "fix sph/astro/snapshot precision", error);
      if (strcmp(arg[iarg + 1], "float") == 0)
        single_ = true;
      else if (strcmp(arg[iarg + 1], "double") == 0)
        single_ = false;
      else
        error->all(FLERR, "fix sph/astro/snapshot: precision {} is not one of: float, double",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(arg[iarg], "units") == 0) {
      if (iarg + 4 > narg) utils::missing_cmd_args(FLERR, "fix sph/astro/snapshot units", error);
      for (int k = 0; k < 3; k++) {
        unit_[k] = utils::numeric(FLERR, arg[iarg + 1 + k], false, lmp);
        if (!(unit_[k] > 0.0))
          error->all(FLERR,
                     "fix sph/astro/snapshot: units {} = {} must be > 0 (the length, mass and "
                     "time units in cm, g and s)",
                     k == 0 ? "L" : (k == 1 ? "M" : "T"), arg[iarg + 1 + k]);
      }
      unit_given_ = true;
      iarg += 4;
    } else if (strcmp(arg[iarg], "pad") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix sph/astro/snapshot pad", error);
      pad_ = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (pad_ < 0 || pad_ > 20)
        error->all(FLERR, "fix sph/astro/snapshot: pad {} must be between 0 and 20", arg[iarg + 1]);
      iarg += 2;
    } else
      error->all(FLERR,
                 "fix sph/astro/snapshot: unknown keyword '{}'; allowed: precision, units, pad",
                 arg[iarg]);
  }
  restart_global = 1;
}

int FixSPHAstroSnapshot::setmask()
{
  return END_OF_STEP;
}

std::string FixSPHAstroSnapshot::filename(bigint step) const
{
  const std::string number = pad_ > 0 ? fmt::format("{:0{}d}", step, pad_) : std::to_string(step);
  std::string name = pattern_;
  return name.replace(name.find('*'), 1, number);
}

void FixSPHAstroSnapshot::init()
{
  if (domain->triclinic)
    error->all(FLERR,
               "fix sph/astro/snapshot: triclinic boxes are not supported (SWIFT and "
               "GADGET snapshots have an orthogonal box)");
  if (!atom->tag_enable)
    error->all(FLERR, "fix sph/astro/snapshot needs atom IDs (they are the ParticleIDs)");
  SPHAstro::StateIndex state;
  if (!SPHAstro::find_state(lmp, state))
    error->all(FLERR,
               "fix sph/astro/snapshot needs the SPH-ASTRO state: define pair_style "
               "sph/astro and fix sph/astro first");
  rho_ = state.rho;
  h_ = state.h;
  u_ = state.u;
  pair_ = dynamic_cast<PairSPHAstro *>(force->pair_match("^sph/astro$", 0, 0));
  if (!pair_) error->all(FLERR, "fix sph/astro/snapshot requires pair_style sph/astro");
  // two fixes with one file name would overwrite each other's snapshots
  const auto mine = std::filesystem::path(pattern_).lexically_normal();
  for (Fix *fix : modify->get_fix_by_style("^sph/astro/snapshot$")) {
    auto *other = dynamic_cast<FixSPHAstroSnapshot *>(fix);
    if (other && other != this &&
        std::filesystem::path(other->pattern()).lexically_normal() == mine)
      error->all(FLERR,
                 "fix sph/astro/snapshot: fixes {} and {} both write {} (the one would overwrite "
                 "the other's snapshots); give them different file names",
                 id, other->id,
                 pattern_ == other->pattern() ? pattern_ : pattern_ + " and " + other->pattern());
  }
  if (!unit_given_) {
    // U_L, U_M, U_t of LAMMPS' unit styles with ftm2v = mvv2e = 1 (those fix sph/astro runs)
    const std::string style = update->unit_style;
    if (style == "lj" || style == "cgs") {
      unit_[0] = unit_[1] = unit_[2] = 1.0;
    } else if (style == "si") {
      unit_[0] = 100.0, unit_[1] = 1000.0, unit_[2] = 1.0;
    } else if (style == "micro") {
      unit_[0] = 1.0e-4, unit_[1] = 1.0e-12, unit_[2] = 1.0e-6;
    } else if (style == "nano") {
      unit_[0] = 1.0e-7, unit_[1] = 1.0e-18, unit_[2] = 1.0e-9;
    } else
      error->all(FLERR,
                 "fix sph/astro/snapshot: no cgs units known for units {}; give them with the "
                 "keyword units L M T",
                 style);
  }
}

void FixSPHAstroSnapshot::setup(int)
{
  // as dump: a snapshot at the setup of a run that starts on a multiple of N, unless this step
  // was written already (the end of the previous run, or the step of a restart file)
  if (update->ntimestep % nevery == 0 && last_written_ != update->ntimestep) write();
}

void FixSPHAstroSnapshot::end_of_step()
{
  if (last_written_ != update->ntimestep) write();
}

// the particles of the group as rows of NCOL doubles; returns the count
int FixSPHAstroSnapshot::pack(double *buf, const double *origin)
{
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  const double *rho = atom->dvector[rho_];
  const double *h = atom->dvector[h_];
  const double *u = atom->dvector[u_];
  const double *pressure = pair_->fields().pressure;
  const double *alpha = pair_->alpha_per_atom();
  int n = 0;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    double *row = buf + static_cast<size_t>(n) * NCOL;
    double x[3] = {atom->x[i][0], atom->x[i][1], atom->x[i][2]};
    imageint image = atom->image[i];
    domain->remap(x, image);    // into the periodic box
    for (int d = 0; d < 3; d++) {
      row[X + d] = x[d] - origin[d];
      row[V + d] = atom->v[i][d];
    }
    row[MASS] = atom->rmass ? atom->rmass[i] : atom->mass[atom->type[i]];
    row[RHO] = rho[i];
    row[H] = h[i];
    row[U] = u[i];
    row[ID] = static_cast<double>(atom->tag[i]);
    row[PRESSURE] = pressure ? pressure[i] : 0.0;
    row[ALPHA] = alpha ? alpha[i] : pair_->options().alpha;
    n++;
  }
  return n;
}

void FixSPHAstroSnapshot::write()
{
  if (!pair_ || pair_->computed_step() != update->ntimestep ||
      pair_->computed_nlocal() != atom->nlocal)
    error->all(FLERR,
               "fix sph/astro/snapshot: pair sph/astro has not evaluated step {} (a snapshot "
               "is written during a run)",
               update->ntimestep);
  last_written_ = update->ntimestep;
  const int dimension = domain->dimension;
  const bigint total = group->count(igroup);

  // the written box starts at 0: periodic dimensions at boxlo; open ones at the lower of boxlo
  // and the lowest particle, and end at the higher of boxhi and the highest particle (between
  // reneighbourings particles may leave a shrink-wrapped box)
  double lo[3], hi[3], origin[3], box[3];
  for (int d = 0; d < 3; d++) lo[d] = domain->boxlo[d], hi[d] = -domain->boxhi[d];
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->mask[i] & groupbit)
      for (int d = 0; d < 3; d++)
        if (!domain->periodicity[d]) {
          lo[d] = std::min(lo[d], atom->x[i][d]);
          hi[d] = std::min(hi[d], -atom->x[i][d]);
        }
  double extent[6] = {lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]}, global[6];
  MPI_Allreduce(extent, global, 6, MPI_DOUBLE, MPI_MIN, world);
  for (int d = 0; d < 3; d++) {
    origin[d] = global[d];
    box[d] = -global[3 + d] - global[d];
  }

  int nme = 0;
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->mask[i] & groupbit) nme++;
  int nmax;
  MPI_Allreduce(&nme, &nmax, 1, MPI_INT, MPI_MAX, world);
  double *buf;
  memory->create(buf, static_cast<bigint>(std::max(nmax, 1)) * NCOL, "sph/astro/snapshot:buf");
  nme = pack(buf, origin);
  const bool has_alpha = pair_->alpha_per_atom() != nullptr;

  if (comm->me != 0) {
    // rank 0 asks each rank in turn, so that only one rank's rows are in flight
    int ready;
    MPI_Recv(&ready, 0, MPI_INT, 0, 0, world, MPI_STATUS_IGNORE);
    MPI_Send(buf, nme * NCOL, MPI_DOUBLE, 0, 0, world);
    memory->destroy(buf);
    return;
  }

  const std::string name = filename(update->ntimestep);
  const hid_t file = H5Fcreate(name.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (file < 0) error->one(FLERR, "fix sph/astro/snapshot: cannot create file {}", name);
  const double time = update->atime + (update->ntimestep - update->atimestep) * update->dt;

  // Header: GADGET-2's attributes (six particle types, gas is type 0) and SWIFT's
  const hid_t header = make_group(file, "Header", error);
  attribute(header, "BoxSize", H5T_NATIVE_DOUBLE, 3, box, error);
  attribute(header, "Code", std::string("SWIFT"), error);    // yt's SWIFT frontend needs it
  attribute(header, "Dimension", dimension, error);
  long long npart[6] = {static_cast<long long>(total), 0, 0, 0, 0, 0};
  unsigned int low[6] = {static_cast<unsigned int>(total & 0xffffffffLL), 0, 0, 0, 0, 0};
  unsigned int high[6] = {static_cast<unsigned int>(total >> 32), 0, 0, 0, 0, 0};
  const double masses[6] = {0, 0, 0, 0, 0, 0};
  const int flags[6] = {0, 0, 0, 0, 0, 0};
  attribute(header, "NumPart_ThisFile", H5T_NATIVE_LLONG, 6, npart, error);
  attribute(header, "NumPart_Total", H5T_NATIVE_UINT, 6, low, error);
  attribute(header, "NumPart_Total_HighWord", H5T_NATIVE_UINT, 6, high, error);
  attribute(header, "MassTable", H5T_NATIVE_DOUBLE, 6, masses, error);
  attribute(header, "Flag_Entropy_ICs", H5T_NATIVE_INT, 6, flags, error);
  attribute(header, "NumFilesPerSnapshot", 1, error);
  attribute(header, "Time", time, error);
  attribute(header, "Redshift", 0.0, error);
  attribute(header, "Scale-factor", 1.0, error);
  attribute(header, "LAMMPS box origin", H5T_NATIVE_DOUBLE, 3, origin, error);
  long long step = update->ntimestep;
  attribute(header, "LAMMPS step", H5T_NATIVE_LLONG, 1, &step, error);
  attribute(header, "LAMMPS units", std::string(update->unit_style), error);
  H5Gclose(header);

  const hid_t units = make_group(file, "Units", error);
  attribute(units, "Unit length in cgs (U_L)", unit_[0], error);
  attribute(units, "Unit mass in cgs (U_M)", unit_[1], error);
  attribute(units, "Unit time in cgs (U_t)", unit_[2], error);
  attribute(units, "Unit current in cgs (U_I)", 1.0, error);
  attribute(units, "Unit temperature in cgs (U_T)", 1.0, error);
  H5Gclose(units);

  // SWIFT's run-time groups that its readers open: no cosmology, all periodic or none
  bool periodic = true;
  for (int d = 0; d < dimension; d++) periodic = periodic && domain->periodicity[d];
  hid_t g = make_group(file, "RuntimePars", error);
  attribute(g, "PeriodicBoundariesOn", periodic ? 1 : 0, error);
  H5Gclose(g);
  g = make_group(file, "Policy", error);
  attribute(g, "cosmological integration", 0, error);
  attribute(g, "hydro", 1, error);
  H5Gclose(g);
  g = make_group(file, "Cosmology", error);
  attribute(g, "Cosmological run", 0, error);
  H5Gclose(g);
  g = make_group(file, "HydroScheme", error);
  const auto &opt = pair_->options();
  attribute(g, "Scheme", std::string("SPH-ASTRO pair_style sph/astro"), error);
  attribute(g, "Kernel function", std::string(SPHAstro::kernel_name(opt.kernel)), error);
  attribute(g, "Kernel support radius in units of h", opt.kernel_radius(), error);
  if (opt.eos.type != SPHAstro::EOSType::ISOTHERMAL)
    attribute(g, "Adiabatic index", opt.eos.gamma, error);
  attribute(g, "Dimension", dimension, error);
  H5Gclose(g);
  H5Gclose(make_group(file, "Parameters", error));
  H5Gclose(make_group(file, "SubgridScheme", error));
  g = make_group(file, "Code", error);
  attribute(g, "Code", std::string("SPH-ASTRO (LAMMPS plugin)"), error);
  attribute(g, "LAMMPS version", std::string(lmp->version), error);
  H5Gclose(g);

  // PartType0: one dataset per field; GADGET's names where yt reads them
  const hid_t gas = make_group(file, "PartType0", error);
  const hid_t real = single_ ? H5T_NATIVE_FLOAT : H5T_NATIVE_DOUBLE;
  const hsize_t n = static_cast<hsize_t>(total);
  struct Field {
    const char *name;
    int column, width;
    hid_t type;
    Dimension dim;
    const char *description;
  };
  std::vector<Field> fields = {
      {"Coordinates",
       X,
       3,
       H5T_NATIVE_DOUBLE,
       {1, 0, 0},
       "Positions of the particles, shifted by -(LAMMPS box origin) and wrapped into periodic "
       "boxes"},
      {"Velocities", V, 3, real, {1, 0, -1}, "Velocities of the particles"},
      {"Masses", MASS, 1, real, {0, 1, 0}, "Masses of the particles"},
      {"Densities", RHO, 1, real, {-3, 1, 0}, "SPH densities (d_rho)"},
      {"SmoothingLengths",
       H,
       1,
       real,
       {1, 0, 0},
       "Smoothing lengths h (d_h); the kernel support is Kernel support radius x h"},
      {"SmoothingLength",
       H,
       1,
       real,
       {1, 0, 0},
       "Kernel support radii (GADGET convention, the smoothing length yt uses)"},
      {"InternalEnergies", U, 1, real, {2, 0, -2}, "Specific internal energies (d_u)"},
      {"ParticleIDs", ID, 1, H5T_NATIVE_ULLONG, {0, 0, 0}, "LAMMPS atom IDs"}};
  fields.push_back({"Pressures",
                    PRESSURE,
                    1,
                    real,
                    {-1, 1, -2},
                    "Pressures of the latest force evaluation of pair sph/astro"});
  if (has_alpha)
    fields.push_back({"ViscosityParameters",
                      ALPHA,
                      1,
                      real,
                      {0, 0, 0},
                      "Artificial viscosity alpha of fix sph/astro/switch"});
  std::vector<hid_t> sets;
  for (const auto &f : fields)
    sets.push_back(dataset(gas, f.name, f.type, n, f.width, f.dim, unit_, f.description, error));
  // GADGET's names of SWIFT's fields, as further links to the same data
  check(H5Lcreate_hard(gas, "Densities", gas, "Density", H5P_DEFAULT, H5P_DEFAULT), error,
        "link Density");
  check(H5Lcreate_hard(gas, "InternalEnergies", gas, "InternalEnergy", H5P_DEFAULT, H5P_DEFAULT),
        error, "link InternalEnergy");

  // rows of rank 0, then of every other rank in turn; precision float: the values beyond the
  // float range (written as inf) per field, with the first atom and value
  struct Overflow {
    bigint count = 0;
    tagint atom = 0;
    double value = 0.0;
  };
  std::vector<Overflow> overflow(fields.size());
  const double support = pair_->options().kernel_radius();
  hsize_t offset = 0;
  for (int proc = 0; proc < comm->nprocs; proc++) {
    int rows = nme;
    if (proc > 0) {
      int ready = 0;
      MPI_Status status;
      MPI_Send(&ready, 0, MPI_INT, proc, 0, world);
      MPI_Recv(buf, nmax * NCOL, MPI_DOUBLE, proc, 0, world, &status);
      MPI_Get_count(&status, MPI_DOUBLE, &rows);
      rows /= NCOL;
    }
    if (rows == 0) continue;
    for (size_t k = 0; k < fields.size(); k++) {
      const auto &f = fields[k];
      std::vector<double> column;    // the support radius is computed, not packed
      const double *src = buf;
      hsize_t mem_dims[2] = {static_cast<hsize_t>(rows), NCOL};
      hsize_t mem_start[2] = {0, static_cast<hsize_t>(f.column)};
      if (strcmp(f.name, "SmoothingLength") == 0) {
        column.resize(rows);
        for (int i = 0; i < rows; i++) column[i] = support * buf[static_cast<size_t>(i) * NCOL + H];
        src = column.data();
        mem_dims[1] = 1;
        mem_start[1] = 0;
      }
      if (f.type == H5T_NATIVE_FLOAT)
        for (int i = 0; i < rows; i++)
          for (int w = 0; w < f.width; w++) {
            const double value = src[static_cast<size_t>(i) * mem_dims[1] + mem_start[1] + w];
            if (std::isfinite(value) && std::fabs(value) > FLT_MAX && overflow[k].count++ == 0) {
              overflow[k].atom = static_cast<tagint>(buf[static_cast<size_t>(i) * NCOL + ID]);
              overflow[k].value = value;
            }
          }
      const hsize_t count[2] = {static_cast<hsize_t>(rows), static_cast<hsize_t>(f.width)};
      const hid_t mem = H5Screate_simple(2, mem_dims, nullptr);
      H5Sselect_hyperslab(mem, H5S_SELECT_SET, mem_start, nullptr, count, nullptr);
      const hid_t space = H5Dget_space(sets[k]);
      const hsize_t file_start[2] = {offset, 0};
      H5Sselect_hyperslab(space, H5S_SELECT_SET, file_start, nullptr, count, nullptr);
      check(H5Dwrite(sets[k], H5T_NATIVE_DOUBLE, mem, space, H5P_DEFAULT, src), error, f.name);
      H5Sclose(space);
      H5Sclose(mem);
    }
    offset += rows;
  }
  if (offset != n)
    error->one(FLERR, "fix sph/astro/snapshot: gathered {} particles of {} in the group", offset,
               total);
  for (hid_t set : sets) H5Dclose(set);
  H5Gclose(gas);
  if (H5Fclose(file) < 0) error->one(FLERR, "fix sph/astro/snapshot: cannot close file {}", name);
  memory->destroy(buf);
  std::string beyond;
  for (size_t k = 0; k < fields.size(); k++)
    if (overflow[k].count > 0)
      beyond += fmt::format("{}{} ({} value{}, first: atom {}, {:.6g})", beyond.empty() ? "" : ", ",
                            fields[k].name, overflow[k].count, overflow[k].count > 1 ? "s" : "",
                            overflow[k].atom, overflow[k].value);
  if (!beyond.empty()) {
    error->warning(FLERR,
                   "fix sph/astro/snapshot precision float: step {}, {}: values beyond the float "
                   "range ({:.6g}) written as inf: {}; use precision double",
                   update->ntimestep, name, FLT_MAX, beyond);
    utils::flush_buffers(lmp);
  }
}

// global restart data: N and the step of the last snapshot
void FixSPHAstroSnapshot::write_restart(FILE *fp)
{
  if (comm->me != 0) return;
  const double list[2] = {static_cast<double>(nevery), static_cast<double>(last_written_)};
  const int size = sizeof(list);
  fwrite(&size, sizeof(int), 1, fp);
  fwrite(list, sizeof(double), 2, fp);
}

void FixSPHAstroSnapshot::restart(char *buf)
{
  const auto *list = reinterpret_cast<double *>(buf);
  last_written_ = static_cast<bigint>(list[1]);
}
