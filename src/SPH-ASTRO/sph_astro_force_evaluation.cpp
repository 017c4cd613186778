/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

#include "sph_astro_force_evaluation.h"

#include "sph_astro_neighbour_lists.h"

#include <cmath>

namespace SPHAstro {

EvaluationResult ForceEvaluation::run(NeighbourLists &lists, const GradhSettings &gradh,
                                      GradhStatistics &hstats, double h_cap,
                                      bool initialise_density, bool initialise_entropy)
{
  EvaluationResult result;
  h_cap_ = h_cap;
  vest_sent_ = false;
  Fields &f = *ctx_.f;
  if (scheme_.hmode == Scheme::HMode::DHDT)
    exchange_.forward({{a_.h, nullptr, 1, false}});    // the ghosts' h of this step
  GradhSettings iteration = gradh;
  if (individual()) {    // the h-rho iteration of the active atoms only
    lists.prepare(a_.steps.active);
    active_owned_.clear();
    for (int ii = 0; ii < gradh.full.inum; ii++)
      if (a_.steps.active[gradh.full.ilist[ii]]) active_owned_.push_back(gradh.full.ilist[ii]);
    iteration.full.inum = static_cast<int>(active_owned_.size());
    iteration.full.ilist = active_owned_.data();
  }
  if (!scheme_.gradh()) select_pairs(lists);
  density(iteration, hstats, initialise_density, result);
  if (scheme_.gradh()) {    // h is that of the iteration now, on the ghosts too
    exchange_.forward({{a_.h, nullptr, 1, false}});
    select_pairs(lists);
  }
  if (individual() && scheme_.gradh()) restore(f.omega, a_.steps.omega);
  if (individual() && iteration.dphidh_sum) keep_softening_sums(iteration.dphidh_sum);
  equation_of_state(initialise_entropy);
  gradients();
  if (individual() && o_.balsara) restore(f.balsara, a_.steps.balsara);
  // pressure-energy with grad-h terms: div v and curl v above are those of the mass density
  // and Omega; now rho_i = P_i / ((gamma-1) u_i) and the EOS again (P = (gamma-1) rho u)
  if (scheme_.gradh() && o_.pressure_energy) {
    pressure_energy_density(ctx_, ctx_.f->energy_sum);
    equation_of_state(false);
  }
  forward_state();
  force();
  if (o_.physical_conduction()) conduction();
  if (individual()) {
    if (scheme_.gradh()) keep(f.omega, a_.steps.omega);
    if (o_.balsara) keep(f.balsara, a_.steps.balsara);
    keep(f.divv, a_.steps.divv);
    restore(f.divv, a_.steps.divv);
    if (result.counted) keep(f.nneigh, a_.steps.nneigh);
    restore(f.nneigh, a_.steps.nneigh);
  }
  return result;
}

NeighView ForceEvaluation::evaluated_pairs(NeighbourLists &lists)
{
  if (!individual()) return lists.half(a_.h);
  return lists.due(a_.h, a_.steps.active);
}

// With individual steps the force pass reads, and sums into, only the ghosts in the pairs it
// evaluates: the state goes to those ghosts and the sums come back from them only
void ForceEvaluation::select_pairs(NeighbourLists &lists)
{
  ctx_.half = evaluated_pairs(lists);
  ctx_.ghosts_in_pairs = nullptr;
  if (!individual()) return;
  const int nlocal = ctx_.p.nlocal;
  const std::size_t nall = ctx_.p.nall;
  if (in_pairs_.size() < nall) in_pairs_.resize(nall);
  std::fill(in_pairs_.begin(), in_pairs_.begin() + nall, 0);
  const NeighView &pairs = ctx_.half;
  for (int ii = 0; ii < pairs.inum; ii++) {
    const int i = pairs.ilist[ii];
    const int *row = pairs.firstneigh[i];
    const int n = pairs.numneigh[i];
    for (int e = 0; e < n; e++)
      if (row[e] >= nlocal) in_pairs_[row[e]] = 1;
  }
  exchange_.gather_marks(in_pairs_.data());
  ctx_.ghosts_in_pairs = in_pairs_.data();
}

void ForceEvaluation::restore(double *field, const double *kept)
{
  const int nlocal = ctx_.p.nlocal;
  const char *active = a_.steps.active;
  for (int i = 0; i < nlocal; i++)
    if (!active[i]) field[i] = kept[i];
}

// S_i = h_i^-2 sum_j m_j g(q_ij), g(q) = -[fpot(q) + q fforce(q)] (sph_astro_gravity_kernel.h):
// kept as h_i^2 S_i, which a homologous drift (q_ij fixed, as rho and h drift) leaves as it is,
// so that an inactive atom's S_i follows its drifted h
void ForceEvaluation::keep_softening_sums(double *sums)
{
  const int nlocal = ctx_.p.nlocal;
  const char *active = a_.steps.active;
  const double *h = a_.h;
  double *kept = a_.steps.dphidh;
  for (int i = 0; i < nlocal; i++) {
    if (!ctx_.p.gas(i)) continue;    // (a point mass has no h)
    if (active[i])
      kept[i] = sums[i] * h[i] * h[i];
    else
      sums[i] = kept[i] / (h[i] * h[i]);
  }
}

void ForceEvaluation::keep(const double *field, double *kept)
{
  const int nlocal = ctx_.p.nlocal;
  const char *active = a_.steps.active;
  for (int i = 0; i < nlocal; i++)
    if (active[i]) kept[i] = field[i];
}

void ForceEvaluation::density(const GradhSettings &gradh, GradhStatistics &hstats, bool initialise,
                              EvaluationResult &result)
{
  Fields &f = *ctx_.f;
  if (o_.pressure_energy) exchange_.forward({{ctx_.uest, nullptr, 1, false}});    // their u
  if (scheme_.gradh()) {
    if (gradh.sums != VelocitySums::NONE) forward_vest();
    density_gradh(ctx_, gradh, hstats);
    result.counted = true;
    result.h_failures = hstats.failures;
    return;
  }
  if (o_.density_continuity && !initialise) return;    // counted only if asked for
  // (individual steps: inactive atoms keep their density, drifted by fix sph/astro)
  if (individual()) rho_kept_.assign(ctx_.rho_sum, ctx_.rho_sum + ctx_.p.nlocal);
  density_summation(ctx_, o_.symmetrise_kernel, o_.pressure_energy);
  result.counted = true;
  if (ctx_.newton)
    exchange_.reverse({{ctx_.rho_sum, nullptr, 1, false}, {f.nneigh, nullptr, 1, false}});
  if (individual()) restore(ctx_.rho_sum, rho_kept_.data());
  if (o_.pressure_energy) pressure_energy_density(ctx_, ctx_.rho_sum);
  if (o_.density_continuity)    // the integrated density starts from one summation
    for (int i = 0; i < ctx_.p.nlocal; i++) a_.rhoest[i] = ctx_.rho_sum[i];
}

void ForceEvaluation::equation_of_state(bool initialise_entropy)
{
  SPHAstro::equation_of_state(ctx_, o_.eos, h_cap_, o_.density_continuity,
                              scheme_.entropy ? &a_.entropy : nullptr, initialise_entropy);
}

void ForceEvaluation::gradients()
{
  Fields &f = *ctx_.f;
  const bool gradh = scheme_.gradh();
  if (o_.reconstruction()) {    // grad v (and from it div v and curl v)
    if (!gradh) {
      forward_vest();
      velocity_sums(ctx_, o_.symmetrise_kernel, VelocitySums::GRADIENT);
      if (ctx_.newton) exchange_.reverse({{nullptr, f.vgsum, VGRAD_SUMS, false}});
    }
    finish_velocity_gradient(ctx_, o_.recon_trigger, scheme_.curl);
    if (scheme_.curl) finish_curl(ctx_, gradh, o_.balsara);
  } else if (scheme_.curl) {
    if (!gradh) {    // (with grad-h terms the sums come from the h iteration)
      forward_vest();
      velocity_sums(ctx_, o_.symmetrise_kernel, VelocitySums::CURL);
      if (ctx_.newton) exchange_.reverse({{nullptr, f.dcurl, 4, false}});
    }
    finish_curl(ctx_, gradh, o_.balsara);
  }
}

// the ghosts' predicted velocities (once per evaluation: nothing changes them in between)
void ForceEvaluation::forward_vest()
{
  exchange_.forward({{nullptr, ctx_.vest, 3, false, true}});
  vest_sent_ = true;
}

// the ghosts' copy of what the force pass reads; u_est goes with it where a term reads the
// partner's u (with formulation pressure-energy it went before the density pass already), v_est
// unless a velocity sum took it already
void ForceEvaluation::forward_state()
{
  Fields &f = *ctx_.f;
  const bool gradh = scheme_.gradh();
  const bool ghost_u =
      o_.eos.uses_energy() && (o_.conductivity > 0.0 || o_.conduction > 0.0) && !o_.pressure_energy;
  const std::initializer_list<CommField> state = {
      {ctx_.rho, nullptr, 1, false},
      {f.pressure, nullptr, 1, false},
      {f.soundspeed, nullptr, 1, false},
      {nullptr, vest_sent_ ? nullptr : ctx_.vest, 3, false, true},
      {gradh ? f.omega : nullptr, nullptr, 1, false},
      {gradh && o_.pressure_energy ? f.pe_gradh : nullptr, nullptr, 1, false},
      {ctx_.alpha, nullptr, 1, false},
      {ghost_u ? ctx_.uest : nullptr, nullptr, 1, false},
      {o_.balsara ? f.balsara : nullptr, nullptr, 1, false},
      {nullptr, o_.reconstruction() ? f.vgrad : nullptr, VGRAD_DATA, false}};
  if (ctx_.ghosts_in_pairs)
    exchange_.forward_chosen(state, ctx_.ghosts_in_pairs);
  else
    exchange_.forward(state);
}

void ForceEvaluation::force()
{
  Fields &f = *ctx_.f;
  const int nlocal = ctx_.p.nlocal;
  const int nall = ctx_.p.nall;
  const bool gradh = scheme_.gradh();
  if (o_.pressure_geometric)    // g = sqrt(P)/rho of owned and ghost atoms
    for (int i = 0; i < nall; i++)
      f.pressure_factor[i] = pressure_geometric_factor(f.pressure[i], ctx_.rho[i]);
  else if (o_.pressure_energy)    // (gamma-1) u = P/rho of owned and ghost atoms
    for (int i = 0; i < nall; i++) f.pressure_factor[i] = f.pressure[i] / ctx_.rho[i];

  const ForceSettings s = force_settings(o_, gradh, ctx_.alpha != nullptr);
  force_pass(ctx_, s, gradh || o_.symmetrise_kernel, o_.symmetrise_kernel);
  if (ctx_.newton) {
    const std::initializer_list<CommField> sums = {
        {s.energy ? ctx_.dudt : nullptr, nullptr, 1, false},
        {f.vdotgradw, nullptr, 1, false},
        {s.track_signal ? f.vsigmax : nullptr, nullptr, 1, true},
        {s.alpha_u > 0.0 ? f.condrate : nullptr, nullptr, 1, false}};
    if (ctx_.ghosts_in_pairs)
      exchange_.reverse_chosen(sums, ctx_.ghosts_in_pairs);
    else
      exchange_.reverse(sums);
  }
  finish_force(ctx_, s);
  if (s.energy)
    thermal_rates(ctx_, o_.eos, gradh && !o_.pressure_energy, o_.pressure_geometric,
                  scheme_.entropy ? a_.entropy.dAdt : nullptr);
  // drho_i/dt = sum_j m_j v_ij . grad_i W_ij (Monaghan 1992, eq. 2.12), integrated by fix
  // sph/astro
  if (o_.density_continuity)
    for (int i = 0; i < nlocal; i++) a_.drhodt[i] = ctx_.p.gas(i) ? f.vdotgradw[i] : 0.0;
}

// physical heat conduction: a pass of its own, only when kappa > 0
void ForceEvaluation::conduction()
{
  Fields &f = *ctx_.f;
  conduction_pass(ctx_, o_.conduction, scheme_.gradh() || o_.symmetrise_kernel);
  if (ctx_.newton) exchange_.reverse({{f.conduct, nullptr, 1, false}});
  const int nlocal = ctx_.p.nlocal;
  for (int i = 0; i < nlocal; i++) ctx_.dudt[i] += f.conduct[i];
  if (scheme_.entropy) {
    const double g1 = o_.eos.gamma - 1.0;
    for (int i = 0; i < nlocal; i++)
      if (ctx_.p.gas(i)) a_.entropy.dAdt[i] += g1 * std::pow(ctx_.rho[i], -g1) * f.conduct[i];
  }
}

}    // namespace SPHAstro
