/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: kernel-softened self-gravity, short-range part
------------------------------------------------------------------------- */

// Pair style sph/astro/gravity: Newtonian gravity between all atoms, softened with the SPH
// kernel (Price & Monaghan 2007, MNRAS 374, 1347, sec. 2; sph_astro_gravity_kernel.h):
//
//   E = G sum_{i<j} m_i m_j phi_ij,   phi_ij = [phi(r_ij, h_i) + phi(r_ij, h_j)] / 2
//   F_i = -G sum_j m_i m_j dphi_ij/dr  r_ij/|r_ij|,   r_ij = x_i - x_j
//
// (the mean of the two softening lengths: Price & Monaghan 2007, symmetric force of their
// sec. 2.2). Without kspace this is the whole interaction within the cutoff (direct summation
// over all pairs without a neighbour list: the cutoff must cover the system).
//
// Adaptive softening (Price & Monaghan 2007, sec. 3): when h follows the density (pair
// sph/astro in grad-h mode, fix sph/astro/h iterate: h_i = hfact (m_i/rho_i)^(1/3)) the
// energy E above depends on h_i(x), and dE/dt = sum_i v_i . grad_i E holds only with the extra
// force (derived from dE/dt with drho_i/dt = 1/Omega_i sum_j m_j v_ij . grad_i W_ij(h_i);
// written with this package's sign of phi, phi = -1/r outside the kernel)
//   F_i^zeta = -(G/2) m_i sum_j m_j [zeta_i/Omega_i grad_i W_ij(h_i)
//                                    + zeta_j/Omega_j grad_i W_ij(h_j)],
//   zeta_i = (dh_i/drho_i) sum_{j != i} m_j dphi(r_ij, h_i)/dh_i,   dh_i/drho_i = -h_i/(3 rho_i)
// (their eqs. for the "gravitational grad-h" term; Phantom implements the same). zeta_i < 0:
// the term acts like a negative pressure. The sum leaves out j = i because E here has no
// self-energy G m_i^2 phi(0, h_i)/2 (Price & Monaghan and Phantom include both; either choice
// conserves energy). Particles whose h is held at the neighbour-list cap (Omega_i = 1 there)
// get zeta_i = 0: their h does not follow rho. The sum of zeta_i runs over the kernel
// neighbours of i, those of its density: pair sph/astro's h iteration sums it.
// With a gravity kspace style the pair computes the short-range remainder that the kspace does
// not supply (the Newtonian potential split as in LAMMPS' coul/long and coul/msm):
//   PPPM (Ewald split, Hockney & Eastwood; LAMMPS pair coul/long):
//     phi_short = phi_ij + erf(g r)/r             (-> -erfc(g r)/r beyond the softening)
//   MSM (Hardy 2006; Hardy et al. 2009, Parallel Computing 35, 164, eq. 4; pair coul/msm):
//     phi_short = phi_ij + gamma(r/a)/a            (-> -(1 - r/a gamma(r/a))/r beyond it)
// where the kspace supplies -G m_i m_j erf(g r)/r or -G m_i m_j gamma(r/a)/a for every pair.

#include "pair_sph_astro_gravity.h"

#include "sph_astro_state.h"

#include "pair_sph_astro.h"
#include "sph_astro_gravity_kernel.h"
#include "sph_astro_gravity_kspace.h"
#include "sph_astro_gravity_pair.h"
#include "sph_astro_options.h"

#include "sph_astro_pair_coeff.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "kspace.h"
#include "math_const.h"
#include "memory.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"
#include "utils.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

using namespace LAMMPS_NS;
using namespace SPHAstro;
using MathConst::MY_PIS;

PairSPHAstroGravity::PairSPHAstroGravity(LAMMPS *lmp) : Pair(lmp)
{
  cut_global_ = 0.0;
  G_ = 0.0;
  G_given_ = false;
  kernel_ = SPHAstro::KernelType::CUBIC;
  kernel_given_ = false;
  hfixed_ = 0.0;
  have_state_ = false;
  split_ = Split::NONE;
  g_ewald_ = 0.0;
  zeta_on_ = true;
  zeta_active_ = false;
  sph_ = nullptr;
  zeta_ = nullptr;
  zeta_over_omega_ = nullptr;
  nmax_ = 0;
  comm_stage_ = Stage::H;
  offset_ = 0;
  ntotal_ = 0;
  state_ = new SPHAstro::StateIndex();
  single_enable = 0;
  restartinfo = 1;
  one_coeff = 1;
  comm_forward = 2;    // softening length h of the ghosts, or zeta and zeta / Omega
  // the long-range solvers check these flags; a non-gravity solver is refused in extract()
  ewaldflag = pppmflag = msmflag = 1;
  ncoultablebits = 0;    // no tabulation (the kspace accuracy estimates include table errors)
}

PairSPHAstroGravity::~PairSPHAstroGravity()
{
  if (copymode) return;
  delete state_;
  memory->destroy(zeta_);
  memory->destroy(zeta_over_omega_);
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
  }
}

void PairSPHAstroGravity::allocate()
{
  allocated = 1;
  const int n = atom->ntypes + 1;
  memory->create(setflag, n, n, "pair:setflag");
  for (int i = 1; i < n; i++)
    for (int j = i; j < n; j++) setflag[i][j] = 0;
  memory->create(cutsq, n, n, "pair:cutsq");
}

/* ----------------------------------------------------------------------
   pair_style sph/astro/gravity CUTOFF [G VALUE] [kernel NAME] [h VALUE] [zeta yes|no]
                                [softening TYPES H] ...
------------------------------------------------------------------------- */

void PairSPHAstroGravity::settings(int narg, char **arg)
{
  if (narg < 1) utils::missing_cmd_args(FLERR, "pair_style sph/astro/gravity", error);
  cut_global_ = utils::numeric(FLERR, arg[0], false, lmp);
  if (!(cut_global_ > 0.0))
    error->all(FLERR, "pair_style sph/astro/gravity: cutoff {} must be > 0", arg[0]);
  G_given_ = kernel_given_ = false;
  hfixed_ = 0.0;
  soft_given_.clear();
  soft_type_.clear();
  zeta_on_ = true;
  kernel_ = KernelType::CUBIC;
  int iarg = 1;
  while (iarg < narg) {
    const std::string key = arg[iarg];
    if (iarg + 2 > narg)
      utils::missing_cmd_args(FLERR, "pair_style sph/astro/gravity " + key, error);
    if (key == "G") {
      G_ = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(G_ > 0.0))
        error->all(FLERR, "pair_style sph/astro/gravity: G = {} must be > 0", arg[iarg + 1]);
      G_given_ = true;
    } else if (key == "kernel") {
      if (!kernel_from_name(arg[iarg + 1], kernel_) || kernel_ == KernelType::GAUSSIAN)
        error->all(FLERR,
                   "pair_style sph/astro/gravity: unknown kernel '{}'; allowed: m4 (cubic), m6 "
                   "(quintic), wendland/c2, wendland/c4",
                   arg[iarg + 1]);
      kernel_given_ = true;
    } else if (key == "h") {
      hfixed_ = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(hfixed_ > 0.0))
        error->all(FLERR,
                   "pair_style sph/astro/gravity: softening length h = {} must be > 0 (point "
                   "masses need a softening length)",
                   arg[iarg + 1]);
    } else if (key == "zeta") {
      zeta_on_ = utils::logical(FLERR, arg[iarg + 1], false, lmp) != 0;
    } else if (key == "softening") {
      // softening TYPES H: softening length H of the atoms of TYPES (a type or a range, e.g.
      // 2*3), point masses that are not SPH gas; repeatable, a later one wins for a type (not
      // "soft": pair_style hybrid would take it for LAMMPS' pair style soft)
      if (iarg + 3 > narg)
        utils::missing_cmd_args(FLERR, "pair_style sph/astro/gravity softening", error);
      const double h = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
      if (!(h > 0.0) || !std::isfinite(h))
        error->all(FLERR,
                   "pair_style sph/astro/gravity: softening {} {}: the length must be finite "
                   "and > 0",
                   arg[iarg + 1], arg[iarg + 2]);
      soft_given_.emplace_back(arg[iarg + 1], h);
      iarg += 1;
    } else
      error->all(FLERR,
                 "pair_style sph/astro/gravity: unknown keyword '{}'; allowed: G, kernel, h, "
                 "zeta, softening",
                 key);
    iarg += 2;
  }
  if (domain->box_exist) resolve_type_softening();
  resolve_gravity_constant();
  // q holds the masses for the kspace solvers; with it in place a non-gravity kspace style
  // reaches extract("cut_coul") below and gets a clear error
  ensure_mass_charge(lmp, "pair_style sph/astro/gravity");
}

// default G by unit system (CODATA 2018: 6.67430e-11 m^3 kg^-1 s^-2)
void PairSPHAstroGravity::resolve_gravity_constant()
{
  if (G_given_) return;
  const std::string units = update->unit_style;
  if (units == "lj")
    G_ = 1.0;
  else if (units == "si")
    G_ = 6.67430e-11;
  else if (units == "cgs")
    G_ = 6.67430e-8;
  else
    error->all(FLERR,
               "pair_style sph/astro/gravity: no default G for units {}; give it explicitly "
               "(pair_style sph/astro/gravity CUTOFF G VALUE); defaults exist for lj (1), si "
               "(6.6743e-11) and cgs (6.6743e-8)",
               units);
}

void PairSPHAstroGravity::coeff(int narg, char **arg)
{
  if (!allocated) allocate();
  SPHAstro::set_type_pairs(lmp, "sph/astro/gravity", narg, arg, setflag);
}

double *PairSPHAstroGravity::state_h() const
{
  return have_state_ ? atom->dvector[state_->h] : nullptr;
}

double PairSPHAstroGravity::softening_length(int i) const
{
  const int t = atom->type[i];
  if (t < static_cast<int>(soft_type_.size()) && soft_type_[t] > 0.0) return soft_type_[t];
  const double *h = state_h();
  return (h && h[i] > 0.0) ? h[i] : hfixed_;
}

// the type ranges of the keyword softening against the number of types (errors name the range and
// the allowed types)
void PairSPHAstroGravity::resolve_type_softening()
{
  const int ntypes = atom->ntypes;
  std::vector<double> soft(ntypes + 1, 0.0);
  for (const auto &[range, h] : soft_given_) {
    int lo = 0, hi = -1;
    if (utils::strmatch(range, "^\\d+$")) {
      lo = hi = utils::inumeric(FLERR, range, false, lmp);
      if (lo < 1 || lo > ntypes)
        error->all(
            FLERR,
            "pair_style sph/astro/gravity: softening {} {}: atom type {} is out of range 1-{}",
            range, h, lo, ntypes);
    } else
      utils::bounds(FLERR, range, 1, ntypes, lo, hi, error);
    for (int t = lo; t <= hi; t++) soft[t] = h;
  }
  soft_type_ = soft;
}

void PairSPHAstroGravity::init_style()
{
  if (domain->dimension != 3)
    error->all(FLERR,
               "pair_style sph/astro/gravity: dimension {} not supported (3d Newtonian gravity)",
               domain->dimension);
  if (domain->triclinic)
    error->all(FLERR, "pair_style sph/astro/gravity: triclinic boxes are not supported");
  resolve_gravity_constant();
  active_ = ActiveSet();    // all active until fix sph/astro says otherwise

  // the kernel of pair sph/astro, if present
  auto *sph = dynamic_cast<PairSPHAstro *>(force->pair_match("^sph/astro$", 0, 0));
  sph_ = sph;
  if (sph) {
    if (kernel_given_ && sph->options().kernel != kernel_)
      error->all(FLERR,
                 "pair_style sph/astro/gravity: kernel {} differs from the kernel {} of pair "
                 "sph/astro; drop the keyword to use the same",
                 kernel_name(kernel_), kernel_name(sph->options().kernel));
    kernel_ = sph->options().kernel;
  }
  // the sums of zeta from pair sph/astro's h iteration
  if (sph && zeta_on_) sph->sum_softening_derivatives();
  // the softened potential has closed forms for the polynomial kernels only
  if (kernel_ == KernelType::GAUSSIAN)
    error->all(FLERR,
               "pair_style sph/astro/gravity: no softened potential for kernel gaussian; "
               "allowed: m4, m6, wendland/c2, wendland/c4");
  have_state_ = find_state(lmp, *state_);
  resolve_type_softening();
  // the softening of the gas is its smoothing length: softening is for the types that are not gas
  if (sph && sph->allocated)
    for (int t = 1; t < static_cast<int>(soft_type_.size()); t++)
      if (soft_type_[t] > 0.0 && sph->setflag[t][t])
        error->all(
            FLERR,
            "pair_style sph/astro/gravity: softening for type {}: type {} is SPH gas of pair "
            "sph/astro (its softening length is its smoothing length d_h); give softening only "
            "for the types of point masses",
            t, t);

  // every atom needs a mass and a softening length
  const double R = SPHAstro::kernel_radius(kernel_);
  double hmax = 0.0;
  for (int i = 0; i < atom->nlocal; i++) {
    const double m = atom->rmass ? atom->rmass[i] : atom->mass[atom->type[i]];
    if (!(m > 0.0) || !std::isfinite(m))
      error->one(FLERR, "pair_style sph/astro/gravity: atom {} has mass {}; masses must be > 0",
                 atom->tag[i], m);
    const double h = softening_length(i);
    if (!(h > 0.0) || !std::isfinite(h))
      error->one(FLERR,
                 "pair_style sph/astro/gravity: atom {} (type {}) has no softening length (d_h "
                 "= {}); set d_h, or give one for its type: pair_style sph/astro/gravity "
                 "CUTOFF softening {} VALUE (or h VALUE for every atom without d_h)",
                 atom->tag[i], atom->type[i], have_state_ ? state_h()[i] : 0.0, atom->type[i]);
    hmax = MAX(hmax, h);
  }
  double hmax_all;
  MPI_Allreduce(&hmax, &hmax_all, 1, MPI_DOUBLE, MPI_MAX, world);

  // which long-range solver supplies the rest
  split_ = Split::NONE;
  if (force->kspace) {
    const std::string style = force->kspace_style;
    if (style == "pppm/sph/astro/gravity") {
      split_ = Split::EWALD;
      g_ewald_ = force->kspace->g_ewald;
    } else if (style == "msm/sph/astro/gravity")
      split_ = Split::MSM;
    else if (style == "tree/sph/astro/gravity")
      split_ = Split::TREE;
    else
      error->all(FLERR,
                 "pair_style sph/astro/gravity: kspace_style {} is not a gravity solver; use "
                 "tree/sph/astro/gravity or msm/sph/astro/gravity (open boundaries), or "
                 "pppm/sph/astro/gravity (periodic)",
                 style);
    if ((split_ != Split::TREE || periodic_tree()) && R * hmax_all > cut_global_)
      error->all(FLERR,
                 "pair_style sph/astro/gravity: cutoff {} is shorter than the softening support "
                 "{} x h = {} of the largest h; the short-range part must cover it",
                 cut_global_, R, R * hmax_all);
  } else {
    if (domain->nonperiodic != 2 && (domain->xperiodic || domain->yperiodic || domain->zperiodic))
      error->all(FLERR,
                 "pair_style sph/astro/gravity without kspace needs non-periodic boundaries "
                 "(direct summation); for periodic boxes add kspace_style pppm/sph/astro/gravity");
    const double diag = std::sqrt(domain->xprd * domain->xprd + domain->yprd * domain->yprd +
                                  domain->zprd * domain->zprd);
    if (cut_global_ < diag && comm->me == 0)
      error->warning(FLERR,
                     "pair_style sph/astro/gravity: cutoff {} is shorter than the box diagonal "
                     "{} and there is no kspace: gravity between atoms farther apart is left "
                     "out",
                     cut_global_, diag);
  }
  // direct summation sums over all atoms itself (gather_all), the tree too; the kspace split
  // needs the short-range neighbour list
  if (split_ == Split::EWALD || split_ == Split::MSM) neighbor->add_request(this);
}

double PairSPHAstroGravity::init_one(int i, int j)
{
  if (setflag[i][j] == 0)
    error->all(FLERR,
               "pair_style sph/astro/gravity: pair_coeff for types {} {} is not set; gravity "
               "acts between all atoms (pair_coeff * *)",
               i, j);
  // direct summation needs neither a neighbour list nor ghost atoms: no cutoff for LAMMPS, so
  // that under hybrid/overlay the lists (and ghost shell) of pair sph/astro keep their size
  return list_cutoff();
}

/* ---------------------------------------------------------------------- */

void PairSPHAstroGravity::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  // the tree (kspace tree/sph/astro/gravity) computes every pair; it takes zeta/Omega of the
  // owned atoms from here
  // ghosts need this step's softening lengths (fix sph/astro/h may have changed them)
  const bool ghosts = split_ == Split::EWALD || split_ == Split::MSM || periodic_tree();
  if (have_state_ && ghosts) {
    comm_stage_ = Stage::H;
    comm->forward_comm(this);
  }
  if (split_ == Split::TREE) {
    zeta_active_ = zeta_terms_apply();
    if (zeta_active_) compute_zeta();
    return;
  }
  if (split_ == Split::NONE) gather_all();
  // individual timesteps: forces only for the pairs with an active atom, unless the virial or
  // per-atom energies are tallied (they need every pair's force)
  active_pairs_only_ = split_ == Split::NONE && !active_.all() && !vflag_either && !eflag_atom;
  zeta_active_ = zeta_terms_apply();
  if (zeta_active_) compute_zeta();
  const bool cubic = kernel_ == KernelType::CUBIC;
#define SPH_ASTRO_GRAVITY_EVAL(SPLIT)          \
  if (zeta_active_) {                          \
    if (cubic)                                 \
      eval<true, SPLIT, true>(eflag, vflag);   \
    else                                       \
      eval<false, SPLIT, true>(eflag, vflag);  \
  } else {                                     \
    if (cubic)                                 \
      eval<true, SPLIT, false>(eflag, vflag);  \
    else                                       \
      eval<false, SPLIT, false>(eflag, vflag); \
  }
  if (split_ == Split::NONE) {
    SPH_ASTRO_GRAVITY_EVAL(0)
  } else if (split_ == Split::EWALD) {
    SPH_ASTRO_GRAVITY_EVAL(1)
  } else {
    SPH_ASTRO_GRAVITY_EVAL(2)
  }
#undef SPH_ASTRO_GRAVITY_EVAL
  if (vflag_fdotr) virial_fdotr_compute();
}

bool PairSPHAstroGravity::periodic_tree() const
{
  return split_ == Split::TREE && domain->xperiodic && domain->yperiodic && domain->zperiodic;
}

namespace {
// direct summation, atom i (xi, yi, zi, softening hi, G m_i) with the partners k < n: the
// force fpair = -G m_i m_k (1/r^2)/r and energy e = 0 - 1/r of pair_term() beyond the softening
// support (the same roundings), computed in vector lanes; kind[k] = 0 beyond the cutoff, 1
// beyond the support, 2 within it (then pair_term() decides)
template <bool ENERGY>
void beyond_support(int n, double xi, double yi, double zi, double hi, double Gmi, double R,
                    double cutsq, const double *__restrict gx, const double *__restrict gy,
                    const double *__restrict gz, const double *__restrict gm,
                    const double *__restrict gh, double *__restrict force,
                    double *__restrict energy, char *__restrict kind)
{
  for (int k = 0; k < n; k++) {
    const double delx = xi - gx[k], dely = yi - gy[k], delz = zi - gz[k];
    const double rsq = delx * delx + dely * dely + delz * delz;
    const double r = std::sqrt(rsq);
    const double hmax = hi > gh[k] ? hi : gh[k];
    kind[k] = static_cast<char>((rsq < cutsq) * (1 + (r < R * hmax)));
    force[k] = -(Gmi * gm[k]) * ((1.0 / rsq) / r);
    if (ENERGY) energy[k] = 0.0 - 1.0 / r;
  }
}
}    // namespace

/* ----------------------------------------------------------------------
   forces and energy; one pair term for both drivers (gathered atoms or neighbour list)
------------------------------------------------------------------------- */

template <bool CUBIC, int SPLIT, bool ZETA> void PairSPHAstroGravity::eval(int eflag, int /*vflag*/)
{
  double **x = atom->x;
  double **f = atom->f;
  const int *type = atom->type;
  const double *rmass = atom->rmass;
  const double *mass = atom->mass;
  const int nlocal = atom->nlocal;
  const int newton_pair = force->newton_pair;
  const double *hstate = state_h();
  const double hfix = hfixed_;
  // softening length of owned or ghost atom i (softening_length(), inlined)
  const double *soft_type = soft_type_.data();
  const int nsoft = static_cast<int>(soft_type_.size());
  auto soft_of = [&](int i) {
    const int t = type[i];
    if (t < nsoft && soft_type[t] > 0.0) return soft_type[t];
    return (hstate && hstate[i] > 0.0) ? hstate[i] : hfix;
  };
  const SoftenedKernel &soft = softened_kernel(kernel_);
  const double R = soft.radius();
  const double cutsq = cut_global_ * cut_global_;
  const double G = G_;
  const double g = g_ewald_;
  const double a = cut_global_;    // MSM split radius
  const KSpace *kspace = force->kspace;
  const KernelType kernel = kernel_;

  // potential e (per G m_i m_j) of the part this pair style supplies and D = de/dr plus the zeta
  // terms, so that F_i = -G m_i m_j D r_ij/r; zoi, zoj: zeta/Omega of the two atoms
  auto pair_term = [&](double rsq, double hi, double hj, double zoi, double zoj, double &e,
                       double &D) {
    const double r = std::sqrt(rsq);
    // softened - Newtonian: s = phi_ij + 1/r, ds = dphi_ij/dr - 1/r^2, zero beyond both
    // supports (computed as the difference only inside, so no cancellation outside)
    double s = 0.0, ds = 0.0, dzeta = 0.0;
    if (r < R * MAX(hi, hj)) {
      double phi, dphi;
      softened_pair_inside<CUBIC>(soft, r, hi, hj, phi, dphi);
      if (r == 0.0) {    // coincident atoms: finite potential, no force
        e = phi;
        if (SPLIT == 1) e += 2.0 * g / MY_PIS;
        if (SPLIT == 2) e += kspace->gamma(0.0) / a;
        D = 0.0;
        return;
      }
      s = phi + 1.0 / r;
      ds = dphi - 1.0 / rsq;
      // zeta terms: 1/2 [zeta_i/Omega_i dW/dr(h_i) + zeta_j/Omega_j dW/dr(h_j)]
      if (ZETA) dzeta = zeta_pair_term(kernel, r, hi, hj, zoi, zoj);
    }
    double de;
    if (SPLIT == 0) {
      e = s - 1.0 / r;
      de = ds + 1.0 / rsq;
    } else if (SPLIT == 1) {
      // Newtonian minus the long-range erf(g r)/r of the kspace: -erfc(g r)/r
      const double erfc_r = std::erfc(g * r) / r;
      e = s - erfc_r;
      de = ds + erfc_r / r + 2.0 * g / MY_PIS * std::exp(-g * g * rsq) / r;
    } else {
      // Newtonian minus the long-range gamma(r/a)/a of MSM: -(1 - rho gamma(rho))/r
      const double rho = r / a;
      e = s - (1.0 - rho * kspace->gamma(rho)) / r;
      de = ds + (1.0 + rho * rho * kspace->dgamma(rho)) / rsq;
    }
    D = (de + dzeta) / r;
  };

  if (SPLIT == 0) {
    // direct summation over the gathered atoms
    const double *all = all_.data();
    const double *zo_all = ZETA ? zo_all_.data() : nullptr;
    const int n = ntotal_;
    const int first = offset_, last = offset_ + nlocal;
    // individual timesteps (active_pairs_only_): the forces of inactive atoms are not used, so
    // an inactive atom's row sums forces only with this rank's active atoms after it (for their
    // forces; pairs with active atoms of other ranks are summed in those atoms' rows there) and,
    // with energy tallied, the potential alone of its other pairs; an active atom's force sums
    // the same terms in the same order as with every pair
    const char *active_all = active_pairs_only_ ? active_all_.data() : nullptr;
    if (active_all) {
      active_mine_.clear();
      for (int j = 0; j < nlocal; j++)
        if (active_all[first + j]) active_mine_.push_back(j);
    }
    const double RR = R * R;
    row_force_.resize(n);
    row_energy_.resize(n);
    row_kind_.resize(n);
    for (int i = 0; i < nlocal; i++) {
      const int gi = first + i;
      const double *ai = all + 5 * gi;
      const double xi = ai[0], yi = ai[1], zi = ai[2], mi = ai[3], hi = ai[4];
      const double zoi = ZETA ? zo_all[gi] : 0.0;
      double fxi = 0.0, fyi = 0.0, fzi = 0.0;
      // the force (and energy) of pair (i, gj): fpair = -G m_i m_j D, e per G m_i m_j
      auto accumulate = [&](int gj, double delx, double dely, double delz, double mm, double fpair,
                            double e) __attribute__((always_inline))
      {
        fxi += delx * fpair;
        fyi += dely * fpair;
        fzi += delz * fpair;
        const bool mine = gj >= first && gj < last;
        if (mine) {
          const int j = gj - first;
          f[j][0] -= delx * fpair;
          f[j][1] -= dely * fpair;
          f[j][2] -= delz * fpair;
        }
        // pairs with atoms of other ranks: the other rank tallies the other half
        if (active_all) {
          if (eflag_global) eng_vdwl += mine ? mm * e : 0.5 * mm * e;
        } else if (mine) {
          if (evflag)
            ev_tally(i, gj - first, nlocal, 1, eflag ? mm * e : 0.0, 0.0, fpair, delx, dely, delz);
        } else if (evflag)
          ev_tally(i, nlocal, nlocal, 0, eflag ? mm * e : 0.0, 0.0, fpair, delx, dely, delz);
      };
      auto pair = [&](int gj) __attribute__((always_inline))
      {
        const double *aj = all + 5 * gj;
        const double delx = xi - aj[0], dely = yi - aj[1], delz = zi - aj[2];
        const double rsq = delx * delx + dely * dely + delz * delz;
        if (rsq >= cutsq) return;
        double e, D;
        pair_term(rsq, hi, aj[4], zoi, ZETA ? zo_all[gj] : 0.0, e, D);
        const double mm = G * mi * aj[3];
        accumulate(gj, delx, dely, delz, mm, -mm * D, e);
      };
      // the pairs (i, gj) of gj in [a, b) (mine: this rank's atoms): first, for all of them at
      // once (in vector lanes), the force and energy of pair_term() beyond the softening
      // support, D = (1/r^2)/r and e = -1/r with the same roundings; then, in the order of gj,
      // the pairs within the support by pair_term() and the sums
      const bool with_e = evflag || (active_all && eflag_global);
      auto pairs = [&](int a, int b, bool mine) {
        const int len = b - a;
        if (len <= 0) return;
        const double *gx = gx_.data() + a, *gy = gy_.data() + a, *gz = gz_.data() + a;
        const double *gm = gm_.data() + a, *gh = gh_.data() + a;
        double *fbuf = row_force_.data(), *ebuf = row_energy_.data();
        char *kind = row_kind_.data();
        const double Gmi = G * mi;
        if (with_e)
          beyond_support<true>(len, xi, yi, zi, hi, Gmi, R, cutsq, gx, gy, gz, gm, gh, fbuf, ebuf,
                               kind);
        else
          beyond_support<false>(len, xi, yi, zi, hi, Gmi, R, cutsq, gx, gy, gz, gm, gh, fbuf, ebuf,
                                kind);
        if (evflag && !active_all) {    // ev_tally()
          for (int k = 0; k < len; k++) {
            if (kind[k] == 0) continue;
            if (kind[k] == 2) {
              pair(a + k);
              continue;
            }
            const double delx = xi - gx[k], dely = yi - gy[k], delz = zi - gz[k];
            accumulate(a + k, delx, dely, delz, Gmi * gm[k], fbuf[k], ebuf[k]);
          }
          return;
        }
        // accumulate()'s sums in registers (the same operations in the same order)
        const bool tally = active_all && eflag_global;
        double fx = fxi, fy = fyi, fz = fzi, eng = eng_vdwl;
        double *fj = f[0] + 3 * (a - first);    // (f is one block of 3 per atom)
        for (int k = 0; k < len; k++, fj += 3) {
          if (kind[k] == 0) continue;
          if (kind[k] == 2) {
            fxi = fx, fyi = fy, fzi = fz, eng_vdwl = eng;
            pair(a + k);
            fx = fxi, fy = fyi, fz = fzi, eng = eng_vdwl;
            continue;
          }
          const double delx = xi - gx[k], dely = yi - gy[k], delz = zi - gz[k];
          const double fpair = fbuf[k];
          fx += delx * fpair;
          fy += dely * fpair;
          fz += delz * fpair;
          if (mine) {
            fj[0] -= delx * fpair;
            fj[1] -= dely * fpair;
            fj[2] -= delz * fpair;
          }
          if (tally) {
            const double mm = Gmi * gm[k], e = ebuf[k];
            eng += mine ? mm * e : 0.5 * mm * e;
          }
        }
        fxi = fx, fyi = fy, fzi = fz, eng_vdwl = eng;
      };
      // the potential of a pair without its force (per G m_i m_j): softened within the
      // support, -1/r beyond it
      auto potential = [&](int gj) {
        const double *aj = all + 5 * gj;
        const double delx = xi - aj[0], dely = yi - aj[1], delz = zi - aj[2];
        const double rsq = delx * delx + dely * dely + delz * delz;
        if (rsq >= cutsq) return 0.0;
        const double hj = aj[4], hmax = MAX(hi, hj);
        double e = 0.0;
        if (rsq < RR * hmax * hmax) {
          double D;
          pair_term(rsq, hi, hj, 0.0, 0.0, e, D);
        } else
          e = -1.0 / std::sqrt(rsq);
        return G * mi * aj[3] * e;
      };
      if (active_all && !active_all[gi]) {
        auto after = std::upper_bound(active_mine_.begin(), active_mine_.end(), i);
        for (auto it = after; it != active_mine_.end(); ++it) pair(first + *it);
        if (eflag_global) {
          double half = 0.0, whole = 0.0;
          for (int gj = 0; gj < first; gj++) half += potential(gj);
          for (int gj = gi + 1; gj < last; gj++)
            if (!active_all[gj]) whole += potential(gj);
          for (int gj = last; gj < n; gj++) half += potential(gj);
          eng_vdwl += whole + 0.5 * half;
        }
      } else {
        pairs(0, first, false);
        pairs(gi + 1, last, true);    // in-rank pairs once
        pairs(last, n, false);
      }
      f[i][0] += fxi;
      f[i][1] += fyi;
      f[i][2] += fzi;
    }
    return;
  }

  // short-range part over the neighbour list; the softening support must be inside the cutoff
  const double *zeta_over_omega = zeta_over_omega_;
  const int inum = list->inum;
  const int *ilist = list->ilist;
  const int *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;
  // individual timesteps: pairs of two inactive atoms left out, as above (owned and ghost flags)
  const bool some = !evflag && !active_.all();
  const int *mask = atom->mask;
  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    const bool i_inactive = some && !active_.active(i, mask);    // then active partners only
    const double xi = x[i][0], yi = x[i][1], zi = x[i][2];
    const double mi = rmass ? rmass[i] : mass[type[i]];
    const double hi = soft_of(i);
    if (R * hi > cut_global_)
      error->one(FLERR,
                 "pair_style sph/astro/gravity: atom {} has softening support {} x h = {} beyond "
                 "the cutoff {} on step {}; the short-range part must cover it (larger cutoff)",
                 atom->tag[i], R, R * hi, cut_global_, update->ntimestep);
    const double zoi = ZETA ? zeta_over_omega[i] : 0.0;
    double fxi = 0.0, fyi = 0.0, fzi = 0.0;
    const int *jlist = firstneigh[i];
    const int jnum = numneigh[i];
    for (int jj = 0; jj < jnum; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      if (i_inactive && !active_.active(j, mask)) continue;
      const double delx = xi - x[j][0], dely = yi - x[j][1], delz = zi - x[j][2];
      const double rsq = delx * delx + dely * dely + delz * delz;
      if (rsq >= cutsq) continue;
      const double mj = rmass ? rmass[j] : mass[type[j]];
      const double hj = soft_of(j);
      double e, D;
      pair_term(rsq, hi, hj, zoi, ZETA ? zeta_over_omega[j] : 0.0, e, D);
      const double mm = G * mi * mj;
      const double fpair = -mm * D;
      fxi += delx * fpair;
      fyi += dely * fpair;
      fzi += delz * fpair;
      if (newton_pair || j < nlocal) {
        f[j][0] -= delx * fpair;
        f[j][1] -= dely * fpair;
        f[j][2] -= delz * fpair;
      }
      if (evflag)
        ev_tally(i, j, nlocal, newton_pair, eflag ? mm * e : 0.0, 0.0, fpair, delx, dely, delz);
    }
    f[i][0] += fxi;
    f[i][1] += fyi;
    f[i][2] += fzi;
  }
}

/* ---------------------------------------------------------------------- */

int PairSPHAstroGravity::pack_forward_comm(int n, int *list, double *buf, int /*pbc_flag*/,
                                           int * /*pbc*/)
{
  if (comm_stage_ == Stage::ZETA) {
    for (int k = 0; k < n; k++) {
      buf[2 * k] = zeta_[list[k]];
      buf[2 * k + 1] = zeta_over_omega_[list[k]];
    }
    return 2 * n;
  }
  const double *h = state_h();
  for (int k = 0; k < n; k++) buf[k] = h[list[k]];
  return n;
}

void PairSPHAstroGravity::unpack_forward_comm(int n, int first, double *buf)
{
  if (comm_stage_ == Stage::ZETA) {
    for (int k = 0; k < n; k++) {
      zeta_[first + k] = buf[2 * k];
      zeta_over_omega_[first + k] = buf[2 * k + 1];
    }
    return;
  }
  double *h = state_h();
  for (int k = 0; k < n; k++) h[first + k] = buf[k];
}

// zeta: zeta_i of owned and ghost atoms, while the zeta terms are active (else null)
void *PairSPHAstroGravity::extract_peratom(const char *name, int &ncol)
{
  ncol = 0;
  if (strcmp(name, "zeta") == 0) return zeta_active_ ? (void *) zeta_ : nullptr;
  return nullptr;
}

double PairSPHAstroGravity::memory_usage()
{
  // (the gathered atoms of direct summation: capacity, as they are kept between steps)
  const double gathered =
      (all_.capacity() + zo_all_.capacity() + gx_.capacity() + gy_.capacity() + gz_.capacity() +
       gm_.capacity() + gh_.capacity() + row_force_.capacity() + row_energy_.capacity()) *
          sizeof(double) +
      active_mine_.capacity() * sizeof(int) + active_all_.capacity() + row_kind_.capacity();
  return 2.0 * nmax_ * sizeof(double) + gathered + Pair::memory_usage();
}

/* ----------------------------------------------------------------------
   cut_coul: the real-space cutoff for the gravity kspace solvers (refused to others);
   gravity_G: the gravitational constant they use as -G in place of qqrd2e
------------------------------------------------------------------------- */

void *PairSPHAstroGravity::extract(const char *str, int &dim)
{
  dim = 0;
  if (strcmp(str, "gravity_G") == 0) {
    resolve_gravity_constant();
    return (void *) &G_;
  }
  // the fixed softening length of atoms without SPH state (0: none; fix sph/astro/sink: sinks)
  if (strcmp(str, "gravity_hfixed") == 0) return (void *) &hfixed_;
  // the softening length per atom type (index 1..ntypes; 0: none given), after init
  if (strcmp(str, "gravity_softening_types") == 0) {
    dim = 1;
    return soft_type_.empty() ? nullptr : (void *) soft_type_.data();
  }
  if (strcmp(str, "cut_coul") == 0) {
    const std::string kstyle = force->kspace ? force->kspace_style : "";
    if (force->kspace && kstyle != "pppm/sph/astro/gravity" && kstyle != "msm/sph/astro/gravity" &&
        kstyle != "tree/sph/astro/gravity")
      error->all(FLERR,
                 "pair_style sph/astro/gravity: kspace_style {} is not a gravity solver; use "
                 "pppm/sph/astro/gravity (periodic) or msm/sph/astro/gravity (open boundaries)",
                 force->kspace_style);
    return (void *) &cut_global_;
  }
  return nullptr;
}

/* ---------------------------------------------------------------------- */

void PairSPHAstroGravity::write_restart(FILE *fp)
{
  write_restart_settings(fp);
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) fwrite(&setflag[i][j], sizeof(int), 1, fp);
}

void PairSPHAstroGravity::read_restart(FILE *fp)
{
  read_restart_settings(fp);
  allocate();
  const int me = comm->me;
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      if (me == 0) utils::sfread(FLERR, &setflag[i][j], sizeof(int), 1, fp, nullptr, error);
      MPI_Bcast(&setflag[i][j], 1, MPI_INT, 0, world);
    }
}

void PairSPHAstroGravity::write_restart_settings(FILE *fp)
{
  const int kernel = static_cast<int>(kernel_);
  const int flags[3] = {G_given_ ? 1 : 0, kernel_given_ ? 1 : 0, zeta_on_ ? 1 : 0};
  fwrite(&cut_global_, sizeof(double), 1, fp);
  fwrite(&G_, sizeof(double), 1, fp);
  fwrite(&hfixed_, sizeof(double), 1, fp);
  fwrite(&kernel, sizeof(int), 1, fp);
  fwrite(flags, sizeof(int), 3, fp);
  // the softening length of each type (keyword softening; 0: none), types 1 to ntypes
  const int n = atom->ntypes;
  std::vector<double> soft(n + 1, 0.0);
  for (int t = 1; t <= n && t < static_cast<int>(soft_type_.size()); t++) soft[t] = soft_type_[t];
  fwrite(soft.data() + 1, sizeof(double), n, fp);
}

void PairSPHAstroGravity::read_restart_settings(FILE *fp)
{
  double d[3];
  int ints[4];
  if (comm->me == 0) {
    utils::sfread(FLERR, d, sizeof(double), 3, fp, nullptr, error);
    utils::sfread(FLERR, ints, sizeof(int), 4, fp, nullptr, error);
  }
  MPI_Bcast(d, 3, MPI_DOUBLE, 0, world);
  MPI_Bcast(ints, 4, MPI_INT, 0, world);
  cut_global_ = d[0];
  G_ = d[1];
  hfixed_ = d[2];
  kernel_ = static_cast<KernelType>(ints[0]);
  G_given_ = ints[1] != 0;
  kernel_given_ = ints[2] != 0;
  zeta_on_ = ints[3] != 0;
  const int n = atom->ntypes;
  std::vector<double> soft(n + 1, 0.0);
  if (comm->me == 0) utils::sfread(FLERR, soft.data() + 1, sizeof(double), n, fp, nullptr, error);
  MPI_Bcast(soft.data(), n + 1, MPI_DOUBLE, 0, world);
  // (kept as given per type, so that init resolves them again)
  soft_given_.clear();
  for (int t = 1; t <= n; t++)
    if (soft[t] > 0.0) soft_given_.emplace_back(std::to_string(t), soft[t]);
  soft_type_ = soft;
  warn_hybrid_restart(lmp, this, "sph/astro/gravity");
}
