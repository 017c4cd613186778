/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: kernel-softened self-gravity, short-range part
------------------------------------------------------------------------- */

#ifdef PAIR_CLASS
// clang-format off
PairStyle(sph/astro/gravity,PairSPHAstroGravity);
// clang-format on
#else

#ifndef LMP_PAIR_SPH_ASTRO_GRAVITY_H
#define LMP_PAIR_SPH_ASTRO_GRAVITY_H

#include "pair.h"
#include "sph_astro_active_set.h"

#include <string>
#include <utility>
#include <vector>

namespace SPHAstro {
struct StateIndex;
enum class KernelType;
}    // namespace SPHAstro

namespace LAMMPS_NS {

class PairSPHAstroGravity : public Pair, public SPHAstro::ActiveSetClient {
 public:
  PairSPHAstroGravity(class LAMMPS *);
  ~PairSPHAstroGravity() override;

  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  void write_restart_settings(FILE *) override;
  void read_restart_settings(FILE *) override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  void *extract(const char *, int &) override;
  void *extract_peratom(const char *, int &) override;
  double memory_usage() override;
  // individual timesteps (fix sph/astro): the pairs with an active atom only
  void set_active_set(const SPHAstro::ActiveSet &set) override { active_ = set; }

  // for compute sph/astro/gravity/direct (valid after init_style)
  double gravity_constant() const { return G_; }
  SPHAstro::KernelType kernel() const { return kernel_; }
  // softening length of local or ghost atom i: that of its type (keyword softening) if given, else
  // d_h of the SPH state if > 0, else the fixed h
  double softening_length(int i) const;
  double cutoff() const { return cut_global_; }
  // the cutoff LAMMPS' lists and ghost shell need: none with direct summation or the tree in an
  // open box; the short range (ghosts as periodic images) with PPPM, MSM or the periodic tree
  double list_cutoff() const
  {
    return (split_ == Split::NONE || (split_ == Split::TREE && !periodic_tree())) ? 0.0
                                                                                  : cut_global_;
  }
  // the adaptive-softening terms were part of the latest force evaluation
  bool zeta_active() const { return zeta_active_; }
  // zeta_i / Omega_i of the owned atoms for the latest force evaluation (null: no zeta terms)
  const double *zeta_over_omega() const { return zeta_active_ ? zeta_over_omega_ : nullptr; }

  // long-range split of the active gravity kspace: none (direct summation within the
  // cutoff), Ewald/PPPM (erfc split), MSM (gamma split), or the tree, which computes all of it
  enum class Split { NONE = 0, EWALD = 1, MSM = 2, TREE = 3 };
  // the tree's TreePM split in a periodic box: the short range on the tree over owned and
  // ghost atoms (their h and zeta/Omega sent here), the long range by PPPM
  bool periodic_tree() const;

 protected:
  double cut_global_;
  double G_;
  bool G_given_;
  SPHAstro::KernelType kernel_;
  bool kernel_given_;
  double hfixed_;    // softening length of atoms without SPH state (0: none)
  // keyword softening TYPES H (repeatable): the type ranges as given (resolved at init, when the
  // number of types is known) and the softening length of each type (0: none; index 0 unused)
  std::vector<std::pair<std::string, double>> soft_given_;
  std::vector<double> soft_type_;
  void resolve_type_softening();

  bool have_state_;
  SPHAstro::StateIndex *state_;
  Split split_;
  double g_ewald_;

  // adaptive-softening ("zeta") terms of Price & Monaghan 2007 with variable h (grad-h mode
  // of pair sph/astro): keyword zeta yes|no; zeta_ holds zeta_i (owned + ghost)
  bool zeta_on_;
  bool zeta_active_;
  class PairSPHAstro *sph_;
  double *zeta_;
  double *zeta_over_omega_;    // kspace split: zeta_i / Omega_i of owned + ghost atoms
  int nmax_;
  enum class Stage { H, ZETA };
  Stage comm_stage_;

  void allocate();
  void resolve_gravity_constant();
  double *state_h() const;
  bool zeta_terms_apply();
  void compute_zeta();
  // direct summation: x, y, z, m, h of all atoms of all ranks (gather_all), zeta/Omega of all
  // atoms; this rank's atoms start at offset_
  std::vector<double> all_, zo_all_;
  std::vector<double> gx_, gy_, gz_, gm_, gh_;    // all_ by quantity
  // eval: one row's pairs beyond the softening support (force, energy) and each pair's kind
  std::vector<double> row_force_, row_energy_;
  std::vector<char> row_kind_;
  SPHAstro::ActiveSet active_;    // all active unless fix sph/astro says otherwise
  // individual timesteps: the flags of all atoms (gathered)
  std::vector<char> active_all_;
  bool active_pairs_only_ = false;    // individual timesteps: see compute()
  std::vector<int> active_mine_;      // this rank's active atoms (eval)
  std::vector<int> gather_counts_, gather_displs_;
  int offset_, ntotal_;
  void gather_all();
  template <bool CUBIC, int SPLIT, bool ZETA> void eval(int eflag, int vflag);
};

}    // namespace LAMMPS_NS

#endif
#endif
