/* ----------------------------------------------------------------------
   SPH-ASTRO: variable smoothing length
------------------------------------------------------------------------- */

// fix ID group sph/astro/h dhdt [margin M]
// fix ID group sph/astro/h iterate [hfact F] [tol T] [maxiter N] [margin M]
//
// In both modes h is advanced with the drift of fix sph/astro, h <- h exp(dt div v / d), the
// integral of dh/dt = (h/d) div v at fixed div v (seed 000 eq. 1). In dhdt mode that is the
// evolution; in iterate mode it is the starting guess of the Newton-Raphson iteration that
// pair sph/astro runs in its density pass. Smoothing lengths are capped at margin x the
// largest h of their type when the run began (the neighbour list cutoffs are set for it).
//
// Global vector: 1 mean Newton iterations per particle of the latest density pass,
// 2 largest number of iterations, 3 particles that did not converge since the run began,
// 4 particles held at the h cap in the latest pass.

#include "fix_sph_astro_h.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "modify.h"
#include "pair_sph_astro.h"
#include "update.h"
#include "utils.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

FixSPHAstroH::FixSPHAstroH(LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg)
{
  vector_flag = 1;
  size_vector = 4;
  global_freq = 1;
  extvector = 0;

  if (narg < 4) utils::missing_cmd_args(FLERR, "fix sph/astro/h", error);
  if (strcmp(arg[3], "dhdt") == 0)
    mode_ = Mode::DHDT;
  else if (strcmp(arg[3], "iterate") == 0)
    mode_ = Mode::ITERATE;
  else
    error->all(FLERR, "fix sph/astro/h: mode '{}' is not one of: dhdt, iterate", arg[3]);

  int iarg = 4;
  while (iarg < narg) {
    const std::string key = arg[iarg];
    if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix sph/astro/h " + key, error);
    const char *val = arg[iarg + 1];
    if (key == "margin") {
      margin_ = utils::numeric(FLERR, val, false, lmp);
      if (!(margin_ >= 1.0)) error->all(FLERR, "fix sph/astro/h: margin = {} must be >= 1", val);
    } else if (mode_ == Mode::ITERATE && key == "hfact") {
      hfact_ = utils::numeric(FLERR, val, false, lmp);
      if (!(hfact_ > 0.0)) error->all(FLERR, "fix sph/astro/h: hfact = {} must be > 0", val);
    } else if (mode_ == Mode::ITERATE && key == "tol") {
      tolerance_ = utils::numeric(FLERR, val, false, lmp);
      if (!(tolerance_ > 0.0) || tolerance_ >= 0.1)
        error->all(FLERR, "fix sph/astro/h: tol = {} must be in (0, 0.1)", val);
    } else if (mode_ == Mode::ITERATE && key == "maxiter") {
      max_iterations_ = utils::inumeric(FLERR, val, false, lmp);
      if (max_iterations_ < 1) error->all(FLERR, "fix sph/astro/h: maxiter = {} must be >= 1", val);
    } else
      error->all(FLERR, "fix sph/astro/h {}: unknown keyword '{}'; allowed: {}", arg[3], key,
                 mode_ == Mode::ITERATE ? "hfact, tol, maxiter, margin" : "margin");
    iarg += 2;
  }
}

int FixSPHAstroH::setmask()
{
  return 0;    // fix sph/astro calls advance_h() in its drift
}

void FixSPHAstroH::init()
{
  pair_ = dynamic_cast<PairSPHAstro *>(force->pair_match("^sph/astro$", 0, 0));
  if (!pair_) error->all(FLERR, "fix sph/astro/h requires pair_style sph/astro");
  if (!SPHAstro::find_state(lmp, state_) || modify->get_fix_by_style("^sph/astro$").empty())
    error->all(FLERR, "fix sph/astro/h requires fix sph/astro (integrator and per-particle state)");
  if (modify->get_fix_by_style("^sph/astro/h$").size() > 1)
    error->all(FLERR, "fix sph/astro/h: only one instance is allowed");
  if (group->count(igroup) != atom->natoms) {
    if (mode_ == Mode::ITERATE)
      error->all(FLERR,
                 "fix sph/astro/h iterate: group {} must hold all particles (the density "
                 "iteration sets h for every SPH particle)",
                 group->names[igroup]);
    else if (comm->me == 0)
      error->warning(FLERR, "fix sph/astro/h dhdt: particles outside group {} keep their h",
                     group->names[igroup]);
  }
  failures_local_ = 0;
}

void FixSPHAstroH::advance_h(double dt)
{
  int ncol;
  const auto *divv = static_cast<double *>(pair_->extract_peratom("divv", ncol));
  if (!divv || pair_->computed_nlocal() != atom->nlocal) return;
  double *h = atom->dvector[state_.h];
  const int *mask = atom->mask;
  const int *type = atom->type;
  const double dt_over_d = dt / domain->dimension;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    h[i] *= std::exp(dt_over_d * divv[i]);
    h[i] = MIN(h[i], pair_->h_cap(type[i]));
  }
}

void FixSPHAstroH::record(double iterations_sum, int iterations_max, int nparticles, int failures,
                          int capped)
{
  iter_sum_ = iterations_sum;
  iter_max_ = iterations_max;
  nparticles_ = nparticles;
  capped_ = capped;
  failures_local_ += failures;
}

double FixSPHAstroH::compute_vector(int n)
{
  if (n == 0) {
    double local[2] = {iter_sum_, static_cast<double>(nparticles_)}, all[2];
    MPI_Allreduce(local, all, 2, MPI_DOUBLE, MPI_SUM, world);
    return all[1] > 0.0 ? all[0] / all[1] : 0.0;
  }
  if (n == 1) {
    int all;
    MPI_Allreduce(&iter_max_, &all, 1, MPI_INT, MPI_MAX, world);
    return all;
  }
  if (n == 2) {
    bigint all = 0;
    MPI_Allreduce(&failures_local_, &all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
    return static_cast<double>(all);
  }
  int all;
  MPI_Allreduce(&capped_, &all, 1, MPI_INT, MPI_SUM, world);
  return all;
}
