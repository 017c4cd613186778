/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Individual (hierarchical block) timesteps of fix sph/astro (keyword steps individual):
// kick-drift-kick with each particle on its own step dt_max / 2^bin (Springel 2005, MNRAS
// 364, 1105, sec. 4; the time line: sph_astro_time_bins.h). A LAMMPS step goes from one end
// of a particle step to the next (update->dt varies); the particles whose step ends with it
// are active, and pair sph/astro evaluates the pairs with an active particle only.
//   a step begins     v += a_other dt_i/2, u += du/dt_other dt_i/2   (of its last evaluation)
//   every LAMMPS step every particle's v and u are predicted to the end of the LAMMPS step,
//                     v_est(t) = v + a (t - t_mid,i), u_est = u + du/dt (t - t_mid,i);
//                     x += v_est(t_c) dt with t_c the LAMMPS step's middle (inside its step
//                     the particle follows x_b + v_b tau + a tau^2 / 2 and ends it at
//                     x_b + (v_b + a dt_i / 2) dt_i, as kick-drift-kick does); an inactive
//                     particle's rho and h follow its last div v: rho *= exp(-div v dt),
//                     h *= exp(div v dt / d)
//   a step ends       v += a_other,new dt_i/2, u += du/dt_other,new dt_i/2; the new bin from the
//                     timestep criteria (shorter at once, longer one bin at a time where its
//                     grid passes), and the timestep limiter (Saitoh & Makino 2009, ApJ 697,
//                     L99): no particle more than 2^levels times its neighbours' step; a
//                     sleeping neighbour is woken (Durier & Dalla Vecchia 2012, MNRAS 419,
//                     465): its step ends at the next point of the allowed bin's grid, and its
//                     first half kick is corrected to the shortened step (its parabola is not)
// kicks particle: a_other is the whole acceleration of the particle's evaluation.
// kicks pair (default): pair sph/astro's forces are integrated pair by pair, on the shorter
// step of the pair's two particles (Springel 2010, MNRAS 401, 791, sec. 7, for fluxes between
// cells): the pair's interval runs from one time either particle is active to the next, and at
// each evaluation both particles get the same impulse F_ij (w_closing + w_opening) (the opening
// part given at the start of the next LAMMPS step), so the total momentum is conserved to
// round-off; a_other is the rest (gravity, other styles, fixes). The pair's du/dt terms (P dV
// and dissipation, m_i du_i + m_j du_j = -F_ij . v_ij) are integrated on the same intervals,
// each particle's own, so that a sleeping particle's u follows the work its pairs do on it;
// du/dt_other (the rest: conduction, fixes) per particle. A pair on a shorter interval than
// particle i's step has kicked i up to its own interval's middle t_mid,ij, not t_mid,i: the
// prediction adds its lead, v_est = v + a (t - t_mid,i) + sum_j F_ij (t_mid,i - t_mid,ij) / m_i
// (d2_step_pair_lead; for u d_step_lead_u). A sleeping particle's pairs re-evaluated since its
// own evaluation (with active partners) enter its prediction of v with their new forces:
// + sum (F_ij,new - F_ij,old) (t - t_mid,ij) / m (d2_step_recent; the old forces wait per
// close time in d2_step_pending). A pair whose interval a wake shortened closes with the rest of
// it, w_closing = (t - t_open) - w_opening (for u at least 0: taking back heat at the new rate
// could make u negative).
// Other forces on inactive particles are computed by LAMMPS every step and not used: an
// inactive particle keeps a_other of its last evaluation.
// longrange sync (split_long_range()): the long-range force of the kspace gravity solver is
// integrated on the intervals between synchronisation points, where every particle ends its
// step, and computed only there (Springel 2005, MNRAS 364, 1105, sec. 4: the long-range force
// on a longer step, the short-range one sub-cycled inside it; Duncan, Levison & Lee 1998, AJ
// 116, 2067: the splitting keeps the integrator symplectic). At a synchronisation point every
// particle gets v += a_long (Delta_old + Delta_new) / 2, Delta the intervals' lengths; a_long is
// not in a, a_other or the drift's parabola. No particle steps longer than
// dt_long = min(C_d r_s / max|v|, C_f min sqrt(r_s / |a_long|)), r_s the solver's split
// (its short-range cutoff), so that the interval is at most dt_long.

#ifndef LMP_SPH_ASTRO_INDIVIDUAL_STEPS_H
#define LMP_SPH_ASTRO_INDIVIDUAL_STEPS_H

#include "atom.h"
#include "pointers.h"
#include "sph_astro_active_set.h"
#include "sph_astro_state.h"

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace LAMMPS_NS {
class Fix;
class PairSPHAstro;
}    // namespace LAMMPS_NS

namespace SPHAstro {

struct PairOptions;

class IndividualSteps : protected LAMMPS_NS::Pointers, public LongRangeSchedule {
 public:
  // per atom: the times pair_impulses() reads (begin, end, woken, end_then); sums_: impulses
  // and u kick (SUM_KICKS), with the forces the next SUM_KICKS: sum_j F_ij and du/dt; extra_
  // (an atom that sleeps through a pair's close): a closing's sum_j F_ij t_mid,ij (3, time),
  // an opening's sum_j F_ij (3) and the close (ticks) per pending slot
  static constexpr int NTIMES = 4;
  static constexpr int SUM_KICKS = 4;
  static constexpr int SUM_STRIDE = 2 * SUM_KICKS;
  static constexpr int EXTRA_STRIDE = 4 * PENDING_SLOTS;

  // owner: the fix whose communication and group this uses; levels: the limiter (0: off);
  // pair_kicks: pair forces integrated pair by pair (else each particle's on its own step)
  IndividualSteps(LAMMPS_NS::LAMMPS *lmp, LAMMPS_NS::Fix *owner, int levels, bool pair_kicks);

  // fix sph/astro's keywords given (with their values) that do nothing (limiter and kicks with
  // global steps, longdisplacement without longrange sync), and a limiter off (levels 0) with
  // individual steps: warnings naming them (rank 0)
  static void warn_keywords(LAMMPS_NS::LAMMPS *lmp, const std::map<std::string, std::string> &given,
                            bool individual, bool long_range_sync, int levels);
  // what the hierarchy does not carry between a particle's evaluations is an error; the fix's
  // group (igroup) must hold all SPH gas particles (point masses may be outside)
  void check_options(const LAMMPS_NS::PairSPHAstro *pair, bool entropy, int igroup);
  // a run: continue the hierarchy where the last run (or the restart file) left it, or start
  // it anew (first run, or v, u or the particles changed in between)
  void init(const StateIndex &state, bool state_unchanged);
  bool continuing() const { return continuing_; }
  // does every particle end its step at the time of the step being taken (from pre_force to
  // end_of_step; after end_of_step, the next step's)
  bool synchronised() const;
  // before the setup's force evaluation: all particles active (a new hierarchy) or none
  void setup_pre_force(LAMMPS_NS::PairSPHAstro *pair);
  // a new hierarchy (first step of the run): every particle's acceleration from the setup's
  // forces, and its bin from wanted (its timestep criteria); the top step dt_max is dtmax (if
  // > 0), else the largest wanted step; with tend > 0 it is (tend - now) / 2^k, so that tend
  // lies on the grid; open_pairs (at the first step, when the setup forces of all fixes are
  // in): the pairs open their first interval, and the other forces are split off
  void start(const std::vector<double> &wanted, double dtmax, double time_left,
             LAMMPS_NS::PairSPHAstro *pair, bool open_pairs);
  bool started() const { return started_; }

  // LAMMPS' step: first half kicks of the steps that begin, drift, predictions; h_cap > 0:
  // variable h (fix sph/astro/h), h follows div v up to h_cap; 0: fixed h
  void kick_drift(double h_cap, bool evolve_u);
  // the active particles of this step (after reneighbouring), told to pair sph/astro
  void pre_force(LAMMPS_NS::PairSPHAstro *pair);
  bool active(int i) const { return active_[i] != 0; }
  // the flags of owned and ghost atoms (from setup_pre_force or pre_force to the step's end)
  const char *active_flags() const { return active_.data(); }
  // owned atom i was evaluated at this step (its step ends with it); dt: its step's length
  bool own_step(int i, double &dt) const
  {
    const double *begin = atom->dvector[idx_.begin], *end = atom->dvector[idx_.end];
    dt = (end[i] - begin[i]) * tick();
    return active_[i] != 0;
  }
  // the closing pair kicks of this evaluation (all particles) and the second half kicks of
  // the active particles; inactive ones get back their f and du/dt
  void final_kick(bool evolve_u, LAMMPS_NS::PairSPHAstro *pair);
  // the active particles' new bins (wanted: their criteria), the limiter, the next step
  void end_of_step(const std::vector<double> &wanted, LAMMPS_NS::PairSPHAstro *pair);
  // owned atom i is inside its step at the current time (after end_of_step): its v and u are
  // those of the middle of its step, d2_vest and d_uest those of now (atoms outside the group,
  // moved by other fixes at every step, never)
  bool mid_step(int i) const
  {
    return started_ && (atom->mask[i] & owner_groupbit()) &&
        atom->dvector[idx_.begin][i] != ti_now_;
  }
  // the LAMMPS timestep to the next end of a particle step
  double next_dt() const { return (ti_next_ - ti_now_) * tick(); }

  // figures: active particles this step, particle-updates and LAMMPS steps since the
  // hierarchy started, occupied bins (collective), particles woken by the limiter
  double active_count() const { return active_total_; }
  double updates() const { return updates_; }
  double steps() const { return steps_; }
  double woken_total() const;    // (collective)
  // at the end of a run (a hierarchy started): updates, steps, woken particles, dt_max and
  // the occupied bins with their particles, one log line (collective)
  void log_summary() const;
  int occupied_bins(std::vector<double> *histogram = nullptr) const;
  // the particle on the shortest step, as "atom N steps dt_max / 2^b" (collective)
  std::string shortest_step() const;
  double dt_max() const { return dt_max_; }

  // longrange sync: the long-range force only at synchronisation points, on their intervals;
  // displacement C_d and force factor C_f of dt_long (above)
  void split_long_range(double displacement, double force_factor);
  bool long_range_split() const { return long_range_; }
  // does the kspace solver compute its forces in this step's evaluation (every particle ends
  // its step with it)
  bool long_range_due() const override { return long_due_; }
  // the kspace solver around its evaluation: the forces before it, then a_long = (f - those) / m;
  // split_scale: r_s
  void long_range_before() override;
  void long_range_after(double split_scale) override;
  // ... or the forces before it back (an evaluation for the energy alone)
  void long_range_discard() override;
  // a_long of owned atom i at the last synchronisation point (zeros without longrange sync)
  const double *long_range_acceleration(int i) const
  {
    static const double none[3] = {0.0, 0.0, 0.0};
    return long_range_ ? atom->darray[accel_long_][i] : none;
  }

  // forward: active flags or bins to the ghosts; reverse: the limiter's bins (max)
  int pack_forward_comm(int n, int *list, double *buf);
  void unpack_forward_comm(int n, int first, const double *buf);
  int pack_reverse_comm(int n, int first, double *buf);
  void unpack_reverse_comm(int n, const int *list, const double *buf);

  // the hierarchy ends (its fix goes: unfix, or defined again): the particles inside their
  // steps take their v and u at the current time, the predictions (as compute sph/astro/global
  // reads them), so that what follows starts from that state; those at the end of a step have
  // it. Only where the rank's atoms are as the last run left them (their local_hash(), taken
  // then): v or u set since are the user's. No communication (a destructor calls it); finds the
  // state by name, does nothing without it
  void hand_over(std::uint64_t last_local_hash);
  // XOR of atom_state_hash() over this rank's atoms (no communication)
  std::uint64_t local_hash() const;

  void write_restart(std::vector<double> &list) const;
  // returns the number of values read
  int read_restart(const double *list);

 private:
  LAMMPS_NS::Fix *owner_;
  int owner_groupbit() const;    // (owner_->groupbit: fix.h is not included here)
  int levels_;
  bool pair_kicks_;
  StateIndex state_;
  StepIndex idx_;
  bool started_ = false, continuing_ = false;
  double ti_now_ = 0.0, ti_next_ = 0.0;    // ticks: this LAMMPS step's start and end
  double ti_last_ = -1.0;    // ticks: the latest end of the particles' steps (-1: unknown)
  double dt_max_ = 0.0;
  LAMMPS_NS::bigint hierarchy_step_ = -1;    // the step the hierarchy's state belongs to
  std::vector<char> active_;
  std::vector<int> active_list_;    // the active owned atoms of this step (pre_force)
  // the owned atoms given an opening kick at step kicked_step_ (end_of_step; -1: any atom may
  // have one)
  std::vector<int> kicked_;
  LAMMPS_NS::bigint kicked_step_ = -1;
  std::vector<double> bins_, required_;      // owned and ghost: bins, the limiter's minimum bin
  std::vector<double> bins_sent_;            // owned: the bins last sent to the ghosts
  std::vector<char> bins_changed_;           // owned and ghost atoms whose bins are sent
  LAMMPS_NS::bigint bins_sent_step_ = -1;    // the step of the last send (-1: none this run)
  int bins_nall_ = 0;                        // owned + ghost atoms then
  std::vector<double> times_, sums_;         // owned and ghost times, pair sums (pair_impulses)
  int nsum_ = 4;                             // sums_ sent per atom (pair_impulses)
  // the prediction's pair sums (pair_impulses) of the atoms that sleep through a pair's close:
  // atom i's at extra_[EXTRA_STRIDE extra_at_[i]] (extra_at_ -1: none)
  std::vector<double> extra_;
  std::vector<int> extra_at_;         // owned and ghost atoms
  int extra_width_ = 3;               // extra_ used per atom then
  bool opening_ = false;              // the sums are those of an opening
  std::vector<int> touched_;          // ghosts with pair sums: only they are sent
  std::vector<int> touched_owned_;    // owned atoms with pair sums (of the last call)
  std::vector<char> touched_mark_;
  std::vector<char> times_changed_;        // owned and ghost atoms whose times are sent
  LAMMPS_NS::bigint times_opened_ = -1;    // the steps of the last opening and closing whose
  LAMMPS_NS::bigint times_closed_ = -1;    // times the ghosts hold (-1: none)
  int times_nall_ = 0;                     // owned + ghost atoms then
  enum class Comm {
    ACTIVE,
    BINS,
    BINS_CHANGED,
    REQUIRED,
    TIMES,
    TIMES_CHANGED,
    SUMS
  } comm_ = Comm::ACTIVE;
  double active_total_ = 0.0, updates_ = 0.0, steps_ = 0.0, woken_ = 0.0;
  bool long_range_ = false;    // longrange sync
  bool long_due_ = false;      // this step's evaluation computes the long range
  double long_displacement_ = 0.02, long_force_factor_ = 0.3, long_split_ = 0.0;
  double long_evaluations_ = 0.0;    // of this run
  double long_middle_ = 0.0;         // ticks: the middle of this step's interval
  int accel_long_ = -1;              // d2_step_accel_long
  std::vector<double> f_before_;

  double tick() const;
  double mass(int i) const { return atom->rmass ? atom->rmass[i] : atom->mass[atom->type[i]]; }
  // pair sph/astro keeps the pairs it evaluates: for the limiter and the pair kicks
  bool records_pairs() const { return levels_ > 0 || pair_kicks_; }
  void grow();
  void assign_bins(const std::vector<double> &wanted, bool fresh, LAMMPS_NS::PairSPHAstro *pair);
  void limit(LAMMPS_NS::PairSPHAstro *pair);
  void pair_impulses(LAMMPS_NS::PairSPHAstro *pair, bool closing, bool with_forces);
  // owned atom i's sums of the last pair_impulses() (zeros for an atom in no pair, or with
  // kicks particle)
  const double *pair_sums(int i) const;
  // owned atom i's prediction sums of the last pair_impulses() (zeros if none)
  const double *extra_sums(int i) const;
  double *extra_of(int i);    // atom i's prediction sums, made (zeros) if it has none
  void keep_pending();
  void send_times(bool changed_only);
  void send_bins();
  void touch(int i, int nlocal)
  {
    if (!touched_mark_[i]) {
      touched_mark_[i] = 1;
      (i >= nlocal ? touched_ : touched_owned_).push_back(i);
    }
  }
  void advance_to_next();
  // dt_long (collective; infinite without a limit)
  double long_range_step() const;
  // the middle of the interval between synchronisation points that holds this LAMMPS step
  // (long_middle_), and at its start v += a_long Delta / 2 (collective)
  void long_range_interval();
  // the earliest begin and the latest end of a particle step, in ticks (collective)
  void interval_ticks(double &first_begin, double &last_end) const;
  // after the limiter: the interval shortened by a wake (last_end_before: the latest end
  // before it; collective)
  void long_range_woken(double last_end_before);
};

}    // namespace SPHAstro

#endif
