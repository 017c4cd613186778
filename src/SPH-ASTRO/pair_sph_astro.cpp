/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Pair style sph/astro: the LAMMPS glue of the hydrodynamics. Options: sph_astro_options.h;
// the equations of one pair: sph_astro_iact.h; the passes over the neighbour lists:
// sph_astro_passes.h; the lists: sph_astro_neighbour_lists.h. Equations of the whole scheme
// (Monaghan 1992, ARA&A 30, 543; Price 2012, J. Comput. Phys. 231, 759):
//   rho_i = sum_j m_j W_ij
//   dv_i/dt = -sum_j m_j (P_i/rho_i^2 + P_j/rho_j^2 + Pi_ij) grad_i W_ij
//   du_i/dt = P_i/rho_i^2 sum_j m_j v_ij . grad_i W_ij + 1/2 sum_j m_j Pi_ij v_ij . grad_i W_ij
// with their grad-h, averaged-kernel, geometric-mean, density-continuity and pressure-energy
// variants (doc/pair_sph_astro.rst). The velocities of the force evaluation are the ones
// predicted by fix sph/astro (d2_vest), so the viscosity sees v at the end of the step.

#include "pair_sph_astro.h"

#include "sph_astro_comm_table.h"
#include "sph_astro_force_evaluation.h"
#include "sph_astro_gravity_kernel.h"
#include "sph_astro_neighbour_lists.h"
#include "sph_astro_options.h"
#include "sph_astro_pair_coeff.h"
#include "sph_astro_passes.h"
#include "sph_astro_scheme.h"
#include "sph_astro_sparse_message.h"
#include "sph_astro_state.h"
#include "sph_astro_timestep.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "neighbor.h"
#include "update.h"

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

using namespace LAMMPS_NS;
using namespace SPHAstro;

PairSPHAstro::PairSPHAstro(LAMMPS *lmp) :
    Pair(lmp), opt_(new PairOptions()), fields_(new Fields()), lists_(new NeighbourLists(lmp)),
    hstats_(new GradhStatistics()), state_(new StateIndex()), entropy_index_(new EntropyIndex()),
    continuity_index_(new ContinuityIndex()), step_index_(new StepIndex()), active_(nullptr),
    scheme_(new Scheme()), entropy_init_pending_(false), density_init_pending_(false),
    entropy_gamma_(0.0), restart_variable_h_(false), alpha_atom_(nullptr), alpha_force_(nullptr),
    h_cap_start_(0.0), h_cap_(0.0), sph_type_(nullptr), kernel_radius_(2.0), h_failures_(0),
    counts_step_(-1), computed_step_(-1), computed_nlocal_(-1), comm_table_(new CommTable())
{
  single_enable = 0;
  restartinfo = 1;
  // pair_coeff I J with type ranges: the types I = J it sets are SPH gas; atoms of other types
  // (point masses under pair sph/astro/gravity) are left out of every SPH sum
  one_coeff = 0;
  manybody_flag = 1;    // forces depend on densities of both partners
  // rho, P, c_s, vest[3]; h, Omega, C (pressure-energy); alpha; u (cond.); Balsara f;
  // symmetric grad v, Delta
  comm_forward = 12 + VGRAD_DATA;
  comm_reverse = VGRAD_SUMS;    // the largest reverse stage: the grad v sums
}

PairSPHAstro::~PairSPHAstro()
{
  if (copymode) return;
  fields_->destroy(memory);
  memory->destroy(sph_type_);
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
  }
  delete opt_;
  delete fields_;
  delete lists_;
  delete hstats_;
  delete state_;
  delete entropy_index_;
  delete continuity_index_;
  delete step_index_;
  delete scheme_;
  delete comm_table_;
}

/* ---------------------------------------------------------------------- */

void PairSPHAstro::settings(int narg, char **arg)
{
  opt_->parse(lmp, narg, arg);
  kernel_radius_ = opt_->kernel_radius();
  // the integrated density and its prediction live in their own per-atom state; it is
  // created here or, after read_restart, by fix sph/astro (then LAMMPS restores its values)
  if (opt_->density_continuity)
    ensure_continuity_state(lmp, "pair_style sph/astro density continuity");
  // the state (d_h, d_u, ...) exists from here on, so `set group all d_h` may follow
  ensure_state(lmp, "pair_style sph/astro");
}

// pair_coeff I J  (type ranges; the types on the diagonal are SPH gas; no parameters)
void PairSPHAstro::coeff(int narg, char **arg)
{
  if (!allocated) allocate();
  SPHAstro::set_type_pairs(lmp, "sph/astro", narg, arg, setflag);
}

void PairSPHAstro::allocate()
{
  allocated = 1;
  const int n = atom->ntypes + 1;
  memory->create(setflag, n, n, "pair:setflag");
  for (int i = 1; i < n; i++)
    for (int j = i; j < n; j++) setflag[i][j] = 0;
  memory->create(cutsq, n, n, "pair:cutsq");
  memory->create(sph_type_, n, "pair:sph_type");
}

void PairSPHAstro::init_style()
{
  const PairOptions &o = *opt_;
  active_ = nullptr;    // fix sph/astro steps individual sets it again before each evaluation
  if (!find_state(lmp, *state_))
    error->all(FLERR,
               "pair_style sph/astro needs the SPH per-particle state: define fix sph/astro "
               "(it creates fix {})",
               STATE_FIX_ID);
  *scheme_ = read_scheme(lmp, o);
  h_failures_ = 0;
  if (scheme_->entropy && !find_entropy_state(lmp, *entropy_index_))
    error->all(FLERR, "pair_style sph/astro: the entropy state fix {} is missing", ENTROPY_FIX_ID);
  // A = (gamma - 1) u / rho^(gamma - 1) holds for the gamma it was derived with: with another
  // gamma it is derived anew from u (u and the thermal energy continue)
  if (scheme_->entropy && entropy_gamma_ > 0.0 && entropy_gamma_ != o.eos.gamma) {
    if (comm->me == 0)
      error->warning(FLERR,
                     "pair_style sph/astro: gamma is {} where the entropic function A of fix "
                     "sph/astro thermal entropy was derived with {}: A is derived anew from u",
                     o.eos.gamma, entropy_gamma_);
    entropy_init_pending_ = true;
  }
  if (scheme_->entropy) entropy_gamma_ = o.eos.gamma;
  if (restart_variable_h_ && scheme_->hmode == Scheme::HMode::FIXED && comm->me == 0)
    error->warning(FLERR,
                   "pair_style sph/astro: the restart file comes from a run with fix "
                   "sph/astro/h; this run has none, so every h stays at its stored value (define "
                   "fix sph/astro/h again after read_restart)");
  restart_variable_h_ = false;
  if (domain->dimension != 2 && domain->dimension != 3)
    error->all(FLERR, "pair_style sph/astro: dimension {} not supported", domain->dimension);
  if (o.density_continuity && !find_continuity_state(lmp, *continuity_index_))
    error->all(FLERR,
               "pair_style sph/astro density continuity: the per-atom state fix {} is missing",
               CONTINUITY_FIX_ID);

  // every particle needs a positive mass and smoothing length; the ghost cutoff is set by
  // the largest h
  const int nlocal = atom->nlocal;
  const int ntypes = atom->ntypes;
  const double *h = atom->dvector[state_->h];
  const double *rmass = atom->rmass;
  const double *mass = atom->mass;
  const int *type = atom->type;
  for (int t = 1; t <= ntypes; t++) sph_type_[t] = setflag[t][t] ? 1 : 0;
  double hmax_local = 0.0, hmax = 0.0;
  for (int i = 0; i < nlocal; i++) {
    if (!sph_type_[type[i]]) continue;
    const double mi = rmass ? rmass[i] : mass[type[i]];
    if (!(mi > 0.0) || !std::isfinite(mi))
      error->one(FLERR, "pair_style sph/astro: atom {} has mass {}; the mass must be > 0",
                 atom->tag[i], mi);
    if (!(h[i] > 0.0) || !std::isfinite(h[i]))
      error->one(FLERR,
                 "pair_style sph/astro: atom {} has smoothing length h = {}; h must be > 0 "
                 "(set it with: set group all d_h VALUE)",
                 atom->tag[i], h[i]);
    hmax_local = MAX(hmax_local, h[i]);
  }
  MPI_Allreduce(&hmax_local, &hmax, 1, MPI_DOUBLE, MPI_MAX, world);
  if (atom->natoms == 0)
    error->all(FLERR,
               "pair_style sph/astro: the system holds no particles (create_atoms, read_data)");
  if (hmax <= 0.0)
    error->all(FLERR, "pair_style sph/astro: no particle has h > 0 (set group all d_h VALUE)");
  // (an h above fix sph/astro/h hmax at the start keeps its value: the cap is not below it)
  h_cap_start_ = h_cap_ = MAX(hmax, MIN(scheme_->margin * hmax, scheme_->h_max));
  // A margin beyond the default reaches at most what half the shortest periodic box length,
  // or the diagonal of a box periodic in none, serves (box_h_cap), the bound of fix
  // sph/astro/h's widening within a run; the default's room, DEFAULT_MARGIN x the largest h,
  // stays for boxes too small for that. Margin 100 in a box of side 2 (h 0.9) asked for a
  // ghost cutoff of 180, 2e8 ghost images of 32 particles; margin 20, 1.7 million (500 MB)
  const double R = o.kernel_radius(), skin = neighbor->skin;
  int axis = -1;
  const double h_cap_box = box_h_cap(lmp, R, skin, axis);
  const double h_cap_bound = MAX(h_cap_box, DEFAULT_MARGIN * hmax);
  const double h_cap_wanted = h_cap_start_;
  h_cap_start_ = h_cap_ = MAX(hmax, MIN(h_cap_wanted, h_cap_bound));
  if (h_cap_start_ < h_cap_wanted && comm->me == 0) {
    const std::string box = axis >= 0
        ? fmt::format("half the periodic box length {:.6g} in {}", domain->prd[axis], "xyz"[axis])
        : fmt::format("the box diagonal {:.6g}", R * h_cap_box);
    error->warning(FLERR,
                   "fix sph/astro/h margin {}: the ghost cutoff for h up to {} x the largest h "
                   "{:.6g} would be {:.6g}, beyond what {} needs; the run starts with h up to "
                   "{:.6g} (ghost cutoff {:.6g}): a margin beyond {} serves at most that, as "
                   "within a run",
                   scheme_->margin, scheme_->margin, hmax, R * h_cap_wanted + skin, box,
                   h_cap_start_, R * h_cap_start_ + skin, DEFAULT_MARGIN);
    utils::flush_buffers(lmp);
  }
  // a run that continues one (restart file or the run before) keeps its h cap and ghost
  // cutoff, so that it makes the same lists and h iterations; not when h outgrew the cap, the
  // cap exceeds hmax or the periodic box's bound, or it is more than CARRIED_CAP_MAX times what
  // the run would take
  carried_cap_used_ = scheme_->carried_cap >= hmax && scheme_->carried_cap <= scheme_->h_max &&
      scheme_->carried_cap_start <= CARRIED_CAP_MAX * h_cap_start_ &&
      scheme_->carried_cap_start <= MAX(hmax, h_cap_bound);
  if (carried_cap_used_) h_cap_start_ = h_cap_ = scheme_->carried_cap_start;

  const double support = o.kernel_radius() * hmax;
  if (neighbor->skin > support && comm->me == 0)
    error->warning(FLERR,
                   "pair_style sph/astro: neighbor skin {} exceeds the kernel support {}: the "
                   "neighbour lists hold many non-neighbours; a skin of 0.1-0.3 x support is "
                   "usual",
                   neighbor->skin, support);
  lists_->invalidate();
  // no LAMMPS neighbour list: the package searches the owned and ghost atoms itself
  // (sph_astro_neighbour_lists.h); LAMMPS' cutoff from init_one() sets the ghost shell
}

/* ----------------------------------------------------------------------
   the end of a run: what the neighbour search did, after LAMMPS' own neighbour statistics
------------------------------------------------------------------------- */

void PairSPHAstro::finish()
{
  if (computed_step_ < 0) return;
  const SearchStatistics &s = lists_->statistics();
  const double *nneigh = neighbour_counts();
  // (individual steps: the entries per row made, weighted alike)
  const double row_entries = s.rows_eager > 0 ? s.reach_entries : s.half_entries;
  double local[6] = {
      row_entries * s.atoms,        s.full_entries * s.atoms,          0.0,
      static_cast<double>(s.atoms), static_cast<double>(atom->nghost), lists_->memory_usage()};
  for (int i = 0; i < atom->nlocal; i++) local[2] += nneigh[i];
  double all[6];
  MPI_Allreduce(local, all, 6, MPI_DOUBLE, MPI_SUM, world);
  bigint builds[3] = {s.builds, s.step_builds, s.extensions}, builds_max[3];
  MPI_Allreduce(builds, builds_max, 3, MPI_LMP_BIGINT, MPI_MAX, world);
  bigint rows[2] = {s.rows_made, s.rows_eager}, rows_all[2];
  MPI_Allreduce(rows, rows_all, 2, MPI_LMP_BIGINT, MPI_SUM, world);
  if (comm->me != 0) return;
  const double atoms = MAX(all[3], 1.0);
  // individual steps with newton on: rows made for the atoms when first active
  const std::string entries = rows_all[1] > 0
      ? fmt::format("rows made for {:.1f} % of the particles' intervals between builds (those "
                    "with an active particle in their tree leaf); per row made: {:.1f} "
                    "reach-row entries (both directions of a pair), {:.1f} gather-row entries; "
                    "per particle:",
                    100.0 * rows_all[0] / rows_all[1], all[0] / atoms, all[1] / atoms)
      : fmt::format("per particle: {:.1f} half-list entries, {:.1f} gather-row entries,",
                    all[0] / atoms, all[1] / atoms);
  utils::logmesg(lmp,
                 "pair sph/astro neighbour search: lists made {} times after LAMMPS' builds "
                 "and {} times inside a step, extended {} times inside a step for grown h "
                 "(most on a rank); {} {:.1f} neighbours inside the kernel support, {:.2f} "
                 "ghost atoms, {:.0f} bytes of lists and tree\n",
                 builds_max[0], builds_max[1], builds_max[2], entries, all[2] / atoms,
                 all[4] / atoms, all[5] / atoms);
}

bigint PairSPHAstro::gas_outside(int groupbit) const
{
  bigint mine = 0, all = 0;
  for (int i = 0; i < atom->nlocal; i++)
    if (gas_type(atom->type[i]) && !(atom->mask[i] & groupbit)) mine++;
  MPI_Allreduce(&mine, &all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  return all;
}

bigint PairSPHAstro::point_masses_in(int groupbit) const
{
  bigint mine = 0, all = 0;
  for (int i = 0; i < atom->nlocal; i++)
    if (!gas_type(atom->type[i]) && (atom->mask[i] & groupbit)) mine++;
  MPI_Allreduce(&mine, &all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  return all;
}

double PairSPHAstro::init_one(int i, int j)
{
  if (setflag[i][j] == 0)
    error->all(FLERR, "pair_style sph/astro: pair_coeff for types {} {} is not set", i, j);
  // the ghost shell must hold every particle within R max(h_i, h_j) of an owned one
  return opt_->kernel_radius() * h_cap_start_;
}

// per-atom arrays, grown to atom->nmax (owned + ghost), only those the scene needs
void PairSPHAstro::grow_fields()
{
  const PairOptions &o = *opt_;
  fields_->grow(memory, atom->nmax,
                {scheme_->curl, o.balsara, o.tracks_signal(), o.reconstruction(),
                 o.artificial_conductivity(), o.pressure_geometric || o.pressure_energy,
                 o.pressure_energy, o.pressure_energy && gradh(), o.physical_conduction(),
                 dphidh_sums_ && gradh()});
}

PassContext PairSPHAstro::context()
{
  PassContext ctx;
  ctx.kernel = opt_->kernel;
  ctx.dim = domain->dimension;
  ctx.p = {atom->x,      atom->dvector[state_->h],    atom->type, atom->rmass, atom->mass,
           atom->nlocal, atom->nlocal + atom->nghost, sph_type_};
  ctx.half = {0, nullptr, nullptr, nullptr};
  ctx.newton = force->newton_pair != 0;
  ctx.f = fields_;
  ctx.rho = eval_density();
  ctx.rho_sum = atom->dvector[state_->rho];
  ctx.uest = atom->dvector[state_->uest];
  ctx.vest = atom->darray[state_->vest];
  ctx.dudt = atom->dvector[state_->dudt];
  ctx.force = atom->f;
  ctx.alpha = alpha_force_;
  ctx.tag = atom->tag;
  ctx.error = error;
  ctx.tally = evflag ? this : nullptr;
  ctx.pairs = nullptr;
  return ctx;
}

bool PairSPHAstro::gradh() const
{
  return scheme_->gradh();
}

// the h-rho iteration's settings: fix sph/astro/h's, the lists and the caps of this run
GradhSettings PairSPHAstro::gradh_settings() const
{
  const PairOptions &o = *opt_;
  GradhSettings s;
  s.hfact = scheme_->hfact;
  s.tolerance = scheme_->tolerance;
  s.max_iterations = scheme_->max_iterations;
  s.full = lists_->full();
  s.hlist = lists_->limits();
  s.wide = lists_->wide_rows();
  s.h_cap = h_cap_;
  s.sums = o.reconstruction() ? VelocitySums::GRADIENT
      : scheme_->curl         ? VelocitySums::CURL
                              : VelocitySums::NONE;
  s.pressure_energy = o.pressure_energy;
  s.gamma = o.eos.gamma;
  if (dphidh_sums_ && fields_->dphidh_sum) {
    s.dphidh_sum = fields_->dphidh_sum;
    s.softened = &softened_kernel(o.kernel);
  }
  return s;
}

namespace {
// the stages' communication: LAMMPS' forward and reverse communication of the pair
class PairExchange : public SPHAstro::Exchange {
 public:
  explicit PairExchange(PairSPHAstro *pair) : pair_(pair) {}
  void forward(std::initializer_list<CommField> fields) override { pair_->forward(fields); }
  void reverse(std::initializer_list<CommField> fields) override { pair_->reverse(fields); }
  void forward_chosen(std::initializer_list<CommField> fields, const char *chosen) override
  {
    pair_->forward(fields, chosen);
  }
  void reverse_chosen(std::initializer_list<CommField> fields, const char *chosen) override
  {
    pair_->reverse(fields, chosen);
  }
  void gather_marks(char *marks) override { pair_->gather_marks(marks); }

 private:
  PairSPHAstro *pair_;
};
}    // namespace

/* ----------------------------------------------------------------------
   one force evaluation: density (summation, h iteration, or none with density continuity
   after its first summation), EOS, velocity gradients, forward communication, forces,
   conduction
------------------------------------------------------------------------- */

void PairSPHAstro::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  grow_fields();
  // the lists: made after every LAMMPS build (reneighbouring), for the ghost cutoff of now
  h_cap_ = (MAX(comm->cutghostuser, neighbor->cutneighmax) - neighbor->skin) / kernel_radius_;
  h_cap_ = MAX(h_cap_start_, MIN(h_cap_, scheme_->h_max));
  SearchSettings search;
  search.kernel_radius = kernel_radius_;
  search.growth = scheme_->hmode == Scheme::HMode::FIXED ? 1.0 : LIST_GROWTH;
  search.h_cap = h_cap_;
  search.full = gradh();
  search.newton = force->newton_pair != 0;
  search.active_only = active_ != nullptr;
  search.sph_type = sph_type_;
  lists_->update(atom->dvector[state_->h], search);
  alpha_atom_ = alpha_force_ = nullptr;
  if (scheme_->has_switch) {
    int flag, cols;
    const int index = atom->find_custom("alpha", flag, cols);
    const int force_index = atom->find_custom("alpha_force", flag, cols);
    if (index >= 0 && force_index >= 0) {
      alpha_atom_ = atom->dvector[index];
      alpha_force_ = atom->dvector[force_index];
    }
  }

  PassContext ctx = context();
  EvaluationArrays arrays{atom->dvector[state_->h], nullptr, nullptr, {}, {}};
  if (opt_->density_continuity) {
    arrays.rhoest = atom->dvector[continuity_index_->rhoest];
    arrays.drhodt = atom->dvector[continuity_index_->drhodt];
  }
  if (scheme_->entropy)
    arrays.entropy = {atom->dvector[entropy_index_->A], atom->dvector[entropy_index_->Aest],
                      atom->dvector[entropy_index_->dAdt], atom->dvector[state_->u]};
  if (active_) {    // individual timesteps (fix sph/astro checked the step state exists)
    if (!find_step_state(lmp, *step_index_))
      error->all(FLERR, "pair_style sph/astro: the individual-step state fix {} is missing",
                 STEPS_FIX_ID);
    arrays.steps = {active_,
                    atom->dvector[step_index_->omega],
                    atom->dvector[step_index_->balsara],
                    atom->dvector[step_index_->divv],
                    atom->dvector[step_index_->nneigh],
                    atom->dvector[step_index_->dphidh]};
    // the limiter, and kicks pair with the forces (and du/dt terms where u evolves)
    evaluated_pairs_.clear(record_forces_, opt_->eos.uses_energy() && !scheme_->entropy);
    if (record_pairs_) ctx.pairs = &evaluated_pairs_;
  }
  PairExchange exchange(this);
  ForceEvaluation evaluation(ctx, *opt_, *scheme_, arrays, exchange);
  const EvaluationResult result =
      evaluation.run(*lists_, gradh_settings(), *hstats_, h_cap_,
                     opt_->density_continuity && density_init_pending_, entropy_init_pending_);
  entropy_init_pending_ = false;
  if (opt_->density_continuity) density_init_pending_ = false;
  counts_step_ = result.counted ? update->ntimestep : -1;
  h_failures_ += result.h_failures;
  if (vflag_fdotr) virial_fdotr_compute();
  computed_step_ = update->ntimestep;
  computed_nlocal_ = atom->nlocal;
}

/* ----------------------------------------------------------------------
   communication: each stage names its arrays; pack and unpack walk the table
------------------------------------------------------------------------- */

// (chosen: a sparse stage; per atom its values and its position, plus one count per message)
void PairSPHAstro::forward(std::initializer_list<CommField> fields, const char *chosen)
{
  const int size = comm_table_->set(fields, chosen);
  const int bound = chosen ? size + 2 : size;
  if (size < 0 || bound > comm_forward)
    error->one(FLERR,
               "pair_style sph/astro: a forward stage sends {} values per atom, more than "
               "the {} its buffer holds (a bug: please report it)",
               bound, comm_forward);
  if (size) comm->forward_comm(this, bound);
}

void PairSPHAstro::reverse(std::initializer_list<CommField> fields, const char *chosen)
{
  const int size = comm_table_->set(fields, chosen);
  const int bound = chosen ? size + 2 : size;
  if (size < 0 || bound > comm_reverse)
    error->one(FLERR,
               "pair_style sph/astro: a reverse stage sends {} values per atom, more than "
               "the {} its buffer holds (a bug: please report it)",
               bound, comm_reverse);
  if (size) comm->reverse_comm(this, bound);
}

void PairSPHAstro::gather_marks(char *marks)
{
  marks_ = marks;
  comm->reverse_comm(this, 2);
  marks_ = nullptr;
}

int PairSPHAstro::pack_forward_comm(int n, int *list, double *buf, int pbc_flag, int *pbc)
{
  if (!pbc_flag || !domain->deform_vremap) return comm_table_->pack(n, list, buf);
  // fix deform remap v: an image across a periodic boundary moves with the box's rate
  const double *rate = domain->h_rate;
  const double dv[3] = {pbc[0] * rate[0] + pbc[5] * rate[5] + pbc[4] * rate[4],
                        pbc[1] * rate[1] + pbc[3] * rate[3], pbc[2] * rate[2]};
  return comm_table_->pack(n, list, buf, dv, atom->mask, domain->deform_groupbit);
}

void PairSPHAstro::unpack_forward_comm(int n, int first, double *buf)
{
  comm_table_->unpack_range(first, n, buf);
}

int PairSPHAstro::pack_reverse_comm(int n, int first, double *buf)
{
  if (!marks_) return comm_table_->pack_range(first, n, buf);
  return SPHAstro::pack_sparse(
      n, 0, buf,
      [&](int k) {
        return marks_[first + k] != 0;
      },
      [](int, double *) {
      });
}

void PairSPHAstro::unpack_reverse_comm(int n, int *list, double *buf)
{
  if (!marks_) {
    comm_table_->accumulate(n, list, buf);
    return;
  }
  SPHAstro::unpack_sparse(n, 0, buf, [&](int k, const double *) {
    marks_[list[k]] = 1;
  });
}

/* ---------------------------------------------------------------------- */

void PairSPHAstro::write_restart(FILE *fp)
{
  write_restart_settings(fp);
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) fwrite(&setflag[i][j], sizeof(int), 1, fp);
}

void PairSPHAstro::read_restart(FILE *fp)
{
  read_restart_settings(fp);
  allocate();
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      if (comm->me == 0) utils::sfread(FLERR, &setflag[i][j], sizeof(int), 1, fp, nullptr, error);
      MPI_Bcast(&setflag[i][j], 1, MPI_INT, 0, world);
    }
}

void PairSPHAstro::write_restart_settings(FILE *fp)
{
  opt_->write_restart(fp, scheme_->hmode != Scheme::HMode::FIXED);
}

void PairSPHAstro::read_restart_settings(FILE *fp)
{
  restart_variable_h_ = opt_->read_restart(lmp, fp);
  entropy_gamma_ = opt_->eos.gamma;    // of the run that wrote the file (thermal entropy: A)
  kernel_radius_ = opt_->kernel_radius();
  warn_hybrid_restart(lmp, this, "sph/astro");
}

const SearchStatistics &PairSPHAstro::search_statistics() const
{
  return lists_->statistics();
}

/* ----------------------------------------------------------------------
   the narrow interface of the package's fixes and computes
------------------------------------------------------------------------- */

const double *PairSPHAstro::omega() const
{
  return gradh() ? fields_->omega : nullptr;
}

const double *PairSPHAstro::dphidh_sums() const
{
  return dphidh_sums_ && gradh() ? fields_->dphidh_sum : nullptr;
}

double *PairSPHAstro::eval_density() const
{
  return opt_->density_continuity ? atom->dvector[continuity_index_->rhoest]
                                  : atom->dvector[state_->rho];
}

// density continuity without a summation: the counts of a pass only for them, run when they
// are asked for (x, h and the lists are still those of the force evaluation)
const double *PairSPHAstro::neighbour_counts()
{
  if (counts_step_ != computed_step_ && computed_step_ >= 0) {
    PassContext ctx = context();
    ctx.half = lists_->half(atom->dvector[state_->h]);
    count_neighbours(ctx, opt_->symmetrise_kernel);
    if (ctx.newton) reverse({{fields_->nneigh, nullptr, 1, false}});
    counts_step_ = computed_step_;
  }
  return fields_->nneigh;
}

double PairSPHAstro::courant_signal_speed(int i) const
{
  const Fields &f = *fields_;
  if (opt_->tracks_signal()) return f.vsigmax[i];
  const double a = alpha_atom_ ? alpha_atom_[i] : opt_->alpha;
  const double b = alpha_atom_ ? opt_->beta_factor() * a : opt_->beta;
  return viscous_signal_speed(f.soundspeed[i], atom->dvector[state_->h][i], f.divv[i], a, b);
}

void PairSPHAstro::xsph_correction(double eps, double **out)
{
  PassContext ctx = context();
  ctx.half = lists_->half(atom->dvector[state_->h]);
  xsph_pass(ctx, out);
  if (ctx.newton) reverse({{nullptr, out, 3, false}});
  for (int i = 0; i < atom->nlocal; i++)
    for (int d = 0; d < 3; d++) out[i][d] *= eps;
}

void PairSPHAstro::set_courant_pairs(bool on)
{
  opt_->courant_pairs = on;
}

double PairSPHAstro::conductivity_rate(int i) const
{
  return opt_->artificial_conductivity() ? fields_->condrate[i] : 0.0;
}

void PairSPHAstro::schedule_initialisation(bool entropy, bool density)
{
  if (entropy) entropy_init_pending_ = true;
  if (density) density_init_pending_ = true;
}

void *PairSPHAstro::extract(const char *name, int &dim)
{
  dim = 0;
  if (strcmp(name, "kernel_radius") == 0) return (void *) &kernel_radius_;
  if (strcmp(name, "alpha") == 0) return (void *) &opt_->alpha;
  if (strcmp(name, "beta") == 0) return (void *) &opt_->beta;
  // the neighbour search's SearchStatistics (sph_astro_neighbour_lists.h) of this rank
  if (strcmp(name, "search_statistics") == 0) return (void *) &lists_->statistics();
  return nullptr;
}

void *PairSPHAstro::extract_peratom(const char *name, int &ncol)
{
  const PairOptions &o = *opt_;
  const Fields &f = *fields_;
  ncol = 0;
  if (strcmp(name, "pressure") == 0) return (void *) f.pressure;
  if (strcmp(name, "soundspeed") == 0) return (void *) f.soundspeed;
  if (strcmp(name, "divv") == 0) return (void *) f.divv;
  // current unless density continuity skipped the summation (see neighbour_counts())
  if (strcmp(name, "nneigh") == 0)
    return counts_step_ == computed_step_ ? (void *) f.nneigh : nullptr;
  if (strcmp(name, "omega") == 0) return (void *) f.omega;
  if (strcmp(name, "curlv") == 0) return (void *) (scheme_->curl ? f.curlv : nullptr);
  if (strcmp(name, "vsigmax") == 0) return (void *) (o.tracks_signal() ? f.vsigmax : nullptr);
  if (strcmp(name, "balsara") == 0) return (void *) (o.balsara ? f.balsara : nullptr);
  if (strcmp(name, "condrate") == 0)
    return (void *) (o.artificial_conductivity() ? f.condrate : nullptr);
  // reconstruction: symmetric grad v (xx, yy, zz, xy, xz, yz) and the spacing Delta per atom
  if (strcmp(name, "vgrad") == 0) {
    ncol = VGRAD_DATA;
    return o.reconstruction() ? (void *) f.vgrad : nullptr;
  }
  return nullptr;
}

double PairSPHAstro::memory_usage()
{
  return fields_->memory_usage() + lists_->memory_usage() + Pair::memory_usage() +
      evaluated_pairs_.memory_usage();
}
