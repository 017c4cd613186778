/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(sph/astro/sink,FixSPHAstroSink);
// clang-format on
#else

#ifndef LMP_FIX_SPH_ASTRO_SINK_H
#define LMP_FIX_SPH_ASTRO_SINK_H

#include "fix.h"
#include "sph_astro_active_set.h"

#include <vector>

namespace LAMMPS_NS {

// Sink particles (Bate, Bonnell & Price 1995, MNRAS 277, 362; Price et al. 2018, PASA 35, e031,
// sec. 2.8): the atoms of the fix's group are point masses that accrete the gas of fix
// sph/astro (mass, linear momentum, angular momentum as spin) and, with *create*, are made
// from dense collapsing gas. Sinks are few: every rank keeps all of them (sinks()).
class FixSPHAstroSink : public Fix, public SPHAstro::TimestepLimiter {
 public:
  // one sink as every rank sees it (gathered, sorted by tag)
  struct Sink {
    tagint tag;
    double x[3], v[3], m;
    double spin[3];    // angular momentum about its own centre of mass
    double macc;       // mass accreted since it was defined or created
    double nacc;       // gas particles accreted
    double mlow;       // the round-off of m: the mass is m + mlow (compensated sums)
  };

  FixSPHAstroSink(class LAMMPS *, int, char **);
  ~FixSPHAstroSink() override;

  int setmask() override;
  void init() override;
  void setup(int) override;
  void setup_pre_exchange() override;
  void pre_exchange() override;
  void end_of_step() override;
  double compute_scalar() override;
  double compute_vector(int) override;

  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  double memory_usage() override;

  // SPHAstro::TimestepLimiter (collective): the longest step the sinks allow now
  double timestep_limit() override;

  // all sinks, sorted by tag, as of the latest gather (collective)
  const std::vector<Sink> &gather_sinks();

 protected:
  double racc_ = 0.0;    // accretion radius
  double rin_ = -1.0;    // inner radius: accreted without further checks (< 0: 0.8 racc)
  double G_ = 0.0;       // gravitational constant (0: from pair sph/astro/gravity)
  bool G_given_ = false;
  double rho_create_ = 0.0;    // creation threshold density (0: no creation)
  int create_type_ = 0;        // the type a sink made from gas takes
  double dt_factor_ = 0.3;     // C of the sinks' timestep criteria
  double hsoft_ = 0.0;         // softening of the pair gravity (for the potential minimum check)

  class FixSPHAstro *gas_fix_ = nullptr;
  class PairSPHAstro *pair_ = nullptr;
  int gasbit_ = 0;
  int rho_index_ = -1, h_index_ = -1, u_index_ = -1;

  // per-atom state (all atoms; used for the sinks): spin (3), accreted mass, accreted count,
  // round-off of the mass
  double **spin_ = nullptr;
  double *macc_ = nullptr;
  double *nacc_ = nullptr;
  double *mlow_ = nullptr;    // round-off of rmass: the sink's mass is rmass + mlow (Neumaier)

  std::vector<Sink> sinks_;
  std::vector<int> sink_owner_;    // rank that owns sinks_[k]
  std::vector<int> sink_local_;    // its local index there (-1 elsewhere)

  // totals (restart): accreted mass, accreted particles, sinks created
  double total_macc_ = 0.0;
  double total_events_ = 0.0;
  double total_created_ = 0.0;
  double last_dt_limit_ = 0.0;
  // atoms made sinks at the latest end_of_step: their neighbours are accreted at the next
  // reneighbouring without further checks
  std::vector<tagint> newborn_;
  bool accretion_due_ = false;

  double gravity_constant() const;
  bool candidates_near_sinks();
  void accrete();
  bool try_create();
  int check_creation(tagint candidate, const double *xc, std::vector<double> &group, int &reason);
};

}    // namespace LAMMPS_NS

#endif
#endif
