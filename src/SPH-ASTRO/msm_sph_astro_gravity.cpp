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

#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "grid3d.h"
#include "math_extra.h"
#include "memory.h"
#include "modify.h"
#include "neighbor.h"
#include "pair.h"
#include "update.h"

#include <algorithm>

using namespace LAMMPS_NS;
using namespace SPHAstro;

static constexpr int OFFSET = 16384;    // as in LAMMPS' msm.cpp: int(-0.75) must be -1
static constexpr const char *STYLE = "kspace_style msm/sph/astro/gravity";

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
    // accuracy estimates with a positive prefactor G and the reference force
    ScopedGravityConstants constants(force, G_, gravity_reference_force(lmp, G_));
    for (double &h : spacing_) h = 0.0;    // MSM::init chooses the grid for this box
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
  // within a run the grid follows the box; at init and at a run's setup the spacing of the
  // grid chosen there is the one to keep
  const bool running = spacing_[0] > 0.0 && !update->setupflag;
  if (running) refine_grid_to_box();
  MSM::setup();
  if (!running) {
    const int npoints[3] = {nx_msm[0], ny_msm[0], nz_msm[0]};
    for (int d = 0; d < 3; d++) spacing_[d] = std::max(spacing_[d], domain->prd[d] / npoints[d]);
  }
  deallocate();
  set_grid_local_corners();
  allocate();
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
   as given.
------------------------------------------------------------------------- */

void MSMSPHAstroGravity::refine_grid_to_box()
{
  if (gridflag) return;
  const int before[3] = {nx_msm[0], ny_msm[0], nz_msm[0]};
  int wanted[3];
  bool finer = false;
  for (int d = 0; d < 3; d++) {
    wanted[d] = before[d];
    while (domain->prd[d] / wanted[d] > spacing_[d]) wanted[d] *= 2;
    finer = finer || wanted[d] != before[d];
  }
  if (!finer) return;
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
