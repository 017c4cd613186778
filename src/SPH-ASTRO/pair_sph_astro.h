/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO: astrophysical smoothed particle hydrodynamics for LAMMPS
------------------------------------------------------------------------- */

#ifdef PAIR_CLASS
// clang-format off
PairStyle(sph/astro,PairSPHAstro);
// clang-format on
#else

#ifndef LMP_PAIR_SPH_ASTRO_H
#define LMP_PAIR_SPH_ASTRO_H

#include "pair.h"

#include "sph_astro_eos.h"
#include "sph_astro_kernel.h"
#include "sph_astro_pruned_list.h"
#include "sph_astro_state.h"
#include <vector>

namespace LAMMPS_NS {

class PairSPHAstro : public Pair {
 public:
  PairSPHAstro(class LAMMPS *);
  ~PairSPHAstro() override;

  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  void init_list(int, class NeighList *) override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  void write_restart_settings(FILE *) override;
  void read_restart_settings(FILE *) override;

  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;

  // per-particle neighbour cutoffs for neighbor multi with h collections (fix sph/astro/h
  // collections): atom i belongs to the collection that covers kernel_radius h_i growth
  double atom2cut(int) override;
  double radii2cut(double, double) override;

  void *extract(const char *, int &) override;
  void *extract_peratom(const char *, int &) override;
  double memory_usage() override;

  // physics settings read by the package's fixes and computes
  const SPHAstro::EOS &eos() const { return eos_; }
  double kernel_radius() const { return kernel_radius_; }    // support = kernel_radius * h
  SPHAstro::KernelType kernel_type() const { return kernel_; }
  double alpha() const { return visc_alpha_; }
  double beta() const { return visc_beta_; }
  bool has_viscosity() const { return visc_on_; }
  // artificial conductivity in force (alpha_u > 0 with an EOS that evolves u)
  bool artificial_conductivity() const { return cond_alpha_ > 0.0 && eos_.uses_energy(); }
  // viscosity signal: Monaghan (1997) form; the Courant criterion then uses max_j v_sig,ij
  bool signal_viscosity() const { return visc_on_ && visc_signal_; }
  // viscosity on slope-limited reconstructed velocities (keyword reconstruct)
  bool reconstruction() const { return visc_on_ && recon_on_; }
  double beta_factor() const { return visc_alpha_ > 0.0 ? visc_beta_ / visc_alpha_ : 0.0; }
  // per-particle alpha (owned + ghost) when fix sph/astro/switch is active, else null
  const double *alpha_per_atom() const { return alpha_atom_; }
  // the per-atom values of extract_peratom() belong to this step and these local atoms
  bigint computed_step() const { return computed_step_; }
  int computed_nlocal() const { return computed_nlocal_; }
  // the largest h a particle of this type may take in this run (neighbour list cutoffs)
  double h_cap(int type) const { return hcap_type_[type]; }
  // the largest h local atom i may take until the next neighbour-list build: h_cap of its
  // type, or less with h collections (the cutoff of the atom's collection)
  double h_limit(int i) const;
  // room an atom's collection leaves for its h to grow before lists are rebuilt
  static constexpr double COLLECTION_GROWTH = 1.2;
  // pruned neighbour lists (keyword prune, sph_astro_pruned_list.h): the largest h local atom
  // i may take before the passes fall back to LAMMPS' lists (infinite when not pruning); fix
  // sph/astro/h has the lists rebuilt when an h comes within PRUNE_REBUILD of it
  bool pruning() const { return prune_on_; }
  double prune_limit(int i) const;
  static constexpr double PRUNE_GROWTH = 1.1;      // room for h to grow, variable h
  static constexpr double PRUNE_REBUILD = 1.05;    // rebuild when PRUNE_REBUILD h > limit
  // force evaluations since the run began in which this rank's pruned half list did not
  // cover every h, and atoms whose h iteration went past its limit (both use LAMMPS' lists)
  bigint prune_fallbacks() const { return prune_fallbacks_; }
  bigint prune_atom_fallbacks() const { return prune_atom_fallbacks_; }
  // physical heat conduction (pair_sph_astro_conduction.cpp): kappa = k / c_v, 0 when off
  double conduction_kappa() const { return cond_kappa_; }
  // density continuity: rho integrated by fix sph/astro (d_rho), the force evaluation uses
  // the prediction d_rhoest; density summation: both are d_rho
  bool density_continuity() const { return density_continuity_; }
  bool symmetrise_kernel() const { return symmetrise_kernel_; }
  bool pressure_geometric() const { return pressure_geometric_; }
  // formulation pressure-energy: P from the kernel-smoothed energy density, rho = P/((gamma-1) u)
  bool pressure_energy() const { return pressure_energy_; }
  // the density of the latest (or current) force evaluation, owned and ghost atoms
  double *eval_density() const;
  // neighbours inside the kernel support of the latest force evaluation (owned atoms). With
  // density continuity there is no summation pass to count them: the first call after a force
  // evaluation counts in a pass of its own (collective: call on all ranks, as computes are)
  const double *neighbour_counts();

 protected:
  SPHAstro::KernelType kernel_ = SPHAstro::KernelType::CUBIC;
  double kernel_radius_ = 2.0;
  SPHAstro::EOS eos_;
  bool visc_on_ = true;
  double visc_alpha_ = 1.0, visc_beta_ = 2.0, visc_eps_ = 0.01;
  double cond_alpha_ = 0.0;     // artificial conductivity alpha_u (0: off)
  bool balsara_on_ = false;     // Balsara shear limiter of the viscosity
  bool visc_signal_ = false;    // signal-velocity form (Monaghan 1997) instead of classic
  bool curl_on_ = false;        // curl v needed this run (Balsara or Cullen-Dehnen switch)
  // viscosity on velocities reconstructed to the pair midpoint (sph_astro_reconstruction.h)
  bool recon_on_ = false;
  double recon_trigger_ = 1.0;    // noise trigger radius in particle spacings
  int recon_gate_ = 16;           // smoothness gate exponent P (0: off)

  // the seeds' other choices (fixed h and dh/dt only; doc/pair_sph_astro.rst):
  //   density continuity: drho_i/dt = sum_j m_j v_ij . grad_i W_ij (seed 004 eq. 33),
  //                       integrated by fix sph/astro, instead of the summation
  //   symmetrise kernel:  W_ij = (W(r_ij, h_i) + W(r_ij, h_j))/2 instead of W(r_ij, h_ij)
  //   pressure geometric: 2 sqrt(P_i P_j)/(rho_i rho_j) instead of P_i/rho_i^2 + P_j/rho_j^2
  //                       (both seed 000, "alternative ways to force anti-symmetry")
  bool density_continuity_ = false;
  bool symmetrise_kernel_ = false;
  bool pressure_geometric_ = false;
  // formulation pressure-energy (Saitoh & Makino 2013, ApJ 768, 44; Hopkins 2013, MNRAS 428,
  // 2840): the pressure is summed, not the density,
  //   P_i = (gamma-1) sum_j m_j u_j W_ij,   rho_i = P_i / ((gamma-1) u_i),
  // so that P is smooth across a contact discontinuity in pressure balance; with fix
  // sph/astro/h iterate (h from the mass density) with the grad-h term C_i of pe_gradh_
  bool pressure_energy_ = false;
  // pressure-energy with grad-h terms: C_i = h_i (dP_i/dh_i) / (d rho^m_i Omega_i) (owned +
  // ghost), rho^m the mass density that sets h; Hopkins' f_ij (gamma-1) u_j = (gamma-1) u_j - C_i
  double *pe_gradh_ = nullptr;
  SPHAstro::ContinuityIndex continuity_index_;
  bigint counts_step_ = -1;    // step whose force evaluation nneigh_ was counted in
  // pressure geometric: sqrt(P)/rho; pressure-energy: (gamma-1) u = P/rho (owned + ghost)
  double *pgeo_ = nullptr;

  // physical heat conduction (pair_sph_astro_conduction.cpp): a separate pass after the
  // force pass, only when kappa > 0; conduct_ holds this step's du/dt from it (owned + ghost)
  double cond_kappa_ = 0.0;
  double *conduct_ = nullptr;
  int conduct_nmax_ = 0;
  void conduction_pass();
  template <class KERNEL, int DIM, bool GRADH> void conduction_loop();
  bool ghosts_need_u() const;

  // per-particle viscosity alpha of fix sph/astro/switch (owned + ghost), null without it;
  // beta follows as (beta / alpha) x alpha_i
  class FixSPHAstroSwitch *switch_ = nullptr;
  double *alpha_atom_ = nullptr;

  SPHAstro::StateIndex state_;
  class FixSPHAstro *integrator_ = nullptr;
  bool entropy_ = false;    // fix sph/astro thermal entropy: P = A rho^gamma
  SPHAstro::EntropyIndex entropy_index_;

  // smoothing length: fixed, evolved by dh/dt (both with the mean h_ij = (h_i + h_j)/2 in
  // every pair term), or iterated with rho (kernels W(h_i) and W(h_j), grad-h factor Omega)
  enum class HMode { FIXED, DHDT, GRADH };
  HMode hmode_ = HMode::FIXED;
  class FixSPHAstroH *hfix_ = nullptr;
  class NeighList *listfull_ = nullptr;       // GRADH density iteration: full list
  class NeighList *lammps_half_ = nullptr;    // LAMMPS' half list (none: GRADH with prune)

  // pruned lists (keyword prune, default yes): LAMMPS' half and full lists cut down to the
  // kernel supports at each list build, for h up to hprune_ (owned + ghost)
  bool prune_on_ = true;
  SPHAstro::PrunedList pruned_half_, pruned_full_;
  SPHAstro::PrunedList fallback_half_;      // GRADH with prune: unpruned half list, on demand
  std::vector<unsigned char> half_keep_;    // per full-list entry: in LAMMPS' half list
  double *hprune_ = nullptr;
  bigint prune_fallbacks_ = 0, prune_atom_fallbacks_ = 0;
  double prune_lengths_[2] = {0.0, 0.0};    // entries per atom, half and full list
  void prune_lists();
  SPHAstro::NeighView half_view();    // the pruned half list if it covers every h, else LAMMPS'
  SPHAstro::NeighView unpruned_half_view();
  SPHAstro::HalfFromFull half_from_full() const;
  bool nothing_to_prune() const;
  void begin_pruned(SPHAstro::PrunedList &list, const class NeighList *src);
  int *pruned_row(SPHAstro::PrunedList &list, int i);

  // h cap of each atom type for this run: margin x its largest h at init. Cutoff of types
  // (i,j): kernel_radius (cap_i + cap_j)/2 with h_ij, kernel_radius max(cap_i, cap_j) with GRADH
  double *hcap_type_ = nullptr;

  // per-atom work arrays (owned + ghost), grown to atom->nmax
  int nmax_ = 0;
  double *pressure_ = nullptr;      // P
  double *soundspeed_ = nullptr;    // c_s
  double *vdotgradw_ = nullptr;     // sum_j m_j v_ij . grad_i W_ij  (= -rho_i div v_i)
  double *divv_ = nullptr;          // div v
  double *nneigh_ = nullptr;        // neighbours inside the kernel support
  double *omega_ = nullptr;         // grad-h factor Omega (1 without GRADH)
  double **dcurl_ = nullptr;        // Balsara: sum_j m_j v_ij . grad W, sum_j m_j v_ij x grad W
  double *curlv_ = nullptr;         // |curl v|
  double *balsara_ = nullptr;       // Balsara factor f of this step
  double *vsigmax_ = nullptr;       // signal viscosity: max_j v_sig,ij over the kernel
  double **vgsum_ = nullptr;        // reconstruction: the sums M, G of grad v = G M^-1
  double **vgrad_ = nullptr;        // reconstruction: symmetric grad v and spacing Delta
  // artificial conductivity: sum_j m_j alpha_u v_sig |dW/dr| / rho_ij, the rate of its
  // explicit diffusion (fix sph/astro's timestep; sph_astro_pair_terms.h)
  double *condrate_ = nullptr;

  bigint computed_step_ = -1;
  int computed_nlocal_ = -1;

  enum class Stage {
    DENSITY,
    FORCE,
    SMOOTHING_LENGTH,
    VELOCITY,
    ENERGY,
    CURL,
    VGRAD,
    CONDUCTION,
    COUNT
  };
  Stage comm_stage_ = Stage::DENSITY;

  void allocate();
  void grow_work_arrays();
  // viscosity variants of the force pass: form (classic/signal) x Balsara limiter or
  // reconstruction (the two are not combined: a linear shear flow is reconstructed away)
  enum ViscosityForm {
    NO_VISCOSITY = 0,
    CLASSIC = 1,
    BALSARA = 2,
    SIGNAL = 3,
    SIGNAL_BALSARA = 4,
    CLASSIC_RECONSTRUCT = 5,
    SIGNAL_RECONSTRUCT = 6
  };
  static constexpr bool visc_balsara(int v) { return v == BALSARA || v == SIGNAL_BALSARA; }
  static constexpr bool visc_signal(int v)
  {
    return v == SIGNAL || v == SIGNAL_BALSARA || v == SIGNAL_RECONSTRUCT;
  }
  static constexpr bool visc_reconstruct(int v)
  {
    return v == CLASSIC_RECONSTRUCT || v == SIGNAL_RECONSTRUCT;
  }
  // pair forms of the force pass (template parameter FORM): how W_ij is symmetrised and how
  // the pressure term is; grad-h terms come with their own kernels and the standard pressure
  enum PairForm {
    HMEAN = 0,                    // W(r_ij, h_ij), P_i/rho_i^2 + P_j/rho_j^2
    GRADH = 1,                    // W(h_i), W(h_j) with grad-h factors (fix sph/astro/h iterate)
    KMEAN = 2,                    // (W(h_i) + W(h_j))/2, P_i/rho_i^2 + P_j/rho_j^2
    HMEAN_GEOMETRIC = 3,          // W(r_ij, h_ij), 2 sqrt(P_i P_j)/(rho_i rho_j)
    KMEAN_GEOMETRIC = 4,          // (W(h_i) + W(h_j))/2, 2 sqrt(P_i P_j)/(rho_i rho_j)
    HMEAN_PRESSURE_ENERGY = 5,    // W(r_ij, h_ij), (gamma-1)^2 u_i u_j (1/P_i + 1/P_j)
    GRADH_PRESSURE_ENERGY = 6     // W(h_i), W(h_j), (gamma-1) u_i ((gamma-1) u_j - C_i) / P_i ...
  };
  static constexpr bool form_gradh(int f) { return f == GRADH || f == GRADH_PRESSURE_ENERGY; }
  static constexpr bool form_kmean(int f) { return f == KMEAN || f == KMEAN_GEOMETRIC; }
  static constexpr bool form_geometric(int f)
  {
    return f == HMEAN_GEOMETRIC || f == KMEAN_GEOMETRIC;
  }
  static constexpr bool form_pressure_energy(int f)
  {
    return f == HMEAN_PRESSURE_ENERGY || f == GRADH_PRESSURE_ENERGY;
  }
  int pair_form() const;
  // velocity sums taken with the density (GRADH) or in a pass of their own: none, the div and
  // curl sums (Balsara, switches), or the full gradient sums (reconstruction; div and curl
  // follow from them)
  enum VelocitySums { VSUMS_NONE = 0, VSUMS_CURL = 1, VSUMS_GRADIENT = 2 };
  template <class KERNEL, int DIM, int KFORM, int VSUMS> void velocity_curl();
  void velocity_curl_finish(bool gradh);
  template <int DIM> void velocity_gradient_finish(bool gradh);
  void forward_predicted_velocities();
  // PE (pressure-energy): the same pass sums m_j u_j W_ij, then rho_i = that / u_i
  template <class KERNEL, int DIM, bool KM, bool PE> void density_sum();
  void pressure_energy_density(const double *energy_sum);
  // PE: also sum_j m_j u_j W_ij(h_i) into pgeo_ and the grad-h term C_i into pe_gradh_, at
  // the h the iteration keeps
  template <class KERNEL, int DIM, int VSUMS, bool PE> void density_gradh();
  void count_neighbours();
  template <class KERNEL, int DIM, int FORM, bool ENERGY, int VISC, bool COND> void force_pass();
  template <class KERNEL, int DIM, int FORM> void dispatch_force();
  template <class KERNEL, int DIM> void dispatch_physics();
  template <class KERNEL> void dispatch_dimension();
  void equation_of_state();
  // dA/dt from the dissipative heating (entropy formulation), then du/dt = heating + P dV
  // (with pressure geometric the P dV part is summed pair by pair in the force pass)
  void finish_thermal_rates(bool gradh, bool pdv_done);
};

}    // namespace LAMMPS_NS

#endif
#endif
