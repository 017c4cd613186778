/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: self-gravity on a tree (open boundaries)
------------------------------------------------------------------------- */

// kspace_style tree/sph/astro/gravity relative ALPHA | geometric THETA [theta THETA] [leaf N]
//                                     [group N]
//
// The whole self-gravity of every atom with mass: the kernel-softened pair potential of pair
// sph/astro/gravity (its G, kernel, softening lengths and adaptive-softening terms) inside
// the softening support, the Newtonian one beyond it, with distant groups of particles
// replaced by their multipole moments to quadrupole order (Barnes & Hut 1986; the tree and the
// opening criteria: sph_astro_gravity_tree.h; the sums: sph_astro_gravity_interactions.h).
// Pair sph/astro/gravity then computes nothing itself (its zeta sums aside).
//
// Each rank builds a tree over its own atoms at every re-neighbouring (when LAMMPS moves atoms
// between ranks) and recomputes its moments from the current positions at every evaluation.
// The other ranks' atoms enter through locally essential trees (Salmon & Warren 1994, J.
// Comput. Phys. 111, 136; Warren & Salmon 1993): every rank sends every other rank the
// multipoles of its nodes accepted for all points of that rank's target box and the particles
// of the leaves that are not, found by walking its tree against that box; the receiver builds
// a second tree over what it gets. Only what the criteria need crosses ranks.
//
// Targets: every atom, or with individual timesteps (fix sph/astro steps individual) the
// active ones only (sph_astro_active_set.h); all of them when the energy or virial is tallied.
// Targets are taken in groups of at most `group` particles of one tree node, one walk per
// group (Barnes 1990).
//
// Periodic boxes (TreePM; Bagla 2002, J. Astrophys. Astron. 23, 185; Springel 2005, MNRAS 364,
// 1105, sec. 3.2): PPPM (pppm/sph/astro/gravity, keyword pm ACCURACY) supplies
// -G m_i m_j erf(g r)/r over all pairs and images, the tree the rest within the pair style's
// cutoff, as pair sph/astro/gravity's short range does with PPPM; its tree holds the owned atoms
// and LAMMPS' ghost atoms (the periodic images within the cutoff), so no exchange is needed.

#include "tree_sph_astro_gravity.h"

#include "pair_sph_astro_gravity.h"
#include "pppm_sph_astro_gravity.h"
#include "sph_astro_gravity_kernel.h"
#include "sph_astro_gravity_kspace.h"
#include "sph_astro_kernel.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "modify.h"
#include "neighbor.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace SPHAstro;

static constexpr const char *STYLE = "kspace_style tree/sph/astro/gravity";
static constexpr const char *ACCEL_FIX_ID = "SPH_ASTRO_TREE_ACCEL";
static constexpr const char *ACCEL_NAME = "sph_astro_tree_accel";

TreeSPHAstroGravity::TreeSPHAstroGravity(LAMMPS *lmp) : KSpace(lmp)
{
  // none of LAMMPS' Coulomb solver flags: pair sph/astro/gravity is checked in init()
  ewaldflag = pppmflag = msmflag = 0;
  accuracy_relative = 0.0;
}

TreeSPHAstroGravity::~TreeSPHAstroGravity()
{
  delete pm_;
}

void TreeSPHAstroGravity::set_long_range_schedule(LongRangeSchedule *schedule)
{
  if (pm_) pm_->set_long_range_schedule(schedule);
}

/* ----------------------------------------------------------------------
   relative ALPHA | geometric THETA, then [theta THETA] [leaf N] [group N]
------------------------------------------------------------------------- */

void TreeSPHAstroGravity::settings(int narg, char **arg)
{
  if (narg < 2) utils::missing_cmd_args(FLERR, STYLE, error);
  const std::string criterion = arg[0];
  crit_.alpha = 0.0;
  crit_.theta = 0.5;
  if (criterion == "relative") {
    crit_.alpha = utils::numeric(FLERR, arg[1], false, lmp);
    if (!(crit_.alpha > 0.0 && crit_.alpha < 1.0))
      error->all(FLERR,
                 "{}: relative criterion alpha = {} must be in (0, 1) (the force error allowed "
                 "per node relative to a particle's acceleration; 0.002: RMS force errors about "
                 "5e-4)",
                 STYLE, arg[1]);
  } else if (criterion == "geometric") {
    crit_.theta = parse_theta(arg[1]);
  } else
    error->all(FLERR,
               "{}: unknown opening criterion '{}'; allowed: relative ALPHA (e.g. 0.002), "
               "geometric THETA (e.g. 0.5)",
               STYLE, criterion);
  int iarg = 2;
  while (iarg < narg) {
    const std::string key = arg[iarg];
    if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, std::string(STYLE) + " " + key, error);
    if (key == "theta" && crit_.alpha > 0.0) {
      crit_.theta = parse_theta(arg[iarg + 1]);
    } else if (key == "leaf") {
      leaf_size_ = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (leaf_size_ < 1 || leaf_size_ > 1024)
        error->all(FLERR, "{}: leaf = {} must be in 1..1024 (particles per leaf)", STYLE,
                   arg[iarg + 1]);
    } else if (key == "group") {
      group_size_ = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (group_size_ < 1 || group_size_ > 4096)
        error->all(FLERR, "{}: group = {} must be in 1..4096 (targets per tree walk)", STYLE,
                   arg[iarg + 1]);
    } else if (key == "pm") {
      const double accuracy = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(accuracy > 0.0 && accuracy < 1.0))
        error->all(FLERR,
                   "{}: pm accuracy = {} must be in (0, 1) (the relative force error of PPPM's "
                   "long range in a periodic box, e.g. 1e-4)",
                   STYLE, arg[iarg + 1]);
      pm_accuracy_ = arg[iarg + 1];
    } else if (key == "theta")
      error->all(FLERR,
                 "{}: keyword theta belongs to the relative criterion (the opening angle of a "
                 "particle's first evaluation); with geometric the angle is its value",
                 STYLE);
    else
      error->all(FLERR, "{}: unknown keyword '{}'; allowed: theta, leaf, group, pm", STYLE, key);
    iarg += 2;
  }
  local_ = GravityTree(leaf_size_);
  imported_ = GravityTree(leaf_size_);
  built_ = false;
  // the relative criterion needs each particle's acceleration of its last evaluation, carried
  // with the atom (exchange, restart)
  if (crit_.alpha > 0.0 && !modify->get_fix_by_id(ACCEL_FIX_ID))
    modify->add_fix(fmt::format("{} all property/atom d_{}", ACCEL_FIX_ID, ACCEL_NAME));
}

double TreeSPHAstroGravity::parse_theta(const char *text)
{
  const double theta = utils::numeric(FLERR, text, false, lmp);
  if (!(theta > 0.0 && theta <= 1.0))
    error->all(FLERR,
               "{}: opening angle theta = {} must be in (0, 1] (0.5: RMS force errors about "
               "1e-3; smaller is more accurate and slower, 1e-6 opens every node: direct "
               "summation)",
               STYLE, text);
  return theta;
}

void TreeSPHAstroGravity::init()
{
  if (domain->dimension != 3)
    error->all(FLERR, "{}: dimension {} not supported (3d Newtonian gravity)", STYLE,
               domain->dimension);
  if (domain->triclinic) error->all(FLERR, "{}: triclinic boxes are not supported", STYLE);
  periodic_ = domain->xperiodic && domain->yperiodic && domain->zperiodic;
  if (!periodic_ && (domain->xperiodic || domain->yperiodic || domain->zperiodic))
    error->all(FLERR,
               "{}: boundary {} is periodic along some axes only; the tree takes open "
               "boundaries (f, s or m) in x, y and z, or periodic ones in all three (TreePM)",
               STYLE, boundary_string(lmp));
  pair_ = dynamic_cast<PairSPHAstroGravity *>(force->pair_match("^sph/astro/gravity$", 0, 0));
  if (!pair_)
    error->all(FLERR,
               "{} needs pair_style sph/astro/gravity (alone or as a hybrid/overlay sub-style) "
               "for G, the kernel and the softening lengths",
               STYLE);
  if (slabflag) error->all(FLERR, "{}: kspace_modify slab is not supported", STYLE);
  crit_.cutoff = INFINITY;
  if (periodic_) {
    // the long range: PPPM with this style's order and (kspace_modify mesh) grid
    if (!pm_) pm_ = new PPPMSPHAstroGravity(lmp);
    std::vector<char> accuracy(pm_accuracy_.begin(), pm_accuracy_.end());
    accuracy.push_back('\0');
    char *args[1] = {accuracy.data()};
    pm_->settings(1, args);
    pm_->order = order;
    if (gridflag) pm_->set_grid(nx_pppm, ny_pppm, nz_pppm);
    pm_->init();
    int dim;
    crit_.cutoff = *static_cast<double *>(force->pair->extract("cut_coul", dim));
  } else {
    delete pm_;
    pm_ = nullptr;
  }
  active_ = ActiveSet();    // all active until fix sph/astro says otherwise
  built_ = false;
  accel_index_ = -1;
  if (crit_.alpha > 0.0) {
    int flag, cols;
    accel_index_ = atom->find_custom(ACCEL_NAME, flag, cols);
    if (accel_index_ < 0 || flag != 1 || cols != 0)
      error->all(FLERR, "{} alpha: the per-atom property d_{} (fix {}) is missing", STYLE,
                 ACCEL_NAME, ACCEL_FIX_ID);
  }
  builds_ = evaluations_ = target_sum_ = multipole_sum_ = particle_sum_ = imported_sum_ = 0.0;
  time_build_ = time_moments_ = time_exchange_ = time_walks_ = 0.0;
  if (comm->me == 0 && periodic_)
    utils::logmesg(lmp,
                   "tree/sph/astro/gravity: TreePM in a periodic box, short range within {} on "
                   "the tree, long range by PPPM (g_ewald {:.8g}, grid {} {} {}, accuracy {})\n",
                   crit_.cutoff, pm_->g_ewald, pm_->nx_pppm, pm_->ny_pppm, pm_->nz_pppm,
                   pm_accuracy_);
  if (comm->me == 0)
    utils::logmesg(lmp, "tree/sph/astro/gravity: quadrupole tree, {}, leaf {}, group {}\n",
                   crit_.alpha > 0.0
                       ? fmt::format("relative criterion alpha = {} (first evaluation: theta "
                                     "= {})",
                                     crit_.alpha, crit_.theta)
                       : fmt::format("geometric criterion theta = {}", crit_.theta),
                   leaf_size_, group_size_);
}

/* ---------------------------------------------------------------------- */

void TreeSPHAstroGravity::setup()
{
  if (pm_) pm_->setup();
}

// the tree over the owned atoms (and in a periodic box the ghosts: images of the same atom
// have its tag, and the build keeps their order)
void TreeSPHAstroGravity::build_local()
{
  const int n = sources();
  std::vector<int64_t> tie(n);
  built_tags_.resize(n);
  for (int i = 0; i < n; i++) {
    tie[i] = static_cast<int64_t>(atom->tag[i]);
    built_tags_[i] = atom->tag[i];
  }
  local_.build(n, atom->x, tie.data());
  local_.groups(group_size_, groups_);
  built_ = true;
  builds_ += 1.0;
}

void TreeSPHAstroGravity::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  const int nlocal = atom->nlocal;
  const int n = sources();
  crit_.G = pair_->gravity_constant();
  crit_.kernel_radius = kernel_radius(pair_->kernel());

  // the structure of the last re-neighbouring, while the atoms are the same in the same slots
  bool rebuild = !built_ || neighbor->ago == 0 || static_cast<int>(built_tags_.size()) != n;
  const tagint *tag = atom->tag;
  for (int i = 0; i < n && !rebuild; i++) rebuild = tag[i] != built_tags_[i];
  double t0 = MPI_Wtime();
  if (rebuild) build_local();
  double t1 = MPI_Wtime();
  time_build_ += t1 - t0;

  double **x = atom->x;
  const double *rmass = atom->rmass;
  const double *mass = atom->mass;
  const int *type = atom->type;
  const double *zo = pair_->zeta_over_omega();
  local_.refit([&](int i, double &px, double &py, double &pz, double &m, double &h, double &z) {
    px = x[i][0];
    py = x[i][1];
    pz = x[i][2];
    m = rmass ? rmass[i] : mass[type[i]];
    h = pair_->softening_length(i);
    z = zo ? zo[i] : 0.0;
  });
  // (checked after: an atom without a softening length stops the run)
  const double *lh = local_.h();
  for (int k = 0; k < n; k++)
    if (!(lh[k] > 0.0) || !std::isfinite(lh[k]))
      error->one(FLERR,
                 "{}: atom {} has softening length {} on step {}; it must be > 0 (the SPH "
                 "smoothing length d_h, or pair_style sph/astro/gravity ... h VALUE)",
                 STYLE, tag[local_.index(k)], lh[k], update->ntimestep);
  t0 = MPI_Wtime();
  time_moments_ += t0 - t1;

  // targets: every particle, or the active ones (the energy and virial need every one)
  const bool every = active_.all() || eflag_either || vflag_either;
  const int *mask = atom->mask;
  target_.resize(n);
  for (int k = 0; k < n; k++) {
    const int i = local_.index(k);
    target_[k] = i < nlocal && (every || active_.active(i, mask));
  }

  if (!periodic_) exchange();
  t1 = MPI_Wtime();
  time_exchange_ += t1 - t0;

  const bool cubic = pair_->kernel() == KernelType::CUBIC;
  const bool zeta = zo != nullptr;
  if (cubic && zeta)
    evaluate<true, true>();
  else if (cubic)
    evaluate<true, false>();
  else if (zeta)
    evaluate<false, true>();
  else
    evaluate<false, false>();
  time_walks_ += MPI_Wtime() - t1;

  // TreePM: the long range (its energy and virial are summed over the ranks)
  double pm_energy = 0.0, pm_virial[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  if (pm_) {
    pm_->compute(eflag, vflag);
    pm_energy = pm_->energy;
    for (int k = 0; k < 6; k++) pm_virial[k] = pm_->virial[k];
    if (eflag_atom)
      for (int i = 0; i < nlocal; i++) eatom[i] += pm_->eatom[i];
    if (vflag_atom)
      for (int i = 0; i < nlocal; i++)
        for (int k = 0; k < 6; k++) vatom[i][k] += pm_->vatom[i][k];
  }

  if (eflag_global) {
    double all;
    MPI_Allreduce(&energy, &all, 1, MPI_DOUBLE, MPI_SUM, world);
    energy = all + pm_energy;
  }
  if (vflag_global) {
    double all[6];
    MPI_Allreduce(virial, all, 6, MPI_DOUBLE, MPI_SUM, world);
    for (int k = 0; k < 6; k++) virial[k] = all[k] + pm_virial[k];
  }
}

/* ----------------------------------------------------------------------
   locally essential trees: to each rank with targets, this rank's multipoles accepted for
   all of that rank's target boxes and the particles of its leaves that are not; a message per
   rank of records: particle (0, x, y, z, m, h, zeta/Omega), multipole (1, x, y, z, m, q[6], b)
------------------------------------------------------------------------- */

void TreeSPHAstroGravity::exchange()
{
  import_items_.clear();
  const int nprocs = comm->nprocs;
  if (nprocs == 1) {
    imported_.build(import_items_);
    last_.imported = 0.0;
    return;
  }
  // this rank's targets as boxes, one per node of the tree at the level of about BOXES nodes:
  // lo, hi, largest h, smallest |a| (0: unknown) of its targets
  constexpr int NBOX = 8, BOXES = 64;
  std::vector<double> mine;
  const double *lx = local_.x(), *ly = local_.y(), *lz = local_.z(), *lh = local_.h();
  const double *accel = accel_index_ >= 0 ? atom->dvector[accel_index_] : nullptr;
  local_.groups(std::max(group_size_, local_.size() / BOXES), box_nodes_);
  for (int g : box_nodes_) {
    const GravityNode &node = local_.node(g);
    double box[NBOX] = {INFINITY,  INFINITY,  INFINITY, -INFINITY,
                        -INFINITY, -INFINITY, 0.0,      INFINITY};
    bool any = false;
    for (int k = node.first; k < node.first + node.count; k++) {
      if (!target_[k]) continue;
      any = true;
      box[0] = std::min(box[0], lx[k]);
      box[1] = std::min(box[1], ly[k]);
      box[2] = std::min(box[2], lz[k]);
      box[3] = std::max(box[3], lx[k]);
      box[4] = std::max(box[4], ly[k]);
      box[5] = std::max(box[5], lz[k]);
      box[6] = std::max(box[6], lh[k]);
      if (accel) box[7] = std::min(box[7], accel[local_.index(k)]);
    }
    if (!any) continue;
    if (!accel || !std::isfinite(box[7])) box[7] = 0.0;
    mine.insert(mine.end(), box, box + NBOX);
  }
  const int nmine = static_cast<int>(mine.size());
  std::vector<int> boxcounts(nprocs), boxdispls(nprocs);
  MPI_Allgather(&nmine, 1, MPI_INT, boxcounts.data(), 1, MPI_INT, world);
  int nboxes = 0;
  for (int r = 0; r < nprocs; r++) {
    boxdispls[r] = nboxes;
    nboxes += boxcounts[r];
  }
  std::vector<double> boxes(nboxes);
  MPI_Allgatherv(mine.data(), nmine, MPI_DOUBLE, boxes.data(), boxcounts.data(), boxdispls.data(),
                 MPI_DOUBLE, world);

  // to each rank with targets: a node's multipole if it is accepted for every one of that
  // rank's boxes (each with its own h and |a|), else its children, and a leaf's particles
  std::vector<double> send;
  std::vector<int> sendcounts(nprocs, 0), senddispls(nprocs, 0);
  std::vector<TargetBox> targets;
  for (int r = 0; r < nprocs; r++) {
    senddispls[r] = static_cast<int>(send.size());
    if (r == comm->me || boxcounts[r] == 0 || local_.empty()) continue;
    targets.clear();
    for (int b = 0; b < boxcounts[r] / NBOX; b++) {
      const double *v = &boxes[boxdispls[r] + NBOX * b];
      targets.push_back(TargetBox{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, v[6], v[7]});
    }
    accepted_.clear();
    leaves_.clear();
    local_.walk(targets, crit_, accepted_, leaves_);
    for (int a : accepted_) {
      const GravityNode &n = local_.node(a);
      if (n.bmax > 0.0) {
        send.insert(
            send.end(),
            {1.0, n.x, n.y, n.z, n.m, n.q[0], n.q[1], n.q[2], n.q[3], n.q[4], n.q[5], n.bmax});
      } else    // a point mass: one particle, or particles at one point
        send.insert(send.end(), {0.0, n.x, n.y, n.z, n.m, n.hmax, 0.0});
    }
    const double *lm = local_.m(), *lzo = local_.zo();
    for (int l : leaves_) {
      const GravityNode &n = local_.node(l);
      for (int k = n.first; k < n.first + n.count; k++)
        send.insert(send.end(), {0.0, lx[k], ly[k], lz[k], lm[k], lh[k], lzo[k]});
    }
    sendcounts[r] = static_cast<int>(send.size()) - senddispls[r];
  }
  std::vector<int> recvcounts(nprocs), recvdispls(nprocs);
  MPI_Alltoall(sendcounts.data(), 1, MPI_INT, recvcounts.data(), 1, MPI_INT, world);
  int total = 0;
  for (int r = 0; r < nprocs; r++) {
    recvdispls[r] = total;
    total += recvcounts[r];
  }
  std::vector<double> recv(total);
  MPI_Alltoallv(send.data(), sendcounts.data(), senddispls.data(), MPI_DOUBLE, recv.data(),
                recvcounts.data(), recvdispls.data(), MPI_DOUBLE, world);
  std::vector<double>().swap(send);
  // (the items' arrays at their size: their memory is the peak of a full evaluation)
  int items = 0, multipoles = 0;
  for (const double *p = recv.data(), *end = p + total; p < end; items++) {
    multipoles += p[0] != 0.0;
    p += p[0] == 0.0 ? 7 : 12;
  }
  for (auto *v : {&import_items_.x, &import_items_.y, &import_items_.z, &import_items_.m,
                  &import_items_.h, &import_items_.zo})
    v->reserve(items);
  import_items_.mp.reserve(items);
  import_items_.tie.reserve(items);
  import_items_.moments.reserve(7 * static_cast<size_t>(multipoles));
  for (int r = 0; r < nprocs; r++) {
    int64_t seq = static_cast<int64_t>(r) << 40;
    const double *p = recv.data() + recvdispls[r], *end = p + recvcounts[r];
    while (p < end) {
      if (p[0] == 0.0) {
        import_items_.add_particle(p[1], p[2], p[3], p[4], p[5], p[6], seq++);
        p += 7;
      } else {
        import_items_.add_multipole(p[1], p[2], p[3], p[4], p + 5, p[11], seq++);
        p += 12;
      }
    }
  }
  std::vector<double>().swap(recv);
  last_.imported = import_items_.size();
  imported_.build(import_items_);
}

/* ---------------------------------------------------------------------- */

template <bool CUBIC, bool ZETA> void TreeSPHAstroGravity::evaluate()
{
  double **f = atom->f;
  const KernelType kernel = pair_->kernel();
  const SoftenedKernel &soft = softened_kernel(kernel);
  const double R = crit_.kernel_radius;
  const double G = crit_.G;
  double *accel = accel_index_ >= 0 ? atom->dvector[accel_index_] : nullptr;
  const double *lx = local_.x(), *ly = local_.y(), *lz = local_.z();
  const double *lm = local_.m(), *lh = local_.h(), *lzo = local_.zo();
  double targets = 0.0, multipoles = 0.0, particles = 0.0;
  for (int g : groups_) {
    const GravityNode &n = local_.node(g);
    TargetBox box{{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}, 0.0, INFINITY};
    int count = 0;
    for (int k = n.first; k < n.first + n.count; k++) {
      if (!target_[k]) continue;
      count++;
      box.lo[0] = std::min(box.lo[0], lx[k]);
      box.lo[1] = std::min(box.lo[1], ly[k]);
      box.lo[2] = std::min(box.lo[2], lz[k]);
      box.hi[0] = std::max(box.hi[0], lx[k]);
      box.hi[1] = std::max(box.hi[1], ly[k]);
      box.hi[2] = std::max(box.hi[2], lz[k]);
      box.hmax = std::max(box.hmax, lh[k]);
      if (accel) box.amin = std::min(box.amin, accel[local_.index(k)]);
    }
    if (count == 0) continue;
    if (!accel || !std::isfinite(box.amin)) box.amin = 0.0;
    lists_.clear();
    accepted_.clear();
    leaves_.clear();
    local_.walk(box, crit_, accepted_, leaves_);
    for (int a : accepted_) lists_.add_node(local_.node(a));
    for (int l : leaves_) lists_.add_leaf(local_, local_.node(l), 0);
    accepted_.clear();
    leaves_.clear();
    imported_.walk(box, crit_, accepted_, leaves_);
    for (int a : accepted_) lists_.add_node(imported_.node(a));
    for (int l : leaves_) lists_.add_leaf(imported_, imported_.node(l), -1);
    lists_.finish(&box, R);
    targets += count;
    multipoles += count * static_cast<double>(lists_.multipoles());
    particles += count * static_cast<double>(lists_.particles());

    for (int k = n.first; k < n.first + n.count; k++) {
      if (!target_[k]) continue;
      const int i = local_.index(k);
      double acc[3], pot, pair_virial[6];
      if (periodic_)
        lists_.evaluate_split<CUBIC, ZETA>(lx[k], ly[k], lz[k], lh[k], lzo[k], k, soft, kernel, R,
                                           pm_->g_ewald, crit_.cutoff, acc, pot,
                                           vflag_either ? pair_virial : nullptr);
      else
        lists_.evaluate<CUBIC, ZETA>(lx[k], ly[k], lz[k], lh[k], lzo[k], k, soft, kernel, R, acc,
                                     pot);
      const double Gm = G * lm[k];
      const double fx = Gm * acc[0], fy = Gm * acc[1], fz = Gm * acc[2];
      f[i][0] += fx;
      f[i][1] += fy;
      f[i][2] += fz;
      if (eflag_either) {
        const double e = 0.5 * Gm * pot;
        if (eflag_global) energy += e;
        if (eflag_atom) eatom[i] += e;
      }
      if (vflag_either) {
        // open boundaries: sum_i x_i F_i (= sum over pairs of r_ij F_ij); periodic: half of
        // each pair's r_ij F_ij (both atoms of a pair are targets somewhere)
        double v[6];
        if (periodic_)
          for (int c = 0; c < 6; c++) v[c] = 0.5 * Gm * pair_virial[c];
        else {
          v[0] = lx[k] * fx;
          v[1] = ly[k] * fy;
          v[2] = lz[k] * fz;
          v[3] = lx[k] * fy;
          v[4] = lx[k] * fz;
          v[5] = ly[k] * fz;
        }
        if (vflag_global)
          for (int c = 0; c < 6; c++) virial[c] += v[c];
        if (vflag_atom)
          for (int c = 0; c < 6; c++) vatom[i][c] += v[c];
      }
      if (accel) accel[i] = G * std::sqrt(acc[0] * acc[0] + acc[1] * acc[1] + acc[2] * acc[2]);
    }
  }
  last_.targets = targets;
  last_.multipoles = targets > 0.0 ? multipoles / targets : 0.0;
  last_.particles = targets > 0.0 ? particles / targets : 0.0;
  last_.depth = local_.depth();
  evaluations_ += 1.0;
  target_sum_ += targets;
  multipole_sum_ += multipoles;
  particle_sum_ += particles;
  imported_sum_ += last_.imported;
}

/* ---------------------------------------------------------------------- */

std::string TreeSPHAstroGravity::run_summary()
{
  double local[12] = {evaluations_,   builds_,        target_sum_,
                      multipole_sum_, particle_sum_,  imported_sum_,
                      time_build_,    time_moments_,  time_exchange_,
                      time_walks_,    memory_usage(), static_cast<double>(atom->nlocal)},
         all[12];
  MPI_Allreduce(local, all, 12, MPI_DOUBLE, MPI_SUM, world);
  if (all[0] == 0.0) return {};
  const double ranks = comm->nprocs;
  return fmt::format(
      "tree/sph/astro/gravity: {:.0f} evaluations, {:.0f} tree builds per rank; {:.4g} "
      "targets per evaluation, each {:.1f} multipoles + {:.1f} particles; {:.4g} items "
      "imported per rank and evaluation; seconds per rank: builds {:.3g}, moments {:.3g}, "
      "exchange {:.3g}, walks and sums {:.3g}; memory {:.0f} bytes per particle",
      all[0] / ranks, all[1] / ranks, all[2] / (all[0] / ranks),
      all[2] > 0.0 ? all[3] / all[2] : 0.0, all[2] > 0.0 ? all[4] / all[2] : 0.0, all[5] / all[0],
      all[6] / ranks, all[7] / ranks, all[8] / ranks, all[9] / ranks,
      all[11] > 0.0 ? all[10] / all[11] : 0.0);
}

double TreeSPHAstroGravity::memory_usage()
{
  return local_.memory_usage() + imported_.memory_usage() + lists_.memory_usage() +
      (pm_ ? pm_->memory_usage() : 0.0) + built_tags_.capacity() * sizeof(tagint) +
      target_.capacity() +
      (groups_.capacity() + accepted_.capacity() + leaves_.capacity()) * sizeof(int) +
      (import_items_.x.capacity() * 6 + import_items_.moments.capacity()) * sizeof(double) +
      import_items_.tie.capacity() * sizeof(int64_t) + import_items_.mp.capacity() * sizeof(int) +
      (box_nodes_.capacity() * sizeof(int));
}
