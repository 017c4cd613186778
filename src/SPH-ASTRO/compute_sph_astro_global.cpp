/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: global conserved quantities
------------------------------------------------------------------------- */

// compute ID group sph/astro/global -> vector of 12:
//   1 mass  2-4 momentum  5-7 angular momentum about the origin  8 kinetic energy
//   9 thermal energy sum m u (EOS-consistent u for polytropes, 0 for the isothermal gas)
//   10 potential energy (pair, kspace and fix contributions, as compute pe)
//   11 total energy  12 (E - E0)/|E0|, E0 the total energy when this compute was first
//   evaluated; fix sph/astro keeps E0 (per compute ID) across restarts.
//   13-14 smallest and largest h; 15-18 h iteration (fix sph/astro/h iterate): mean and
//   largest Newton iterations of the latest density pass, particles that failed to converge
//   since the run began, particles held at the h cap (0 without that fix)
// Sums run over the compute's group; the potential energy is that of the whole system.

#include "compute_sph_astro_global.h"

#include "sph_astro_state.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "fix_sph_astro.h"
#include "force.h"
#include "kspace.h"
#include "modify.h"
#include "pair_sph_astro.h"
#include "sph_astro_options.h"
#include "update.h"
#include "utils.h"

#include <cmath>

using namespace LAMMPS_NS;

ComputeSPHAstroGlobal::ComputeSPHAstroGlobal(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg)
{
  state_ = new SPHAstro::StateIndex();
  pair_ = nullptr;
  fix_ = nullptr;
  hfix_ = nullptr;
  own_reference_set_ = false;
  own_reference_ = 0.0;

  if (narg != 3)
    error->all(FLERR, "compute sph/astro/global takes no arguments (got {})", narg - 3);
  vector_flag = 1;
  size_vector = NVALUES;
  extvector = -1;    // sums are extensive, the relative energy error is not
  extlist = new int[NVALUES];
  for (int k = 0; k < NVALUES; k++) extlist[k] = (k <= ETOT) ? 1 : 0;
  peflag = 1;    // the potential energy must be tallied on the steps this compute is used
  timeflag = 1;
  vector = new double[NVALUES];
}

ComputeSPHAstroGlobal::~ComputeSPHAstroGlobal()
{
  delete state_;
  delete[] vector;
  delete[] extlist;
}

void ComputeSPHAstroGlobal::init()
{
  pair_ = dynamic_cast<PairSPHAstro *>(force->pair_match("^sph/astro$", 0, 0));
  if (!pair_) error->all(FLERR, "compute sph/astro/global requires pair_style sph/astro");
  if (!SPHAstro::find_state(lmp, *state_))
    error->all(FLERR, "compute sph/astro/global requires fix sph/astro (the per-particle state)");
  auto fixes = modify->get_fix_by_style("^sph/astro$");
  fix_ = fixes.empty() ? nullptr : dynamic_cast<FixSPHAstro *>(fixes.front());
  auto hfixes = modify->get_fix_by_style("^sph/astro/h$");
  hfix_ = hfixes.empty() ? nullptr : hfixes.front();
  // (fix sph/astro's init(), which follows, tells whether v or u changed since the last run)
  check_state_ = true;
}

void ComputeSPHAstroGlobal::compute_vector()
{
  invoked_vector = update->ntimestep;
  if (update->eflag_global != invoked_vector)
    error->all(FLERR, "compute sph/astro/global: energy was not tallied on step {}",
               update->ntimestep);

  double **x = atom->x;
  double **v = atom->v;
  const int *mask = atom->mask;
  const int *type = atom->type;
  const imageint *image = atom->image;
  const double *rmass = atom->rmass;
  const double *mass = atom->mass;
  const double *rho = atom->dvector[state_->rho];
  const double *u = atom->dvector[state_->u];
  const SPHAstro::EOS &eos = pair_->options().eos;
  const int nlocal = atom->nlocal;

  double local[NVALUES] = {0.0};
  uint64_t hash = 0;    // of the state read
  double unwrap[3];
  const double *h = atom->dvector[state_->h];
  double hrange[2] = {INFINITY, -INFINITY};    // -hmin, hmax for one MPI_MAX
  // with individual steps a particle inside its step enters with v and u at the current time
  // (its predictions), not those of the middle of its step
  double **vest = atom->darray[state_->vest];
  const double *uest = atom->dvector[state_->uest];
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double m = rmass ? rmass[i] : mass[type[i]];
    const bool mid = fix_ && fix_->mid_step(i);
    const double *vi = mid ? vest[i] : v[i];
    const double ui = mid ? uest[i] : u[i];
    domain->unmap(x[i], image[i], unwrap);
    local[MASS] += m;
    local[PX] += m * vi[0];
    local[PY] += m * vi[1];
    local[PZ] += m * vi[2];
    local[LX] += m * (unwrap[1] * vi[2] - unwrap[2] * vi[1]);
    local[LY] += m * (unwrap[2] * vi[0] - unwrap[0] * vi[2]);
    local[LZ] += m * (unwrap[0] * vi[1] - unwrap[1] * vi[0]);
    local[EKIN] += 0.5 * m * (vi[0] * vi[0] + vi[1] * vi[1] + vi[2] * vi[2]);
    local[ETHERM] += m * eos.energy_of(rho[i], ui);
    hash ^= SPHAstro::atom_state_hash(atom->tag[i], vi, ui);
    if (pair_->gas_type(type[i])) {    // (point masses have no h)
      hrange[0] = MIN(hrange[0], h[i]);
      hrange[1] = MAX(hrange[1], h[i]);
    }
  }
  MPI_Allreduce(local, vector, NVALUES, MPI_DOUBLE, MPI_SUM, world);
  hrange[0] = -hrange[0];
  double hall[2];
  MPI_Allreduce(hrange, hall, 2, MPI_DOUBLE, MPI_MAX, world);
  vector[HMIN] = -hall[0];
  vector[HMAX] = hall[1];
  for (int k = HITER_MEAN; k <= HCAPPED; k++)
    vector[k] = hfix_ ? hfix_->compute_vector(k - HITER_MEAN) : 0.0;

  // potential energy as compute pe: pair (sph/astro itself adds none), kspace, fixes
  double epot = 0.0, pair_energy = 0.0;
  if (force->pair) {
    double one = force->pair->eng_vdwl + force->pair->eng_coul;
    MPI_Allreduce(&one, &pair_energy, 1, MPI_DOUBLE, MPI_SUM, world);
    epot += pair_energy;
  }
  if (force->kspace) epot += force->kspace->energy;
  epot += modify->energy_global();
  vector[EPOT] = epot;
  vector[ETOT] = vector[EKIN] + vector[ETHERM] + epot;

  // E0 is the energy of the state the run began from, kept across runs that continue it: v or u
  // changed since the last run (velocity, set; fix sph/astro knows, from its state hash at the
  // run's end, or, defined since, this compute from the state it read at that step) set it anew
  uint64_t read_hash = 0;
  MPI_Allreduce(&hash, &read_hash, 1, MPI_UINT64_T, MPI_BXOR, world);
  if (check_state_) {
    check_state_ = false;
    const int changed = fix_ ? fix_->state_changed() : -1;
    if (own_reference_set_ &&
        (changed == 1 ||
         (changed == -1 && read_step_ == update->ntimestep && read_hash != read_hash_))) {
      own_reference_set_ = false;
      if (comm->me == 0)
        utils::logmesg(lmp,
                       "compute sph/astro/global {}: the reference energy E0 is reset from {:.10g} "
                       "to {:.10g} at step {}: v or u changed since the last run (velocity, set, "
                       "...)\n",
                       id, own_reference_, vector[ETOT], update->ntimestep);
    }
  }
  read_hash_ = read_hash;
  read_step_ = update->ntimestep;
  if (!own_reference_set_) {    // (fix sph/astro's: that of a restart file, if it holds one)
    own_reference_ = fix_ ? fix_->reference_energy(id, vector[ETOT]) : vector[ETOT];
    own_reference_set_ = true;
  } else if (fix_)
    fix_->reference_energy(id, own_reference_);    // (for its restart files)
  const double e0 = own_reference_;
  vector[DEREL] = (e0 != 0.0) ? (vector[ETOT] - e0) / std::fabs(e0) : vector[ETOT] - e0;
}
