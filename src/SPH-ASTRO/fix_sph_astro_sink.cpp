/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Fix sph/astro/sink: sink particles after Bate, Bonnell & Price (1995, MNRAS 277, 362; BBP95
// below), sec. 2, as Phantom has them (Price et al. 2018, PASA 35, e031; P18 below, sec. 2.8).
// The sinks are ordinary LAMMPS atoms with per-atom mass (the fix's group), integrated by fix
// nve and felt by the package's gravity; the gas is the group of fix sph/astro.
//
// Accretion (BBP95 sec. 2.2; P18 sec. 2.8.2), gas particle i, sink a, r = x_i - x_a,
// v = v_i - v_a (minimum image), e_ia = |v|^2/2 - G M_a/|r| (the two-body specific energy):
//   |r| < r_in                 accreted without further checks
//   r_in <= |r| < r_acc        accreted if (i) bound, e_ia < 0, (ii) moving towards the sink,
//                              r.v < 0, (iii) |r x v|^2 < G M_a r_acc (less specific angular
//                              momentum than a circular orbit at r_acc), and (iv) more bound to a
//                              than to any other sink: e_ia = min_b e_ib
// A particle several sinks qualify for goes to the one it is most bound to (smallest e_ia, then
// the smallest sink ID). The sink takes the particles' mass, momentum and position
// (its new position is the centre of mass), and their angular momentum about that centre of mass
// becomes its spin S, so that, summed in ID order (the same bits on any number of ranks),
//   M' = M + sum m_i,  M' x' = M x + sum m_i x_i,  M' v' = M v + sum m_i v_i,
//   S' = S + M (x - x') x (v - v') + sum m_i (x_i - x') x (v_i - v')
// keep the total mass, momentum and angular momentum sum (m x x v) + sum S to round-off.
//
// Creation (BBP95 sec. 2.3; P18 sec. 2.8.4; Federrath et al. 2010, ApJ 713, 269, sec. 2.2):
// the densest gas particle c with rho_c > rho_crit whose kernel support lies inside r_acc
// (R h_c <= r_acc), with div v_c < 0 and not inside any sink's r_acc, becomes a sink when the gas
// within r_acc of it (c included) has alpha = E_th/|E_grav| <= 1/2, alpha + beta <= 1 (beta =
// E_rot/|E_grav|), E_kin + E_th + E_grav < 0, and c is the minimum of the potential of that gas
// and the sinks. It keeps its ID, mass, position and velocity, takes the sink type and the fix's
// group and leaves fix sph/astro's group; the gas within r_acc of it is accreted at the next
// reneighbouring without further checks.
//
// Atoms are deleted only in pre_exchange of a reneighbouring step (as fix evaporate does):
// end_of_step asks for one at the next step (next_reneighbor) when a gas particle is inside a
// sink's r_acc or a sink was created.
//
// Timestep (P18 sec. 2.8.3 in spirit; C = dtfactor), reported to fix sph/astro through
// SPHAstro::TimestepLimiter:
//   dt <= C sqrt(r_ab^3 / (G (M_a + M_b))),  dt <= C r_ab / |v_ab|   (sink pairs)
//   dt <= C sqrt(r_acc / |a_a|)                                        (each sink)
//   dt <= C r_acc / |v_i - v_a|             (gas within 2 r_acc of a sink: no particle crosses
//                                            the accretion zone in one step)

#include "fix_sph_astro_sink.h"

#include "fix_sph_astro.h"
#include "pair_sph_astro.h"

#include "atom.h"
#include "atom_vec.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "memory.h"
#include "modify.h"
#include "pair.h"
#include "sph_astro_fields.h"
#include "sph_astro_gravity_kernel.h"
#include "sph_astro_options.h"
#include "sph_astro_sink_records.h"
#include "sph_astro_state.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

using namespace SPHAstro::SinkRecords;

FixSPHAstroSink::FixSPHAstroSink(LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg)
{
  restart_global = 1;
  restart_peratom = 1;
  create_attribute = 1;
  force_reneighbor = 1;
  next_reneighbor = -1;
  scalar_flag = 1;    // number of sinks
  vector_flag = 1;    // [sinks, accreted mass, accreted particles, sinks made, dt bound, mass]
  size_vector = 6;
  global_freq = 1;
  extscalar = 0;
  extvector = 0;

  int iarg = 3;
  while (iarg < narg) {
    const std::string key = arg[iarg];
    if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix sph/astro/sink " + key, error);
    const char *val = arg[iarg + 1];
    if (key == "racc") {
      racc_ = utils::numeric(FLERR, val, false, lmp);
      if (!(racc_ > 0.0) || !std::isfinite(racc_))
        error->all(FLERR, "fix sph/astro/sink: racc = {} must be > 0 (the accretion radius)", val);
    } else if (key == "rin") {
      rin_ = utils::numeric(FLERR, val, false, lmp);
      if (!(rin_ >= 0.0) || !std::isfinite(rin_))
        error->all(FLERR,
                   "fix sph/astro/sink: rin = {} must be >= 0 and at most racc (the radius inside "
                   "which gas is accreted without further checks)",
                   val);
    } else if (key == "G") {
      G_ = utils::numeric(FLERR, val, false, lmp);
      G_given_ = true;
      if (!(G_ > 0.0) || !std::isfinite(G_))
        error->all(FLERR, "fix sph/astro/sink: G = {} must be > 0", val);
    } else if (key == "create") {
      rho_create_ = utils::numeric(FLERR, val, false, lmp);
      if (!(rho_create_ > 0.0) || !std::isfinite(rho_create_))
        error->all(FLERR, "fix sph/astro/sink: create = {} must be a density > 0", val);
    } else if (key == "type") {
      create_type_ = utils::inumeric(FLERR, val, false, lmp);
      if (create_type_ < 1 || create_type_ > atom->ntypes)
        error->all(FLERR, "fix sph/astro/sink: type {} is not an atom type (1 to {})", val,
                   atom->ntypes);
    } else if (key == "dtfactor") {
      dt_factor_ = utils::numeric(FLERR, val, false, lmp);
      if (!(dt_factor_ > 0.0) || dt_factor_ > 1.0)
        error->all(FLERR, "fix sph/astro/sink: dtfactor = {} must be in (0, 1]", val);
    } else
      error->all(FLERR,
                 "fix sph/astro/sink: unknown keyword '{}'; allowed: racc, rin, G, create, type, "
                 "dtfactor",
                 key);
    iarg += 2;
  }
  if (racc_ <= 0.0) error->all(FLERR, "fix sph/astro/sink: the accretion radius racc is required");
  if (rin_ < 0.0) rin_ = 0.8 * racc_;    // Phantom's default f_acc = 0.8 (P18 sec. 2.8.2)
  if (rin_ > racc_)
    error->all(FLERR,
               "fix sph/astro/sink: rin = {} is larger than racc = {}; allowed: 0 <= rin <= racc",
               rin_, racc_);
  if (rho_create_ > 0.0 && create_type_ == 0)
    error->all(FLERR,
               "fix sph/astro/sink: create needs the type of the new sinks (keyword type T, a type "
               "without pair_coeff of pair_style sph/astro)");
  if (!atom->rmass_flag)
    error->all(FLERR,
               "fix sph/astro/sink needs per-atom masses (sinks grow): use fix property/atom rmass "
               "before the atoms are made, or an atom style with rmass");
  if (!atom->tag_enable) error->all(FLERR, "fix sph/astro/sink needs atom IDs");

  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
  for (int i = 0; i < atom->nlocal; i++) set_arrays(i);
}

FixSPHAstroSink::~FixSPHAstroSink()
{
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  memory->destroy(spin_);
  memory->destroy(macc_);
  memory->destroy(nacc_);
  memory->destroy(mlow_);
}

int FixSPHAstroSink::setmask()
{
  return PRE_EXCHANGE | END_OF_STEP;
}

double FixSPHAstroSink::gravity_constant() const
{
  if (G_given_) return G_;
  if (force->pair) {
    int dim = 0;
    auto *g = static_cast<double *>(force->pair->extract("gravity_G", dim));
    if (g) return *g;
  }
  return 0.0;
}

void FixSPHAstroSink::init()
{
  auto gas = modify->get_fix_by_style("^sph/astro$");
  if (gas.empty())
    error->all(FLERR, "fix sph/astro/sink needs fix sph/astro (its group is the gas accreted)");
  gas_fix_ = dynamic_cast<FixSPHAstro *>(gas.front());
  gasbit_ = gas_fix_->groupbit;
  if (gas_fix_->individual_steps())
    error->all(FLERR,
               "fix sph/astro/sink: fix sph/astro steps individual is not supported with sinks "
               "yet; use steps global");
  if (gas_fix_->igroup == igroup || gas_fix_->igroup == 0)
    error->all(FLERR,
               "fix sph/astro/sink: fix sph/astro's group {} must not hold the sinks; give the "
               "gas a group of its own (e.g. group gas type 1) and the sinks another",
               group->names[gas_fix_->igroup]);
  int overlap = 0, overlap_all;
  for (int i = 0; i < atom->nlocal; i++)
    if ((atom->mask[i] & groupbit) && (atom->mask[i] & gasbit_)) overlap = 1;
  MPI_Allreduce(&overlap, &overlap_all, 1, MPI_INT, MPI_MAX, world);
  if (overlap_all)
    error->all(FLERR, "fix sph/astro/sink: an atom of group {} is also in fix sph/astro's group {}",
               group->names[igroup], group->names[gas_fix_->igroup]);
  G_ = gravity_constant();
  if (!(G_ > 0.0))
    error->all(FLERR,
               "fix sph/astro/sink: no gravitational constant: give G VALUE or use pair_style "
               "sph/astro/gravity");
  pair_ = dynamic_cast<PairSPHAstro *>(force->pair_match("^sph/astro$", 0, 0));
  SPHAstro::StateIndex state;
  if (!SPHAstro::find_state(lmp, state))
    error->all(FLERR, "fix sph/astro/sink: the SPH state {} is missing", SPHAstro::STATE_FIX_ID);
  rho_index_ = state.rho;
  h_index_ = state.h;
  u_index_ = state.u;
  // the sinks' softening: pair sph/astro/gravity's softening of the new sinks' type (keyword
  // softening), else its fixed h
  hsoft_ = 0.0;
  if (force->pair) {
    int dim = 0;
    auto *h = static_cast<double *>(force->pair->extract("gravity_hfixed", dim));
    if (h) hsoft_ = *h;
    auto *per_type = static_cast<double *>(force->pair->extract("gravity_softening_types", dim));
    if (per_type && rho_create_ > 0.0 && create_type_ >= 1 && create_type_ <= atom->ntypes &&
        per_type[create_type_] > 0.0)
      hsoft_ = per_type[create_type_];
  }
  if (rho_create_ > 0.0) {
    if (!pair_) error->all(FLERR, "fix sph/astro/sink: create needs pair_style sph/astro");
    if (pair_->setflag[create_type_][create_type_])
      error->all(FLERR,
                 "fix sph/astro/sink: type {} of the new sinks has a pair_coeff of pair_style "
                 "sph/astro (it would stay gas); give a type without one",
                 create_type_);
    int dim = 0;
    if (force->pair && force->pair->extract("gravity_G", dim) && !(hsoft_ > 0.0))
      error->all(FLERR,
                 "fix sph/astro/sink: create needs a softening length for type {} of the new "
                 "sinks, which have no SPH h: pair_style sph/astro/gravity ... softening {} H "
                 "(or h H for every atom without one)",
                 create_type_, create_type_);
  }
}

/* ----------------------------------------------------------------------
   the sinks on every rank (few: P18 sec. 2.8 keeps them on every thread too)
------------------------------------------------------------------------- */

const std::vector<FixSPHAstroSink::Sink> &FixSPHAstroSink::gather_sinks()
{
  std::vector<double> mine;
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    const double rec[SINK_DOUBLES] = {static_cast<double>(atom->tag[i]),
                                      atom->x[i][0],
                                      atom->x[i][1],
                                      atom->x[i][2],
                                      atom->v[i][0],
                                      atom->v[i][1],
                                      atom->v[i][2],
                                      atom->rmass[i],
                                      spin_[i][0],
                                      spin_[i][1],
                                      spin_[i][2],
                                      macc_[i],
                                      nacc_[i],
                                      mlow_[i]};
    mine.insert(mine.end(), rec, rec + SINK_DOUBLES);
  }
  // (the owner of each record: one more gather of counts)
  const int count = static_cast<int>(mine.size() / SINK_DOUBLES);
  std::vector<int> counts(comm->nprocs);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, world);
  const std::vector<double> all = allgather(mine, world, comm->nprocs);
  const int n = static_cast<int>(all.size() / SINK_DOUBLES);
  std::vector<int> owner(n);
  for (int p = 0, k = 0; p < comm->nprocs; p++)
    for (int c = 0; c < counts[p]; c++) owner[k++] = p;
  std::vector<int> order(n);
  for (int k = 0; k < n; k++) order[k] = k;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return all[a * SINK_DOUBLES] < all[b * SINK_DOUBLES];
  });
  sinks_.resize(n);
  sink_owner_.resize(n);
  sink_local_.assign(n, -1);
  for (int k = 0; k < n; k++) {
    const double *r = &all[order[k] * SINK_DOUBLES];
    Sink &s = sinks_[k];
    s.tag = static_cast<tagint>(r[0]);
    for (int d = 0; d < 3; d++) {
      s.x[d] = r[1 + d];
      s.v[d] = r[4 + d];
      s.spin[d] = r[8 + d];
    }
    s.m = r[7];
    s.macc = r[11];
    s.nacc = r[12];
    s.mlow = r[13];
    sink_owner_[k] = owner[order[k]];
  }
  // the local index of each sink this rank owns (by ID: sinks_ is sorted)
  for (int i = 0; i < nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    auto it =
        std::lower_bound(sinks_.begin(), sinks_.end(), atom->tag[i], [](const Sink &s, tagint t) {
          return s.tag < t;
        });
    if (it != sinks_.end() && it->tag == atom->tag[i]) sink_local_[it - sinks_.begin()] = i;
  }
  return sinks_;
}

void FixSPHAstroSink::setup(int /*vflag*/)
{
  gather_sinks();
  if (candidates_near_sinks()) next_reneighbor = update->ntimestep + 1;
}

// a gas particle inside some sink's accretion radius (collective)
bool FixSPHAstroSink::candidates_near_sinks()
{
  int found = 0;
  const double racc2 = racc_ * racc_;
  if (!sinks_.empty()) {
    double **x = atom->x;
    const int *mask = atom->mask;
    for (int i = 0; i < atom->nlocal && !found; i++) {
      if (!(mask[i] & gasbit_)) continue;
      for (const Sink &s : sinks_) {
        double dx[3] = {x[i][0] - s.x[0], x[i][1] - s.x[1], x[i][2] - s.x[2]};
        domain->minimum_image(dx);
        if (dot(dx, dx) < racc2) {
          found = 1;
          break;
        }
      }
    }
  }
  int any = 0;
  MPI_Allreduce(&found, &any, 1, MPI_INT, MPI_MAX, world);
  return any != 0;
}

void FixSPHAstroSink::end_of_step()
{
  if (rho_create_ > 0.0 && try_create()) accretion_due_ = true;
  gather_sinks();
  if (accretion_due_ || candidates_near_sinks()) next_reneighbor = update->ntimestep + 1;
  accretion_due_ = false;
}

void FixSPHAstroSink::setup_pre_exchange()
{
  accrete();
}

void FixSPHAstroSink::pre_exchange()
{
  accrete();
}

/* ----------------------------------------------------------------------
   accretion (BBP95 sec. 2.2; P18 sec. 2.8.2): decided per gas particle from the gathered sinks
   (the same on every rank), applied to each sink in the order of the gas IDs
------------------------------------------------------------------------- */

void FixSPHAstroSink::accrete()
{
  gather_sinks();
  const int nsinks = static_cast<int>(sinks_.size());
  if (nsinks == 0) {
    newborn_.clear();
    return;
  }
  const int nlocal = atom->nlocal;
  double **x = atom->x;
  double **v = atom->v;
  const int *mask = atom->mask;
  const tagint *tag = atom->tag;
  const double *rmass = atom->rmass;
  const double racc2 = racc_ * racc_, rin2 = rin_ * rin_;
  std::vector<char> newborn(nsinks, 0);
  for (int k = 0; k < nsinks; k++)
    newborn[k] = std::find(newborn_.begin(), newborn_.end(), sinks_[k].tag) != newborn_.end();

  std::vector<double> records;
  std::vector<int> doomed;
  std::vector<double> e(nsinks);
  std::vector<double> rel(6 * nsinks);
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & gasbit_)) continue;
    bool inside = false;
    for (int k = 0; k < nsinks; k++) {
      const Sink &s = sinks_[k];
      double *r = &rel[6 * k];
      for (int d = 0; d < 3; d++) {
        r[d] = x[i][d] - s.x[d];
        r[3 + d] = v[i][d] - s.v[d];
      }
      domain->minimum_image(r);
      const double r2 = dot(r, r);
      // e_ia = v^2/2 - G M_a / r (BBP95 sec. 2.2); -inf at r = 0 (inside r_in anyway)
      e[k] = 0.5 * dot(r + 3, r + 3) - (r2 > 0.0 ? G_ * s.m / std::sqrt(r2) : INFINITY);
      if (r2 < racc2) inside = true;
    }
    if (!inside) continue;
    // (iv) the sink the particle is most bound to (smallest e, then smallest ID)
    int most = 0;
    for (int k = 1; k < nsinks; k++)
      if (e[k] < e[most]) most = k;
    int chosen = -1;
    for (int k = 0; k < nsinks; k++) {
      const double *r = &rel[6 * k];
      const double r2 = dot(r, r);
      if (!(r2 < racc2)) continue;
      bool ok;
      if (r2 < rin2 || newborn[k])
        ok = true;    // inner zone, or the gas around a new sink: no further checks
      else {
        double j[3];
        cross(r, r + 3, j);
        ok = e[k] < 0.0                                // (i) bound
            && dot(r, r + 3) < 0.0                     // (ii) approaching
            && dot(j, j) < G_ * sinks_[k].m * racc_    // (iii) j < sqrt(G M r_acc)
            && k == most;                              // (iv) most bound to this sink
      }
      if (ok && (chosen < 0 || e[k] < e[chosen])) chosen = k;
    }
    if (chosen < 0) continue;
    const double *r = &rel[6 * chosen];
    const double rec[RECORD_DOUBLES] = {static_cast<double>(sinks_[chosen].tag),
                                        static_cast<double>(tag[i]),
                                        rmass[i],
                                        r[0],
                                        r[1],
                                        r[2],
                                        v[i][0],
                                        v[i][1],
                                        v[i][2]};
    records.insert(records.end(), rec, rec + RECORD_DOUBLES);
    doomed.push_back(i);
  }
  newborn_.clear();

  const std::vector<double> all = allgather(records, world, comm->nprocs);
  const int nrec = static_cast<int>(all.size() / RECORD_DOUBLES);
  if (nrec == 0) return;
  // in the order (sink ID, gas ID): the same sums on every number of ranks
  std::vector<int> order(nrec);
  for (int k = 0; k < nrec; k++) order[k] = k;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const double *ra = &all[a * RECORD_DOUBLES], *rb = &all[b * RECORD_DOUBLES];
    return ra[0] != rb[0] ? ra[0] < rb[0] : ra[1] < rb[1];
  });

  int first = 0;
  for (int k = 0; k < nsinks; k++) {
    const double stag = static_cast<double>(sinks_[k].tag);
    int last = first;
    while (last < nrec && all[order[last] * RECORD_DOUBLES] == stag) last++;
    if (last == first) continue;
    const Sink &s = sinks_[k];
    // M' = M + sum m_i; M' dx' = sum m_i r_i (positions relative to the sink); M' v' = M v + sum
    // m_i v_i
    double mass = s.m, mr[3] = {0.0, 0.0, 0.0}, p[3] = {s.m * s.v[0], s.m * s.v[1], s.m * s.v[2]};
    double added = 0.0, low = s.mlow;
    for (int q = first; q < last; q++) {
      const double *rec = &all[order[q] * RECORD_DOUBLES];
      // M' = M + m_i with its round-off kept (Neumaier's compensated sum), so that the sinks'
      // mass plus the gas's stays the same to round-off of one sum over many events
      const double sum = mass + rec[2];
      low += std::fabs(mass) >= std::fabs(rec[2]) ? (mass - sum) + rec[2] : (rec[2] - sum) + mass;
      mass = sum;
      added += rec[2];
      for (int d = 0; d < 3; d++) {
        mr[d] += rec[2] * rec[3 + d];
        p[d] += rec[2] * rec[6 + d];
      }
    }
    {    // (the round-off into the mass where it fits: M + low unchanged)
      const double sum = mass + low;
      low -= sum - mass;
      mass = sum;
    }
    double shift[3], vnew[3];
    for (int d = 0; d < 3; d++) {
      shift[d] = mr[d] / mass;
      vnew[d] = p[d] / mass;
    }
    // S' = S + M (0 - shift) x (v - v') + sum m_i (r_i - shift) x (v_i - v')
    double spin[3] = {s.spin[0], s.spin[1], s.spin[2]};
    double a[3], b[3], c[3];
    for (int d = 0; d < 3; d++) {
      a[d] = -shift[d];
      b[d] = s.v[d] - vnew[d];
    }
    cross(a, b, c);
    for (int d = 0; d < 3; d++) spin[d] += s.m * c[d];
    for (int q = first; q < last; q++) {
      const double *rec = &all[order[q] * RECORD_DOUBLES];
      for (int d = 0; d < 3; d++) {
        a[d] = rec[3 + d] - shift[d];
        b[d] = rec[6 + d] - vnew[d];
      }
      cross(a, b, c);
      for (int d = 0; d < 3; d++) spin[d] += rec[2] * c[d];
    }
    total_macc_ += added;
    total_events_ += last - first;
    const int i = sink_local_[k];
    if (sink_owner_[k] == comm->me && i >= 0) {
      atom->rmass[i] = mass;
      for (int d = 0; d < 3; d++) {
        x[i][d] = s.x[d] + shift[d];
        v[i][d] = vnew[d];
        spin_[i][d] = spin[d];
      }
      macc_[i] += added;
      nacc_[i] += last - first;
      mlow_[i] = low;
    }
    first = last;
  }

  // delete the accreted gas (in reverse order: as fix evaporate), then the global count and map
  AtomVec *avec = atom->avec;
  for (auto it = doomed.rbegin(); it != doomed.rend(); ++it) {
    avec->copy(atom->nlocal - 1, *it, 1);
    atom->nlocal--;
  }
  atom->natoms -= nrec;
  if (atom->map_style != Atom::MAP_NONE) {
    atom->nghost = 0;
    atom->map_init();
    atom->map_set();
  }
  gather_sinks();
}

/* ----------------------------------------------------------------------
   the sinks' timestep bound (SPHAstro::TimestepLimiter, collective)
------------------------------------------------------------------------- */

double FixSPHAstroSink::timestep_limit()
{
  gather_sinks();
  double dt = INFINITY;
  const int nsinks = static_cast<int>(sinks_.size());
  if (nsinks == 0) {
    last_dt_limit_ = dt;
    return dt;
  }
  const double C = dt_factor_;
  // sink pairs: a fraction of the orbit, and of the approach time
  for (int a = 0; a < nsinks; a++)
    for (int b = a + 1; b < nsinks; b++) {
      double dr[3], dv[3];
      for (int d = 0; d < 3; d++) {
        dr[d] = sinks_[a].x[d] - sinks_[b].x[d];
        dv[d] = sinks_[a].v[d] - sinks_[b].v[d];
      }
      domain->minimum_image(dr);
      const double r = std::sqrt(dot(dr, dr)), vrel = std::sqrt(dot(dv, dv));
      if (r > 0.0) dt = MIN(dt, C * std::sqrt(r * r * r / (G_ * (sinks_[a].m + sinks_[b].m))));
      if (vrel > 0.0) dt = MIN(dt, C * r / vrel);
    }
  double mine = INFINITY;
  const int nlocal = atom->nlocal;
  double **x = atom->x;
  double **v = atom->v;
  double **f = atom->f;
  const int *mask = atom->mask;
  for (int i = 0; i < nlocal; i++) {
    if (mask[i] & groupbit) {    // the sink's own acceleration
      const double a = std::sqrt(dot(f[i], f[i])) / atom->rmass[i];
      if (a > 0.0) mine = MIN(mine, C * std::sqrt(racc_ / a));
    } else if (mask[i] & gasbit_) {    // gas near a sink: r_acc / |v_ia|
      for (const Sink &s : sinks_) {
        double dr[3] = {x[i][0] - s.x[0], x[i][1] - s.x[1], x[i][2] - s.x[2]};
        domain->minimum_image(dr);
        if (!(dot(dr, dr) < 4.0 * racc_ * racc_)) continue;
        double dv[3] = {v[i][0] - s.v[0], v[i][1] - s.v[1], v[i][2] - s.v[2]};
        const double vrel = std::sqrt(dot(dv, dv));
        if (vrel > 0.0) mine = MIN(mine, C * racc_ / vrel);
      }
    }
  }
  double all;
  MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE, MPI_MIN, world);
  dt = MIN(dt, all);
  last_dt_limit_ = dt;
  return dt;
}

/* ----------------------------------------------------------------------
   output
------------------------------------------------------------------------- */

double FixSPHAstroSink::compute_scalar()
{
  return static_cast<double>(gather_sinks().size());
}

double FixSPHAstroSink::compute_vector(int n)
{
  switch (n) {
    case 0:
      return static_cast<double>(gather_sinks().size());
    case 1:
      return total_macc_;
    case 2:
      return total_events_;
    case 3:
      return total_created_;
    case 4:
      return last_dt_limit_;
    default: {    // the sinks' mass with its round-off, summed in ID order
      double mass = 0.0, low = 0.0;
      for (const Sink &sink : gather_sinks()) {
        mass += sink.m;
        low += sink.mlow;
      }
      return mass + low;
    }
  }
}

/* ----------------------------------------------------------------------
   per-atom state: spin (3), accreted mass, accreted particles
------------------------------------------------------------------------- */

void FixSPHAstroSink::grow_arrays(int nmax)
{
  memory->grow(spin_, nmax, 3, "sph/astro/sink:spin");
  memory->grow(macc_, nmax, "sph/astro/sink:macc");
  memory->grow(nacc_, nmax, "sph/astro/sink:nacc");
  memory->grow(mlow_, nmax, "sph/astro/sink:mlow");
}

void FixSPHAstroSink::copy_arrays(int i, int j, int /*delflag*/)
{
  for (int d = 0; d < 3; d++) spin_[j][d] = spin_[i][d];
  macc_[j] = macc_[i];
  nacc_[j] = nacc_[i];
  mlow_[j] = mlow_[i];
}

void FixSPHAstroSink::set_arrays(int i)
{
  spin_[i][0] = spin_[i][1] = spin_[i][2] = 0.0;
  macc_[i] = nacc_[i] = mlow_[i] = 0.0;
}

int FixSPHAstroSink::pack_exchange(int i, double *buf)
{
  buf[0] = spin_[i][0];
  buf[1] = spin_[i][1];
  buf[2] = spin_[i][2];
  buf[3] = macc_[i];
  buf[4] = nacc_[i];
  buf[5] = mlow_[i];
  return 6;
}

int FixSPHAstroSink::unpack_exchange(int i, double *buf)
{
  spin_[i][0] = buf[0];
  spin_[i][1] = buf[1];
  spin_[i][2] = buf[2];
  macc_[i] = buf[3];
  nacc_[i] = buf[4];
  mlow_[i] = buf[5];
  return 6;
}

int FixSPHAstroSink::pack_restart(int i, double *buf)
{
  buf[0] = 7;    // (LAMMPS' convention: the count first)
  buf[1] = spin_[i][0];
  buf[2] = spin_[i][1];
  buf[3] = spin_[i][2];
  buf[4] = macc_[i];
  buf[5] = nacc_[i];
  buf[6] = mlow_[i];
  return 7;
}

void FixSPHAstroSink::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  m++;
  spin_[nlocal][0] = extra[nlocal][m++];
  spin_[nlocal][1] = extra[nlocal][m++];
  spin_[nlocal][2] = extra[nlocal][m++];
  macc_[nlocal] = extra[nlocal][m++];
  nacc_[nlocal] = extra[nlocal][m++];
  mlow_[nlocal] = extra[nlocal][m++];
}

int FixSPHAstroSink::size_restart(int /*i*/)
{
  return 7;
}

int FixSPHAstroSink::maxsize_restart()
{
  return 7;
}

// global restart data: the totals
void FixSPHAstroSink::write_restart(FILE *fp)
{
  if (comm->me != 0) return;
  const double list[3] = {total_macc_, total_events_, total_created_};
  const int size = 3 * sizeof(double);
  fwrite(&size, sizeof(int), 1, fp);
  fwrite(list, sizeof(double), 3, fp);
}

void FixSPHAstroSink::restart(char *buf)
{
  const auto *list = reinterpret_cast<double *>(buf);
  total_macc_ = list[0];
  total_events_ = list[1];
  total_created_ = list[2];
}

double FixSPHAstroSink::memory_usage()
{
  return 6.0 * atom->nmax * sizeof(double) + sinks_.capacity() * sizeof(Sink);
}
