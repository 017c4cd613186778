/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: long-range self-gravity from LAMMPS' MSM (open boundaries)
------------------------------------------------------------------------- */

// kspace_style msm/sph/astro/gravity ACCURACY: LAMMPS' multilevel summation (Hardy 2006; Hardy
// et al. 2009, Parallel Computing 35, 164) with the masses as charges and -G in place of the
// Coulomb prefactor (sph_astro_gravity_kspace.h): it supplies -G sum m_i m_j gamma(r_ij/a)/a
// over all pairs (a = the pair cutoff), the pair style sph/astro/gravity the softened rest.
// LAMMPS' MSM refuses systems whose charges do not sum to zero; for open boundaries the
// multilevel sum is exact for any total mass (the top grid level is summed directly), so the
// gravity variant allows it. Periodic boxes are refused: a periodic self-gravitating system
// needs the neutralising background that only the Ewald/PPPM variant supplies. The grid levels
// are shared among the MPI ranks as in LAMMPS' MSM but with the grid points at cell corners, which
// mends LAMMPS' MSM with more than 2 ranks along an axis (set_grid_local_corners below).

#include "msm_sph_astro_gravity.h"

#include "fix.h"
#include "sph_astro_gravity_kspace.h"
#include "sph_astro_pair_coeff.h"
#include "sph_astro_shrink_wrap.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "grid3d.h"
#include "math_const.h"
#include "math_extra.h"
#include "memory.h"
#include "modify.h"
#include "neighbor.h"
#include "pair.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

using namespace LAMMPS_NS;
using namespace SPHAstro;

static constexpr int OFFSET = 16384;    // as in LAMMPS' msm.cpp: int(-0.75) must be -1
static constexpr const char *STYLE = "kspace_style msm/sph/astro/gravity";
// LAMMPS' MSM takes at most 10 grid levels (MAX_LEVELS in msm.cpp): 2^9 points along an axis;
// past that it stops with "Too many MSM grid levels" and, as a library, frees its levels twice
static constexpr int MAX_POINTS = 512;
// a box LAMMPS will wrap at the run's setup to more than this factor longer or shorter along
// an axis than at init has MSM choose its grid and cutoff for the wrapped box (init)
static constexpr double WRAP_CHOICE = 2.0;
// MSM's direct-sum weights (stencil points x levels) beyond this stop the run (7 arrays of
// doubles: 0.9 GB)
static constexpr double MAX_STENCIL = 16777216.0;
// an atom farther from the centre of mass than this times the other atoms' RMS distance is
// warned about at init (a uniform ball: 1.29; Evrard's profile: 1.41)
static constexpr double FAR_ATOM = 10.0;

namespace {
// what a user can do about an atom far from the rest
std::string remedies(bool growth)
{
  return fmt::format("remove such atoms (delete_atoms), {}set the grid (kspace_modify mesh: its "
                     "error then grows with the box) or sum directly (pair_style "
                     "sph/astro/gravity without kspace_style)",
                     growth ? "raise the bound (kspace_modify mesh/growth), " : "");
}

// the atom farthest from the centre of mass, which stretches an open box most: its ID, its
// distance and the other atoms' RMS distance from the centre of mass (collective)
struct FarAtom {
  tagint tag;
  double distance, rms;
  std::string text() const
  {
    return fmt::format("atom {} lies {:.6g} from the centre of mass (the other atoms' RMS "
                       "distance from it: {:.6g})",
                       tag, distance, rms);
  }
};

FarAtom farthest_atom(LAMMPS *lmp)
{
  const Atom *atom = lmp->atom;
  double **x = atom->x;
  const int nlocal = atom->nlocal;
  double local[4] = {0.0, 0.0, 0.0, 0.0}, sum[4];
  for (int i = 0; i < nlocal; i++) {
    const double m = atom->rmass ? atom->rmass[i] : atom->mass[atom->type[i]];
    for (int d = 0; d < 3; d++) local[d] += m * x[i][d];
    local[3] += m;
  }
  MPI_Allreduce(local, sum, 4, MPI_DOUBLE, MPI_SUM, lmp->world);
  double centre[3];
  for (int d = 0; d < 3; d++) centre[d] = sum[3] > 0.0 ? sum[d] / sum[3] : 0.0;
  struct {
    double r2;
    int rank;
  } mine = {-1.0, lmp->comm->me}, far;
  tagint tag = 0;
  double r2sum = 0.0, r2all = 0.0;
  for (int i = 0; i < nlocal; i++) {
    double r2 = 0.0;
    for (int d = 0; d < 3; d++) r2 += (x[i][d] - centre[d]) * (x[i][d] - centre[d]);
    r2sum += r2;
    if (r2 > mine.r2) {
      mine.r2 = r2;
      tag = atom->tag[i];
    }
  }
  MPI_Allreduce(&mine, &far, 1, MPI_DOUBLE_INT, MPI_MAXLOC, lmp->world);
  MPI_Bcast(&tag, 1, MPI_LMP_TAGINT, far.rank, lmp->world);
  MPI_Allreduce(&r2sum, &r2all, 1, MPI_DOUBLE, MPI_SUM, lmp->world);
  const double others = static_cast<double>(std::max<bigint>(atom->natoms - 1, 1));
  far.r2 = std::max(far.r2, 0.0);
  return {tag, std::sqrt(far.r2), std::sqrt(std::max(r2all - far.r2, 0.0) / others)};
}

// the power of two MSM::set_grid_global rounds n to: the nearer one in log2
double msm_power_of_two(double n)
{
  n = std::max(n, 2.0);
  const double k = std::log2(n);
  return std::exp2(k - std::floor(k) > 0.5 ? std::ceil(k) : std::floor(k));
}
}    // namespace

// the split radius and grid of the run that wrote the restart file read (fix sph/astro's
// restart record), nullptr if none
static const double *restart_continuation_state(LAMMPS *lmp)
{
  for (Fix *fix : lmp->modify->get_fix_list()) {
    auto *store = dynamic_cast<ContinuationStore *>(fix);
    const std::vector<double> *kept = store ? store->restart_continuation() : nullptr;
    if (kept && kept->size() == MSMSPHAstroGravity::CONTINUATION_VALUES) return kept->data();
  }
  return nullptr;
}

MSMSPHAstroGravity::MSMSPHAstroGravity(LAMMPS *lmp) : MSM(lmp)
{
  G_ = 0.0;
  warn_nonneutral = 2;    // allow (and do not warn about) a non-zero total mass
  ensure_mass_charge(lmp, STYLE);
}

void MSMSPHAstroGravity::settings(int narg, char **arg)
{
  check_accuracy(lmp, STYLE, narg, arg);
  MSM::settings(narg, arg);
}

void MSMSPHAstroGravity::init()
{
  schedule_ = nullptr;    // fix sph/astro longrange sync sets it at its init, after this
  if (domain->dimension == 2)
    error->all(FLERR,
               "{}: LAMMPS' MSM works in 3d only; in 2d use pair_style sph/astro/gravity "
               "without a kspace style (direct summation)",
               STYLE);
  if (domain->xperiodic || domain->yperiodic || domain->zperiodic)
    error->all(FLERR,
               "{}: boundary {} is periodic; MSM gravity needs non-periodic boundaries (f, s "
               "or m) in x, y and z (for periodic boxes use kspace_style pppm/sph/astro/gravity)",
               STYLE, boundary_string(lmp));
  check_hybrid_coeffs(lmp, STYLE);
  G_ = gravity_constant(lmp, STYLE);
  masses_to_charges(lmp);
  // MSM::init chooses the split radius (the pair's cutoff) and the grid for the box of this
  // run's start. A run that continues another at the step where that one ended (a second run
  // command, or the run that wrote the restart file read) keeps that run's instead: the ones
  // chosen anew would give other forces (on a collapsing ball with a hot core, x, v and u 3.7e-4
  // apart, relative to their largest values, 8 steps after a restart written during a run)
  double kept[CONTINUATION_VALUES];
  bool continuing = false;
  if (last_step_ == update->ntimestep && spacing_[0] > 0.0) {
    const std::vector<double> state = continuation_state();
    std::copy(state.begin(), state.end(), kept);
    continuing = true;
  } else {
    const double *stored = restart_continuation_state(lmp);
    continuing = stored && static_cast<bigint>(stored[0]) == update->ntimestep;
    if (continuing) std::copy_n(stored, CONTINUATION_VALUES, kept);
  }
  continuing = continuing && !gridflag;    // (a grid given with kspace_modify mesh stays)
  const int adjust = adjust_cutoff_flag;
  if (continuing) {
    int dim;
    auto *pair_cutoff = static_cast<double *>(force->pair->extract("cut_coul", dim));
    if (pair_cutoff) *pair_cutoff = kept[1];
    gridflag = 1;    // (MSM::init then takes this grid and cutoff as given)
    adjust_cutoff_flag = 0;
    nx_msm_max = static_cast<int>(kept[2]);
    ny_msm_max = static_cast<int>(kept[3]);
    nz_msm_max = static_cast<int>(kept[4]);
  }
  {
    // MSM chooses its grid and cutoff for the box it sees at init; LAMMPS wraps a shrink-wrapped
    // box around the atoms only afterwards, at the run's setup. A box that grows there has its
    // grid refined to the spacing of init (setup); one that differs by more than a factor
    // WRAP_CHOICE along an axis has them chosen for the wrapped box: with the box of init, an
    // atom 100 from a cloud of radius 5 (box 12 -> 106) had MSM choose a grid of 8 points for
    // 12 and the others' relative RMS force error was 0.25 for 1e-4, and a box created 2000
    // long around that cloud kept the cutoff 1350 chosen for it with a spacing of 1.25 (a
    // direct-sum stencil beyond memory). Within that factor the box of init is kept, which is
    // the created box or that of the run before.
    double lo[3], hi[3];
    bool other = false;
    if (shrink_wrapped_box(lmp, lo, hi))
      for (int d = 0; d < 3; d++) {
        const double ratio = (hi[d] - lo[d]) / domain->prd[d];
        other = other || ratio > WRAP_CHOICE || ratio < 1.0 / WRAP_CHOICE;
      }
    BoxScope wrapped(domain, lo, hi, other);
    // accuracy estimates with a positive prefactor G and the reference force
    ScopedGravityConstants constants(force, G_, gravity_reference_force(lmp, G_));
    for (double &h : spacing_) h = 0.0;    // MSM::init chooses the grid for this box
    check_levels_at_init();
    MSM::init();
  }
  if (continuing) {
    gridflag = 0;
    adjust_cutoff_flag = adjust;
    std::copy_n(kept + 5, 3, spacing_);
    if (comm->me == 0)
      utils::logmesg(lmp,
                     "{}: split radius {:.8g} and grid {} {} {} of the run continued (step {}) "
                     "kept\n",
                     STYLE, cutoff, nx_msm[0], ny_msm[0], nz_msm[0], update->ntimestep);
  }
  qqrd2e = -G_;    // attraction

  // an atom far from the rest stretches the shrink-wrapped box that MSM's grid spans; its
  // cutoff, chosen for the accuracy relative to the force at the box's size (F_ref), grows with
  // the box: an atom 1000 from a ball of 4000 atoms along x, y and z made it 323 (its pair part
  // summed every pair: LAMMPS stopped with "Neighbor list overflow")
  if (domain->nonperiodic == 2 && atom->natoms > 1) {
    const FarAtom far = farthest_atom(lmp);
    if (far.distance > FAR_ATOM * far.rms && comm->me == 0) {
      error->warning(FLERR,
                     "{}: {}, {:.3g} times that: the shrink-wrapped box reaches out to it, and "
                     "MSM's grid and cutoff (now {:.6g}) grow with the box, the cost with "
                     "them; {}",
                     STYLE, far.text(), far.distance / far.rms, cutoff, remedies(false));
      utils::flush_buffers(lmp);
    }
  }
}

/* ----------------------------------------------------------------------
   kspace_modify mesh/growth F: within a run the finest grid may hold at most F times the
   points chosen at init (refine_grid_to_box)
------------------------------------------------------------------------- */

int MSMSPHAstroGravity::modify_param(int narg, char **arg)
{
  if (strcmp(arg[0], "mesh/growth") != 0) return 0;
  if (narg < 2) utils::missing_cmd_args(FLERR, "kspace_modify mesh/growth", error);
  const double growth = utils::numeric(FLERR, arg[1], false, lmp);
  if (!(growth >= 1.0))
    error->all(FLERR,
               "kspace_modify mesh/growth {}: the bound on the growth of the grid of {} must be "
               ">= 1 (a factor of the points chosen at init, e.g. 128)",
               arg[1], STYLE);
  growth_ = growth;
  return 2;
}

/* ----------------------------------------------------------------------
   The number of points along each axis that MSM::set_grid_global will choose, predicted as it
   does, against the 512 LAMMPS' MSM takes (MAX_POINTS): a box stretched by a far atom asks for
   more. With the cutoff adjusted (the default) the spacing is that of Hardy's cost estimate,
   h = (3072 (p+1) / ((p-1) (448 pi + 28 pi (p+1) + 1701)))^(1/6) (V/N)^(1/3) for order p+1
   (Hardy 2006, as in LAMMPS' msm.cpp); with the cutoff given the points double until MSM's
   error estimate meets the accuracy; a grid given with kspace_modify mesh is taken as given.
------------------------------------------------------------------------- */

void MSMSPHAstroGravity::check_levels_at_init()
{
  const double *prd = domain->prd;
  const char axis[3] = {'x', 'y', 'z'};
  double npoints[3];
  if (gridflag) {
    const int given[3] = {nx_msm_max, ny_msm_max, nz_msm_max};
    for (int d = 0; d < 3; d++)
      if (msm_power_of_two(given[d]) > MAX_POINTS)
        error->all(FLERR,
                   "kspace_modify mesh {} {} {}: {} takes at most {} grid points along an axis "
                   "(LAMMPS' MSM: 10 levels)",
                   nx_msm_max, ny_msm_max, nz_msm_max, STYLE, MAX_POINTS);
    return;
  }
  if (atom->natoms == 0) return;
  if (adjust_cutoff_flag) {
    const int p = order - 1;
    const double hmin =
        std::pow(3072.0 * (p + 1) / (p - 1) /
                     (448.0 * MathConst::MY_PI + 56.0 * MathConst::MY_PI * order / 2 + 1701.0),
                 1.0 / 6.0) *
        std::cbrt(prd[0] * prd[1] * prd[2] / static_cast<double>(atom->natoms));
    for (int d = 0; d < 3; d++) npoints[d] = msm_power_of_two(std::floor(prd[d] / hmin));
  } else {
    // the members MSM::init sets before it chooses the grid
    two_charge();
    int dim = 0;
    auto *p_cutoff = static_cast<double *>(force->pair->extract("cut_coul", dim));
    if (!p_cutoff) return;    // (MSM::init names the pair style)
    cutoff = *p_cutoff;
    qsum_qsq(0);
    accuracy = accuracy_absolute >= 0.0 ? accuracy_absolute : accuracy_relative * two_charge_force;
    for (int d = 0; d < 3; d++) {
      npoints[d] = 2.0;
      double err = 2.0 * accuracy;
      while (err > accuracy && npoints[d] <= MAX_POINTS) {
        npoints[d] *= 2.0;
        err = estimate_1d_error(prd[d] / npoints[d], prd[d]);
      }
    }
  }
  for (int d = 0; d < 3; d++)
    if (npoints[d] > MAX_POINTS)
      error->all(FLERR,
                 "{}: the box {:.6g} x {:.6g} x {:.6g} asks for {:.0f} grid points along {} "
                 "for the accuracy, more than the {} LAMMPS' MSM takes (10 levels); {}: {}",
                 STYLE, prd[0], prd[1], prd[2], npoints[d], axis[d], MAX_POINTS,
                 farthest_atom(lmp).text(), remedies(false));
}

std::vector<double> MSMSPHAstroGravity::continuation_state() const
{
  return {static_cast<double>(last_step_),
          cutoff,
          static_cast<double>(nx_msm[0]),
          static_cast<double>(ny_msm[0]),
          static_cast<double>(nz_msm[0]),
          spacing_[0],
          spacing_[1],
          spacing_[2]};
}

void MSMSPHAstroGravity::compute(int eflag, int vflag)
{
  last_step_ = update->ntimestep;
  // fix sph/astro longrange sync: the forces only where every particle ends its step, kept
  // apart; in between only the energy and virial when asked for (its forces are taken back)
  LongRangeSchedule *split = schedule_;
  const bool energy_only = split && !split->long_range_due();
  if (energy_only && !eflag && !vflag) return;
  masses_to_charges(lmp);
  qsum_qsq(0);
  q2 = qsqsum * G_;
  if (split) split->long_range_before();
  MSM::compute(eflag, vflag);
  if (energy_only)
    split->long_range_discard();
  else if (split)
    split->long_range_after(cutoff);
}

/* ----------------------------------------------------------------------
   LAMMPS' MSM::setup, then the grid levels re-partitioned among the ranks with grid points at
   cell corners (set_grid_local_corners below) and the grids allocated for that partition
------------------------------------------------------------------------- */

void MSMSPHAstroGravity::setup()
{
  // the spacing of the grid MSM chose at init (on the box of the run's setup) is the one kept
  // as the box changes, from the run's setup on
  const bool chosen = spacing_[0] > 0.0;
  if (chosen) refine_grid_to_box();
  check_direct_stencil();
  MSM::setup();
  if (!chosen) {
    const int npoints[3] = {nx_msm[0], ny_msm[0], nz_msm[0]};
    for (int d = 0; d < 3; d++) spacing_[d] = domain->prd[d] / npoints[d];
    points_init_ = static_cast<double>(npoints[0]) * npoints[1] * npoints[2];
  }
  deallocate();
  set_grid_local_corners();
  allocate();
}

/* ----------------------------------------------------------------------
   MSM's direct sum on every level covers the cutoff a: a stencil of 8 (2 a / h + 1)^3 grid
   points for the spacing h (MSM::setup), whose weights and those of the virial (7 arrays) it
   keeps for every level. Too many spacings in the cutoff ask for more than any memory: the
   accuracy 1e-20 made MSM choose a cutoff 485 for a spacing of 1.5 (2.2e9 points on each of 4
   levels, whose byte count overflowed: "Failed to allocate -67781918720 bytes")
------------------------------------------------------------------------- */

void MSMSPHAstroGravity::check_direct_stencil()
{
  const double *prd = domain->prd;
  const int npoints[3] = {nx_msm[0], ny_msm[0], nz_msm[0]};
  double points = 8.0, spans = 0.0;
  for (int d = 0; d < 3; d++) {
    const double span = std::floor(2.0 * cutoff * npoints[d] / prd[d]);
    points *= span + 1.0;
    spans = std::max(spans, 0.5 * span);
  }
  if (points * levels <= MAX_STENCIL) return;
  error->all(FLERR,
             "{}: its cutoff {:.6g} spans {:.0f} grid spacings ({:.6g} {:.6g} {:.6g}), and its "
             "direct sums would hold {:.3g} weights on each of {} levels ({:.3g} GB); the "
             "accuracy {:g} asks for that cutoff: use a larger accuracy (1e-6 takes a cutoff of "
             "about 9 spacings) or sum directly (pair_style sph/astro/gravity without "
             "kspace_style)",
             STYLE, cutoff, spans, prd[0] / npoints[0], prd[1] / npoints[1], prd[2] / npoints[2],
             points, levels, 7.0 * 8.0 * points * levels / 1.0e9, accuracy_relative);
}

/* ----------------------------------------------------------------------
   The grid spacing of the run's start kept as a shrink-wrapped box grows. LAMMPS calls setup()
   at every re-wrap of the box (Domain::reset_box); MSM keeps its number of grid points, so its
   spacing grows with the box, and the error of MSM's interpolation grows as (h/a)^(p-1) for
   the spacing h, the split radius a and order p+1 (Hardy et al. 2009, sec. 3): an Evrard
   collapse whose halo widens the box 1.6x ends with 2.5e-3 of energy error, against 8.2e-5
   with the grid refined as here. Here the points along an axis double (a power of two, as MSM needs)
   whenever the spacing would exceed the one of the run's start (the grid chosen at init, on
   the box of the run's setup); they never halve. A grid given with kspace_modify mesh stays
   as given. The finest grid holds at most mesh/growth times the points chosen at init and
   512 along an axis: past that the run stops, naming the atom farthest from the centre of mass.
------------------------------------------------------------------------- */

void MSMSPHAstroGravity::refine_grid_to_box()
{
  if (gridflag) return;
  const int before[3] = {nx_msm[0], ny_msm[0], nz_msm[0]};
  const double *prd = domain->prd;
  int wanted[3];
  bool finer = false;
  for (int d = 0; d < 3; d++) {
    wanted[d] = before[d];
    while (prd[d] / wanted[d] > spacing_[d] && wanted[d] <= MAX_POINTS) wanted[d] *= 2;
    finer = finer || wanted[d] != before[d];
  }
  if (!finer) return;
  // the bound: an atom escaping from the rest would double the points with every doubling of
  // the box (8 -> 64 along each axis made each step of 401 atoms take 7 s), the cost of MSM
  // growing with them at a fixed cutoff and spacing
  const double points = static_cast<double>(wanted[0]) * wanted[1] * wanted[2];
  const int longest = std::max({wanted[0], wanted[1], wanted[2]});
  const bool beyond_growth = points > growth_ * points_init_;
  if (beyond_growth || longest > MAX_POINTS) {
    const std::string limit = beyond_growth
        ? fmt::format("more than {:g} times the {:.0f} points of the run's start (kspace_modify "
                      "mesh/growth {:g})",
                      growth_, points_init_, growth_)
        : fmt::format("more than the {} points along an axis LAMMPS' MSM takes (10 levels)",
                      MAX_POINTS);
    error->all(FLERR,
               "{}: on step {} the box {:.6g} x {:.6g} x {:.6g} needs a grid of {} {} {} to keep "
               "the spacing of the run's start ({:.6g} {:.6g} {:.6g}: the accuracy), {}; {}: {}",
               STYLE, update->ntimestep, prd[0], prd[1], prd[2], wanted[0], wanted[1], wanted[2],
               spacing_[0], spacing_[1], spacing_[2], limit, farthest_atom(lmp).text(),
               remedies(beyond_growth));
  }
  // the per-level grids are sized by the levels being replaced
  if (peratom_allocate_flag) deallocate_peratom();
  const int adjust = adjust_cutoff_flag;
  adjust_cutoff_flag = 0;    // the split radius (pair cutoff) stays: only the grid changes
  gridflag = 1;
  nx_msm_max = wanted[0];
  ny_msm_max = wanted[1];
  nz_msm_max = wanted[2];
  set_grid_global();
  gridflag = 0;
  adjust_cutoff_flag = adjust;
  if (comm->me == 0)
    utils::logmesg(lmp,
                   "{}: grid {} {} {} -> {} {} {} on step {} (box {:.6g} {:.6g} {:.6g}: the "
                   "spacing of the run's start, {:.6g} {:.6g} {:.6g}, kept)\n",
                   STYLE, before[0], before[1], before[2], nx_msm[0], ny_msm[0], nz_msm[0],
                   update->ntimestep, domain->prd[0], domain->prd[1], domain->prd[2], spacing_[0],
                   spacing_[1], spacing_[2]);
  utils::flush_buffers(lmp);
}

/* ----------------------------------------------------------------------
   MSM::set_grid_local of LAMMPS (4 Feb 2025, src/KSPACE/msm.cpp) with one change: the grid
   points a rank owns on each level are assigned with the points at cell corners (Grid3d shift
   0), where MSM puts them; LAMMPS assigns them with Grid3d's default, cell centres (shift 0.5).

   Why: MSM::compute restricts level n onto level n+1 only on the ranks active on level n, and a
   rank restricts onto the coarse points it owns. With cell centres and more than 2 ranks along
   an axis, the owner of a coarse point may own no point of the finer level: with 3 ranks the
   single point of a 1-point level (centre 0.5) belongs to the middle rank, which owns nothing of
   the 2-point level below (centres 0.25 and 0.75), so it never restricts onto that point and
   the charge of the coarsest level is lost. With corners, coarse point i sits where fine point
   2i sits and both belong to the same rank. Measured with open boundaries (1061 particles, MSM
   1e-5, grid 8, order 10): relative RMS force error against direct summation 2.3e-3 with
   LAMMPS' partition on 3 ranks (any axis) and on 4 as 4x1x1, 1.4e-5 with this one on every
   grid, as on 1 rank (stock msm with charges: 2.6e-4 against 2.7e-8,
   examples/gravity_sphere/in.msm_stock_ranks).
------------------------------------------------------------------------- */

void MSMSPHAstroGravity::set_grid_local_corners()
{
  const double *prd = triclinic ? domain->prd_lamda : domain->prd;
  const double *sublo = triclinic ? domain->sublo_lamda : domain->sublo;
  const double *subhi = triclinic ? domain->subhi_lamda : domain->subhi;
  const int periodic[3] = {domain->xperiodic, domain->yperiodic, domain->zperiodic};
  int *in_lo[3] = {nxlo_in, nylo_in, nzlo_in};
  int *in_hi[3] = {nxhi_in, nyhi_in, nzhi_in};
  int *out_lo[3] = {nxlo_out, nylo_out, nzlo_out};
  int *out_hi[3] = {nxhi_out, nyhi_out, nzhi_out};
  int *out_all_lo[3] = {&nxlo_out_all, &nylo_out_all, &nzlo_out_all};
  int *out_all_hi[3] = {&nxhi_out_all, &nyhi_out_all, &nzhi_out_all};
  const int direct_lo[3] = {nxlo_direct, nylo_direct, nzlo_direct};
  const int direct_hi[3] = {nxhi_direct, nyhi_direct, nzhi_direct};
  int *beta[3] = {betax, betay, betaz};

  // stencil of the particle-to-grid mapping
  nlower = -(order - 1) / 2;
  nupper = order / 2;

  for (int n = 0; n < levels; n++) {
    memory->destroy3d_offset(qgrid[n], nzlo_out[n], nylo_out[n], nxlo_out[n]);
    memory->destroy3d_offset(egrid[n], nzlo_out[n], nylo_out[n], nxlo_out[n]);
    {
      Grid3d partition(lmp, world, nx_msm[n], ny_msm[n], nz_msm[n]);
      partition.set_shift_grid(0.0);
      partition.setup_grid(nxlo_in[n], nxhi_in[n], nylo_in[n], nyhi_in[n], nzlo_in[n], nzhi_in[n],
                           nxlo_out[n], nxhi_out[n], nylo_out[n], nyhi_out[n], nzlo_out[n],
                           nzhi_out[n]);
    }
    const int npoints[3] = {nx_msm[n], ny_msm[n], nz_msm[n]};

    // ghost points: the particles of my sub-domain (plus half the skin on the finest level)
    // reach them; coarser levels need room for the direct sum and the restriction
    double dist[3];
    const double cuthalf = (n == 0) ? 0.5 * neighbor->skin : 0.0;
    dist[0] = dist[1] = dist[2] = cuthalf;
    if (triclinic) MathExtra::tribbox(domain->h, cuthalf, &dist[0]);

    for (int d = 0; d < 3; d++) {
      const int nlo =
          static_cast<int>((sublo[d] - dist[d] - boxlo[d]) * npoints[d] / prd[d] + OFFSET) - OFFSET;
      const int nhi =
          static_cast<int>((subhi[d] + dist[d] - boxlo[d]) * npoints[d] / prd[d] + OFFSET) - OFFSET;
      if (n == 0) {
        *out_all_lo[d] = nlo + nlower;
        *out_all_hi[d] = nhi + nupper;
      }
      // the direct sum uses the +z hemisphere only: no direct-sum ghosts below in z
      out_lo[d][n] = (d < 2) ? nlo + std::min(-order, direct_lo[d]) : nlo - order;
      out_hi[d][n] = nhi + std::max(order, direct_hi[d]);

      // extra grid points beyond a non-periodic boundary, on the ranks that own grid points
      if (domain->nonperiodic && !periodic[d] && in_lo[d][n] <= in_hi[d][n]) {
        if (in_lo[d][n] == 0) in_lo[d][n] = alpha[n];
        out_lo[d][n] = std::max(out_lo[d][n], alpha[n]);
        if (n == 0) *out_all_lo[d] = std::max(*out_all_lo[d], alpha[0]);
        if (in_hi[d][n] == npoints[d] - 1) in_hi[d][n] = beta[d][n];
        out_hi[d][n] = std::min(out_hi[d][n], beta[d][n]);
        if (n == 0) *out_all_hi[d] = std::min(*out_all_hi[d], beta[d][0]);
      }
    }

    // ranks without grid points on this level leave its communication
    set_proc_grid(n);
    ngrid[n] = (nxhi_out[n] - nxlo_out[n] + 1) * (nyhi_out[n] - nylo_out[n] + 1) *
        (nzhi_out[n] - nzlo_out[n] + 1);
  }
}
