/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: the per-particle state shared by the package's styles
------------------------------------------------------------------------- */

// LAMMPS plugins cannot add atom styles, so the SPH state lives in custom per-atom
// properties owned by one "fix property/atom" with the fixed ID SPH_ASTRO_STATE. That fix
// gives migration, ghost (border) communication, restart, read_data/write_data sections,
// the set command (set ... d_u 2.5), dump custom (d_rho) and Python access by name.
//
//   d_rho     density                               (computed by pair sph/astro)
//   d_h       smoothing length h (kernel support = kernel radius * h)
//   d_u       specific internal energy
//   d_dudt    du/dt                                 (computed by pair sph/astro)
//   d_uest    u predicted to the end of the step    (set by fix sph/astro)
//   d2_vest 3 velocity predicted to the end of the step (set by fix sph/astro)
//
// Mass is the per-type mass, or the per-atom mass where the atom style has one.

#ifndef LMP_SPH_ASTRO_STATE_H
#define LMP_SPH_ASTRO_STATE_H

#include <cstdint>

namespace LAMMPS_NS {
class LAMMPS;
class Fix;
}    // namespace LAMMPS_NS

namespace SPHAstro {

constexpr const char *STATE_FIX_ID = "SPH_ASTRO_STATE";

// indices into atom->dvector / atom->darray
struct StateIndex {
  int rho = -1, h = -1, u = -1, dudt = -1, uest = -1, vest = -1;
};

// the "fix property/atom" arguments that define the state
const char *state_fix_arguments();

// create the state fix if it does not exist yet, or check that an existing one (for
// instance defined by the sph/astro/state command before read_data) is complete;
// caller names the command for error messages
LAMMPS_NS::Fix *ensure_state(LAMMPS_NS::LAMMPS *lmp, const char *caller);

// look up the state columns; returns false if the state fix was never created
bool find_state(LAMMPS_NS::LAMMPS *lmp, StateIndex &idx);

// Entropy formulation (fix sph/astro thermal entropy): the entropic function A with
// P = A rho^gamma lives in its own fix property/atom SPH_ASTRO_ENTROPY:
//   d_entropy       A
//   d_entropy_est   A predicted to the end of the step
//   d_dentropy      dA/dt                   (computed by pair sph/astro)
constexpr const char *ENTROPY_FIX_ID = "SPH_ASTRO_ENTROPY";
struct EntropyIndex {
  int A = -1, Aest = -1, dAdt = -1;
};
void ensure_entropy_state(LAMMPS_NS::LAMMPS *lmp, const char *caller);
bool find_entropy_state(LAMMPS_NS::LAMMPS *lmp, EntropyIndex &idx);

// Density by the continuity equation (pair_style sph/astro density continuity): d_rho is
// integrated in time by fix sph/astro like u; the force evaluation uses the prediction. Both
// live in their own fix property/atom SPH_ASTRO_CONTINUITY, created only for such scenes:
//   d_rhoest   rho predicted to the end of the step     (set by fix sph/astro)
//   d_drhodt   drho/dt = sum_j m_j v_ij . grad_i W_ij   (computed by pair sph/astro)
constexpr const char *CONTINUITY_FIX_ID = "SPH_ASTRO_CONTINUITY";
struct ContinuityIndex {
  int rhoest = -1, drhodt = -1;
};
void ensure_continuity_state(LAMMPS_NS::LAMMPS *lmp, const char *caller);
bool find_continuity_state(LAMMPS_NS::LAMMPS *lmp, ContinuityIndex &idx);

// Individual timesteps (fix sph/astro steps individual): each particle's place on the time
// line and what its neighbours need of its last force evaluation until its next one, in their
// own fix sph/astro/owned SPH_ASTRO_STEPS (owned atoms only: fix_sph_astro_owned.h), created
// only for such scenes:
//   d_step_begin, d_step_end   the particle's current step, in ticks (sph_astro_time_bins.h)
//   d_step_bin                 its bin: dt = dt_max / 2^bin
//   d_step_woken               the time the limiter first woke it in this step (ticks; -1:
//                              not woken)
//   d_step_end_then            its step's end before that (kicks pair: the pairs it opened
//                              before were given their opening kick for that end)
//   d2_step_accel 3            acceleration of its last force evaluation (all forces)
//   d2_step_accel_other 3      the part of it that is not pair sph/astro's pressure and
//                              viscosity (gravity, other styles, fixes): kicked per particle
//   d2_step_kick 3             the velocity change of the pair kicks that opened at the last
//                              evaluation, given at the start of the next LAMMPS step
//   d2_step_pair_lead 3        kicks pair: sum_j F_ij (t_mid,i - t_mid,ij) / m_i, how far the
//                              pair kicks given lead those of the particle's own step (the
//                              prediction's term for pairs whose interval is not that step)
//   d_step_dudt                du/dt of its last force evaluation
//   d_step_divv                div v (drifts rho and h between its evaluations)
//   d_step_omega               grad-h factor Omega           (set by pair sph/astro)
//   d_step_balsara             Balsara factor                (set by pair sph/astro)
//   d_step_nneigh              neighbours inside the kernel support (set by pair sph/astro)
//   d_step_dphidh              h_i^2 sum_j m_j dphi(r_ij, h_i)/dh_i (adaptive softening of pair
//                              sph/astro/gravity; set by pair sph/astro)
//   d_step_kick_u, d_step_lead_u, d_step_dudt_other
//                              the same as d2_step_kick, d2_step_pair_lead, d2_step_accel_other
//                              for u: kicks pair integrates pair sph/astro's du/dt terms pair
//                              by pair too
//   d2_step_pending 20         kicks pair, a sleeping particle: its pairs with particles on
//                              shorter steps, by the time their interval closes (up to 4 such
//                              times, PENDING_SLOTS): per time the close (ticks, 0: none), the
//                              interval's middle (ticks) and sum_j F_ij of their opening
//   d_step_pending_next        the earliest of these closes (0: none)
//   d2_step_recent 6           kicks pair, a sleeping particle: the prediction's term for the
//                              forces of its pairs evaluated since its own evaluation,
//                              sum (F_ij,new - F_ij,old) (t - t_mid,ij) / m = s t - c: s, c (3 each)
constexpr int PENDING_SLOTS = 4;
constexpr int PENDING_VALUES = 5;    // close, middle, F (3)
constexpr int RECENT_VALUES = 6;
constexpr const char *STEPS_FIX_ID = "SPH_ASTRO_STEPS";
// fix sph/astro longrange sync: each particle's long-range (kspace) acceleration of the last
// synchronisation point, d2_step_accel_long (owned atoms)
constexpr const char *LONG_RANGE_FIX_ID = "SPH_ASTRO_LONG_RANGE";
struct StepIndex {
  int begin = -1, end = -1, bin = -1, woken = -1, end_then = -1, accel = -1, accel_other = -1,
      kick = -1, pair_lead = -1, dudt = -1, divv = -1, omega = -1, balsara = -1, nneigh = -1,
      kick_u = -1, lead_u = -1, dudt_other = -1, pending = -1, recent = -1, pending_next = -1,
      dphidh = -1;
};
void ensure_step_state(LAMMPS_NS::LAMMPS *lmp, const char *caller);

// empty the package's per-particle state of atom i (all of the above that exist): a particle
// created during a simulation (fix property/atom clears only memory it grows, not a slot a
// ghost or a deleted atom left)
void clear_state(LAMMPS_NS::LAMMPS *lmp, int i);
bool find_step_state(LAMMPS_NS::LAMMPS *lmp, StepIndex &idx);

// order-independent hash of every owned atom's ID, v and u (and rho with with_rho: integrated
// with density continuity), over all ranks: whether the state changed between two runs
std::uint64_t state_hash(LAMMPS_NS::LAMMPS *lmp, const StateIndex &state, bool with_rho);
// the part of one atom (ID, v, u) in state_hash() without rho: state_hash() is their XOR over
// the atoms
std::uint64_t atom_state_hash(std::int64_t tag, const double *v, double u);
// d2_step_accel_long (LONG_RANGE_FIX_ID): made if missing; its index (-1: none)
void ensure_long_range_state(LAMMPS_NS::LAMMPS *lmp, const char *caller);
int find_long_range_state(LAMMPS_NS::LAMMPS *lmp);

}    // namespace SPHAstro

#endif
