/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: the per-particle state shared by the package's styles
------------------------------------------------------------------------- */

#include "sph_astro_state.h"

#include "atom.h"
#include "error.h"
#include "fix.h"
#include "lammps.h"
#include "modify.h"

#include <cstdint>
#include <cstring>
#include <mpi.h>
#include <string>

using namespace LAMMPS_NS;

namespace SPHAstro {

const char *state_fix_arguments()
{
  return "property/atom d_rho d_h d_u d_dudt d_uest d2_vest 3 ghost yes";
}

bool find_state(LAMMPS *lmp, StateIndex &idx)
{
  Atom *atom = lmp->atom;
  int flag, cols;
  idx.rho = atom->find_custom("rho", flag, cols);
  if (idx.rho < 0 || flag != 1 || cols != 0) return false;
  idx.h = atom->find_custom("h", flag, cols);
  if (idx.h < 0 || flag != 1 || cols != 0) return false;
  idx.u = atom->find_custom("u", flag, cols);
  if (idx.u < 0 || flag != 1 || cols != 0) return false;
  idx.dudt = atom->find_custom("dudt", flag, cols);
  if (idx.dudt < 0 || flag != 1 || cols != 0) return false;
  idx.uest = atom->find_custom("uest", flag, cols);
  if (idx.uest < 0 || flag != 1 || cols != 0) return false;
  idx.vest = atom->find_custom("vest", flag, cols);
  if (idx.vest < 0 || flag != 1 || cols != 3) return false;
  return true;
}

Fix *ensure_state(LAMMPS *lmp, const char *caller)
{
  Modify *modify = lmp->modify;
  Fix *fix = modify->get_fix_by_id(STATE_FIX_ID);
  if (!fix) {
    int flag, cols;
    for (const char *name : {"rho", "h", "u", "dudt", "uest", "vest"})
      if (lmp->atom->find_custom(name, flag, cols) >= 0)
        lmp->error->all(FLERR,
                        "{}: a custom per-atom property d_{} already exists outside fix {}; "
                        "SPH-ASTRO owns the names d_rho d_h d_u d_dudt d_uest d2_vest",
                        caller, name, STATE_FIX_ID);
    fix = modify->add_fix(std::string(STATE_FIX_ID) + " all " + state_fix_arguments());
  } else {
    StateIndex idx;
    if (strcmp(fix->style, "property/atom") != 0 || !find_state(lmp, idx))
      lmp->error->all(FLERR,
                      "{}: fix {} exists but is not 'fix {} all {}'; remove it or define it "
                      "with exactly those arguments",
                      caller, STATE_FIX_ID, STATE_FIX_ID, state_fix_arguments());
  }
  return fix;
}

bool find_entropy_state(LAMMPS *lmp, EntropyIndex &idx)
{
  int flag, cols;
  idx.A = lmp->atom->find_custom("entropy", flag, cols);
  if (idx.A < 0 || flag != 1 || cols != 0) return false;
  idx.Aest = lmp->atom->find_custom("entropy_est", flag, cols);
  if (idx.Aest < 0 || flag != 1 || cols != 0) return false;
  idx.dAdt = lmp->atom->find_custom("dentropy", flag, cols);
  if (idx.dAdt < 0 || flag != 1 || cols != 0) return false;
  return true;
}

void ensure_entropy_state(LAMMPS *lmp, const char *caller)
{
  EntropyIndex idx;
  if (lmp->modify->get_fix_by_id(ENTROPY_FIX_ID)) {
    if (!find_entropy_state(lmp, idx))
      lmp->error->all(FLERR,
                      "{}: fix {} exists but does not hold d_entropy d_entropy_est d_dentropy",
                      caller, ENTROPY_FIX_ID);
    return;
  }
  lmp->modify->add_fix(std::string(ENTROPY_FIX_ID) +
                       " all property/atom d_entropy d_entropy_est d_dentropy");
}

bool find_continuity_state(LAMMPS *lmp, ContinuityIndex &idx)
{
  int flag, cols;
  idx.rhoest = lmp->atom->find_custom("rhoest", flag, cols);
  if (idx.rhoest < 0 || flag != 1 || cols != 0) return false;
  idx.drhodt = lmp->atom->find_custom("drhodt", flag, cols);
  if (idx.drhodt < 0 || flag != 1 || cols != 0) return false;
  return true;
}

void ensure_continuity_state(LAMMPS *lmp, const char *caller)
{
  ContinuityIndex idx;
  if (lmp->modify->get_fix_by_id(CONTINUITY_FIX_ID)) {
    if (!find_continuity_state(lmp, idx))
      lmp->error->all(FLERR, "{}: fix {} exists but does not hold d_rhoest d_drhodt", caller,
                      CONTINUITY_FIX_ID);
    return;
  }
  int flag, cols;
  for (const char *name : {"rhoest", "drhodt"})
    if (lmp->atom->find_custom(name, flag, cols) >= 0)
      lmp->error->all(FLERR,
                      "{}: a custom per-atom property d_{} already exists outside fix {}; "
                      "SPH-ASTRO owns the names d_rhoest d_drhodt",
                      caller, name, CONTINUITY_FIX_ID);
  lmp->modify->add_fix(std::string(CONTINUITY_FIX_ID) +
                       " all property/atom d_rhoest d_drhodt ghost yes");
}

namespace {
  const char *const STEP_VECTORS[] = {
      "step_begin",  "step_end",    "step_bin",        "step_woken",        "step_end_then",
      "step_dudt",   "step_divv",   "step_omega",      "step_balsara",      "step_nneigh",
      "step_kick_u", "step_lead_u", "step_dudt_other", "step_pending_next", "step_dphidh"};
  constexpr int NSTEP_VECTORS = sizeof(STEP_VECTORS) / sizeof(STEP_VECTORS[0]);
}    // namespace

bool find_step_state(LAMMPS *lmp, StepIndex &idx)
{
  int flag, cols;
  int *fields[] = {&idx.begin,  &idx.end,    &idx.bin,        &idx.woken,        &idx.end_then,
                   &idx.dudt,   &idx.divv,   &idx.omega,      &idx.balsara,      &idx.nneigh,
                   &idx.kick_u, &idx.lead_u, &idx.dudt_other, &idx.pending_next, &idx.dphidh};
  static_assert(sizeof(fields) / sizeof(fields[0]) == NSTEP_VECTORS, "one index per vector");
  for (int k = 0; k < NSTEP_VECTORS; k++) {
    *fields[k] = lmp->atom->find_custom(STEP_VECTORS[k], flag, cols);
    if (*fields[k] < 0 || flag != 1 || cols != 0) return false;
  }
  idx.accel = lmp->atom->find_custom("step_accel", flag, cols);
  if (idx.accel < 0 || flag != 1 || cols != 3) return false;
  idx.accel_other = lmp->atom->find_custom("step_accel_other", flag, cols);
  if (idx.accel_other < 0 || flag != 1 || cols != 3) return false;
  idx.kick = lmp->atom->find_custom("step_kick", flag, cols);
  if (idx.kick < 0 || flag != 1 || cols != 3) return false;
  idx.pair_lead = lmp->atom->find_custom("step_pair_lead", flag, cols);
  if (idx.pair_lead < 0 || flag != 1 || cols != 3) return false;
  idx.pending = lmp->atom->find_custom("step_pending", flag, cols);
  if (idx.pending < 0 || flag != 1 || cols != PENDING_SLOTS * PENDING_VALUES) return false;
  idx.recent = lmp->atom->find_custom("step_recent", flag, cols);
  return idx.recent >= 0 && flag == 1 && cols == RECENT_VALUES;
}

void ensure_step_state(LAMMPS *lmp, const char *caller)
{
  StepIndex idx;
  if (lmp->modify->get_fix_by_id(STEPS_FIX_ID)) {
    if (!find_step_state(lmp, idx))
      lmp->error->all(FLERR, "{}: fix {} exists but does not hold the individual-step state",
                      caller, STEPS_FIX_ID);
    return;
  }
  int flag, cols;
  for (const char *name : STEP_VECTORS)
    if (lmp->atom->find_custom(name, flag, cols) >= 0)
      lmp->error->all(FLERR,
                      "{}: a custom per-atom property d_{} already exists outside fix {}; "
                      "SPH-ASTRO owns the names d_step_*",
                      caller, name, STEPS_FIX_ID);
  // (owned atoms only: no ghost reads the step state, and a ghost costs it no memory; not in
  // data files: without the time line, which a data file cannot hold, the state means nothing,
  // and its 53 values per atom make lines longer than read_data reads)
  lmp->modify->add_fix(std::string(STEPS_FIX_ID) +
                       " all sph/astro/owned d_step_begin d_step_end d_step_bin d_step_woken "
                       "d_step_end_then d2_step_accel 3 "
                       "d2_step_accel_other 3 d2_step_kick 3 d2_step_pair_lead 3 d_step_dudt "
                       "d_step_divv d_step_omega d_step_balsara d_step_nneigh d_step_kick_u "
                       "d_step_lead_u d_step_dudt_other d_step_pending_next d_step_dphidh "
                       "d2_step_pending " +
                       std::to_string(PENDING_SLOTS * PENDING_VALUES) + " d2_step_recent " +
                       std::to_string(RECENT_VALUES) + " writedata no");
}

namespace {
  // a mixed 64-bit value (the splitmix64 finaliser)
  std::uint64_t mix(std::uint64_t z)
  {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  std::uint64_t bits(double value)
  {
    std::uint64_t b;
    memcpy(&b, &value, sizeof(b));
    return b;
  }
}    // namespace

std::uint64_t atom_state_hash(std::int64_t tag, const double *v, double u)
{
  std::uint64_t h = mix(static_cast<std::uint64_t>(tag));
  h = mix(h ^ bits(v[0]));
  h = mix(h ^ bits(v[1]));
  h = mix(h ^ bits(v[2]));
  return mix(h ^ bits(u));
}

// XOR over atoms of a mixed 64-bit value
std::uint64_t state_hash(LAMMPS *lmp, const StateIndex &state, bool with_rho)
{
  Atom *atom = lmp->atom;
  const double *u = atom->dvector[state.u];
  const double *rho = with_rho ? atom->dvector[state.rho] : nullptr;
  double **v = atom->v;
  std::uint64_t local = 0;
  for (int i = 0; i < atom->nlocal; i++) {
    std::uint64_t h = atom_state_hash(atom->tag[i], v[i], u[i]);
    if (rho) h = mix(h ^ bits(rho[i]));
    local ^= h;
  }
  std::uint64_t all = 0;
  MPI_Allreduce(&local, &all, 1, MPI_UINT64_T, MPI_BXOR, lmp->world);
  return all;
}

void ensure_long_range_state(LAMMPS *lmp, const char *caller)
{
  if (lmp->modify->get_fix_by_id(LONG_RANGE_FIX_ID)) {
    if (find_long_range_state(lmp) < 0)
      lmp->error->all(FLERR, "{}: fix {} exists but does not hold d2_step_accel_long", caller,
                      LONG_RANGE_FIX_ID);
    return;
  }
  int flag, cols;
  if (lmp->atom->find_custom("step_accel_long", flag, cols) >= 0)
    lmp->error->all(FLERR,
                    "{}: a custom per-atom property d2_step_accel_long already exists outside "
                    "fix {}; SPH-ASTRO owns the names d_step_*",
                    caller, LONG_RANGE_FIX_ID);
  // (not in data files either: it belongs to the time line of the steps)
  lmp->modify->add_fix(std::string(LONG_RANGE_FIX_ID) +
                       " all sph/astro/owned d2_step_accel_long 3 writedata no");
}

int find_long_range_state(LAMMPS *lmp)
{
  int flag, cols;
  const int index = lmp->atom->find_custom("step_accel_long", flag, cols);
  return (index >= 0 && flag == 1 && cols == 3) ? index : -1;
}

void clear_state(LAMMPS *lmp, int i)
{
  Atom *atom = lmp->atom;
  int flag, cols;
  for (const char *name : {"rho",
                           "h",
                           "u",
                           "dudt",
                           "uest",
                           "entropy",
                           "entropy_est",
                           "dentropy",
                           "rhoest",
                           "drhodt",
                           "step_begin",
                           "step_end",
                           "step_bin",
                           "step_woken",
                           "step_end_then",
                           "step_dudt",
                           "step_divv",
                           "step_omega",
                           "step_balsara",
                           "step_nneigh",
                           "step_kick_u",
                           "step_lead_u",
                           "step_dudt_other",
                           "step_pending_next",
                           "step_dphidh"}) {
    const int index = atom->find_custom(name, flag, cols);
    if (index >= 0 && flag == 1 && cols == 0) atom->dvector[index][i] = 0.0;
  }
  for (const char *name : {"vest", "step_accel", "step_accel_other", "step_kick", "step_pair_lead",
                           "step_pending", "step_recent", "step_accel_long"}) {
    const int index = atom->find_custom(name, flag, cols);
    if (index >= 0 && flag == 1 && cols > 0)
      for (int c = 0; c < cols; c++) atom->darray[index][i][c] = 0.0;
  }
}

}    // namespace SPHAstro
