/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

#ifdef PAIR_CLASS
// clang-format off
PairStyle(sph/astro,PairSPHAstro);
// clang-format on
#else

#ifndef LMP_PAIR_SPH_ASTRO_H
#define LMP_PAIR_SPH_ASTRO_H

#include "pair.h"
#include "sph_astro_evaluated_pairs.h"

#include <initializer_list>
#include <vector>

namespace SPHAstro {
struct PairOptions;
struct EOS;
struct Fields;
struct PassContext;
struct GradhStatistics;
struct SearchStatistics;
struct StateIndex;
struct EntropyIndex;
struct ContinuityIndex;
struct StepIndex;
struct NeighView;
class NeighbourLists;
struct Scheme;
struct GradhSettings;
class CommTable;
struct CommField;
enum class KernelType;
}    // namespace SPHAstro

namespace LAMMPS_NS {

// pair_style sph/astro owns the hydrodynamics of a step: options, neighbour lists, the passes
// (sph_astro_passes.h) and their per-atom results. The package's fixes configure it through
// Fix::extract() (h mode, thermal variable, switch), read its results through the narrow
// interface below and hold no state of it; it holds no pointer to them (doc/architecture.md).
class PairSPHAstro : public Pair {
 public:
  PairSPHAstro(class LAMMPS *);
  ~PairSPHAstro() override;

  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  void finish() override;
  double init_one(int, int) override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  void write_restart_settings(FILE *) override;
  void read_restart_settings(FILE *) override;

  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;

  void *extract(const char *, int &) override;
  void *extract_peratom(const char *, int &) override;
  double memory_usage() override;

  // settings
  const SPHAstro::PairOptions &options() const { return *opt_; }
  // per-particle alpha (owned + ghost) when fix sph/astro/switch is active, else null
  const double *alpha_per_atom() const { return alpha_atom_; }

  // results of the latest force evaluation (owned atoms; ghosts where communicated):
  // P, c_s, div v, curl v (null unless Balsara or Cullen-Dehnen need it), Omega, ...
  const SPHAstro::Fields &fields() const { return *fields_; }
  bigint computed_step() const { return computed_step_; }
  int computed_nlocal() const { return computed_nlocal_; }
  // grad-h factors Omega, null unless fix sph/astro/h iterate
  const double *omega() const;
  // pair sph/astro/gravity's adaptive softening: S_i = sum_j m_j dphi(r_ij, h_i)/dh_i of the
  // h iteration (owned atoms), null unless it asked for them and h iterates
  const double *dphidh_sums() const;
  // the density of the latest force evaluation: the summed d_rho, or with density continuity
  // the prediction d_rhoest (owned and ghost atoms)
  double *eval_density() const;
  // neighbours inside the kernel support (owned atoms). With density continuity there is no
  // summation pass to count them: the first call after a force evaluation counts in a pass
  // of its own (collective: call on all ranks, as computes are)
  const double *neighbour_counts();
  // the signal speed of the Courant criterion of atom i, dt = C h_i / v: max_j v_sig,ij with
  // signal viscosity or set_courant_pairs(true), else c + h |div v| + 1.2 (alpha c + beta h
  // |div v|)
  double courant_signal_speed(int i) const;
  // fix sph/astro vsig pairs: keep max_j v_sig,ij for the Courant criterion whatever the
  // viscosity (PairOptions::tracks_signal)
  void set_courant_pairs(bool on);
  // the artificial conductivity's diffusion rate sum_j k_ij of atom i (0 without it)
  double conductivity_rate(int i) const;
  // fix sph/astro xsph: dv_i = eps sum_j m_j / rho_ij (v_j - v_i) W(r_ij, h_ij) of the owned
  // atoms into out (rows for owned and ghost atoms), over the pair's lists (collective)
  void xsph_correction(double eps, double **out);

  // fix sph/astro: A from u (thermal entropy) and rho from one summation (density
  // continuity) at the next force evaluation
  void schedule_initialisation(bool entropy, bool density);
  // fix sph/astro/h: statistics of the latest h iteration (this rank) and failures since init
  const SPHAstro::GradhStatistics &h_statistics() const { return *hstats_; }
  bigint h_failures() const { return h_failures_; }

  // neighbour search (sph_astro_neighbour_lists.h). h_cap: the largest h any particle may
  // take, (ghost cutoff - skin) / kernel radius; a run starts with the ghost cutoff at
  // kernel radius x margin x the largest h + skin
  double h_cap() const { return h_cap_; }
  double h_cap_start() const { return h_cap_start_; }
  // the SPH gas: the atom types of this style's pair_coeff I I (valid after init_style); the
  // other types (point masses) are in no SPH sum
  bool gas_type(int t) const { return sph_type_ && sph_type_[t]; }
  // the number of gas atoms outside a group (collective): those fix sph/astro and fix
  // sph/astro/h must hold all of
  bigint gas_outside(int groupbit) const;
  // the number of atoms of a group that are not gas (collective): fix sph/astro refuses them
  // (its timestep criteria need an h and a sound speed)
  bigint point_masses_in(int groupbit) const;
  // the run keeps the h cap of the run it continues (fix sph/astro/h then keeps its ghost cutoff)
  bool carried_cap_used() const { return carried_cap_used_; }
  static constexpr double CARRIED_CAP_MAX = 4.0;
  double kernel_radius() const { return kernel_radius_; }
  static constexpr double LIST_GROWTH = 1.1;    // room for h to grow in the lists, variable h
  // fix sph/astro/h widens the ghost cutoff when LIST_REBUILD x the largest h exceeds h_cap
  static constexpr double LIST_REBUILD = 1.05;
  const SPHAstro::SearchStatistics &search_statistics() const;

  // individual timesteps (fix sph/astro steps individual): the owned and ghost atoms whose
  // step ends with this step's force evaluation (one flag per atom, valid until the next
  // reneighbouring; null: global stepping). Only the pairs with an active atom are evaluated,
  // and only active atoms get new values (sph_astro_force_evaluation.h)
  // record: keep each evaluated pair (evaluated_pairs(): the timestep limiter's neighbours),
  // with_forces: and its force (the pair kicks of fix sph/astro kicks pair)
  void set_active(const char *active, bool record = false, bool with_forces = false)
  {
    active_ = active;
    record_pairs_ = record;
    record_forces_ = record && with_forces;
  }
  // pair sph/astro/gravity's adaptive softening (its init_style asks): the h iteration also
  // sums, for the owned atoms, S_i = sum_{j != i} m_j dphi(r_ij, h_i)/dh_i over the kernel
  // neighbours (dphidh_sums(); this style acts on every gas type, so these are all gravitating
  // gas neighbours within R h_i)
  void sum_softening_derivatives() { dphidh_sums_ = true; }
  // the active flags of owned and ghost atoms set for this step (null: global stepping)
  const char *active_flags() const { return active_; }
  // the pairs of the latest evaluation with individual steps, those inside the kernel
  // support(s) of the force pass, with their pressure and viscous force if asked (when
  // recorded; valid until the next reneighbouring)
  const SPHAstro::EvaluatedPairs &evaluated_pairs() const { return evaluated_pairs_; }

  // the communication of one stage of a force evaluation (sph_astro_force_evaluation.h):
  // owned -> ghost copies of these arrays, or the ghosts' parts summed into their owners
  // (chosen: only the atoms marked there, per owned and ghost atom)
  void forward(std::initializer_list<SPHAstro::CommField> fields, const char *chosen = nullptr);
  void reverse(std::initializer_list<SPHAstro::CommField> fields, const char *chosen = nullptr);
  // the ghosts' marks to their owners (and to the ghosts a later swap passes on)
  void gather_marks(char *marks);

 protected:
  SPHAstro::PairOptions *opt_;
  SPHAstro::Fields *fields_;
  SPHAstro::NeighbourLists *lists_;
  SPHAstro::GradhStatistics *hstats_;
  SPHAstro::StateIndex *state_;
  SPHAstro::EntropyIndex *entropy_index_;
  SPHAstro::ContinuityIndex *continuity_index_;
  SPHAstro::StepIndex *step_index_;
  const char *active_;
  SPHAstro::EvaluatedPairs evaluated_pairs_;
  bool record_pairs_ = false, record_forces_ = false;

  SPHAstro::Scheme *scheme_;    // what the package's fixes ask for (sph_astro_scheme.h)
  bool entropy_init_pending_, density_init_pending_;
  double entropy_gamma_;       // gamma of the last run with thermal entropy (0: none)
  bool restart_variable_h_;    // the restart file read comes from a run with variable h
  double *alpha_atom_;         // d_alpha of fix sph/astro/switch: the current alpha (timestep)
  double *alpha_force_;        // d_alpha_force: the alpha the forces use (fix_sph_astro_switch.cpp)
  double h_cap_start_;         // margin x the largest h at init (sets the ghost cutoff)
  double h_cap_;               // (ghost cutoff - skin) / kernel_radius_
  bool carried_cap_used_ = false;
  int *sph_type_;               // per type: 1 if this pair style acts on it
  bool dphidh_sums_ = false;    // sum_softening_derivatives()
  double kernel_radius_;        // the support is kernel_radius_ h
  bigint h_failures_;
  bigint counts_step_;    // step whose force evaluation the neighbour counts belong to
  bigint computed_step_;
  int computed_nlocal_;

  // communication: the arrays a stage sends (forward) or sums (reverse)
  SPHAstro::CommTable *comm_table_;
  char *marks_ = nullptr;    // gather_marks(): its reverse communication

  void allocate();
  bool gradh() const;
  void grow_fields();
  SPHAstro::PassContext context();
  SPHAstro::GradhSettings gradh_settings() const;
};

}    // namespace LAMMPS_NS

#endif
#endif
