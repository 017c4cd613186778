/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The neighbour passes of pair sph/astro. Each is one pair_loop() (sph_astro_pair_loop.h)
// with an interaction adapter around the functions of sph_astro_iact.h, compiled per kernel,
// dimension and kernel form; the options of a scene are run-time values (but for the few
// compiled in where they cost: doc/architecture.md). The passes read and write plain arrays:
// they do not communicate (pair sph/astro sums the ghosts' parts with a reverse
// communication after a pass and sends what the next pass needs).
//
// The order of the passes in one force evaluation, with the communication between them:
// sph_astro_force_evaluation.h.

#ifndef LMP_SPH_ASTRO_PASSES_H
#define LMP_SPH_ASTRO_PASSES_H

#include "lmptype.h"
#include "sph_astro_eos.h"
#include "sph_astro_evaluated_pairs.h"
#include "sph_astro_fields.h"
#include "sph_astro_iact.h"
#include "sph_astro_options.h"
#include "sph_astro_pair_loop.h"

#include <vector>

namespace LAMMPS_NS {
class Error;
class Pair;
}    // namespace LAMMPS_NS

namespace SPHAstro {

class SoftenedKernel;

// what every pass sees
struct PassContext {
  KernelType kernel;
  int dim;
  Particles p;
  NeighView half;    // the half list of the passes
  bool newton;
  Fields *f;
  double *rho;        // the density of this force evaluation (summed, or predicted)
  double *rho_sum;    // where the summation writes (d_rho)
  double *uest;       // predicted u (owned + ghost where a pass needs it)
  double **vest;      // predicted v
  double *dudt;
  double **force;
  double *alpha;    // per-atom alpha of a viscosity switch (owned + ghost), or null
  const LAMMPS_NS::tagint *tag;
  LAMMPS_NS::Error *error;
  LAMMPS_NS::Pair *tally;    // non-null: tally the pair virial (ev_tally)
  EvaluatedPairs *pairs;     // non-null: the force pass records each pair
  // individual steps: marks over owned and ghost atoms, set for the ghosts in the pairs of
  // this evaluation and their owners (null: every ghost); the state goes to, and the sums come
  // back from, the marked ghosts only, and the force pass leaves the others out of its loops
  const char *ghosts_in_pairs = nullptr;
  // per type: 1 if pair sph/astro acts on it (its pair_coeff); atoms of other types (sinks,
  // stars) are in no list and get no density, pressure or sound speed (null: all types)
  const int *sph_type = nullptr;
  bool is_sph(int i) const { return !sph_type || sph_type[p.type[i]]; }
  int nzero() const { return newton ? p.nall : p.nlocal; }
};

// rho_i = sum_j m_j W_ij with the self term (or sum_j m_j u_j W_ij with weight_u), into
// rho_sum, and the neighbour counts; two_h: the averaged kernel
void density_summation(const PassContext &ctx, bool two_h, bool weight_u);
// neighbours inside the support only (density continuity has no summation pass)
void count_neighbours(const PassContext &ctx, bool two_h);

// the h-rho iteration over a full list (Springel & Hernquist 2002; Price 2012, sec. 2.4)
enum class VelocitySums { NONE, CURL, GRADIENT };
// the rows of an h iteration that went past its list's limit: every j with r_ij < R h_row,
// h_row = min(WIDE_ROW x h, h_cap) (returned)
struct WideRows {
  static constexpr double WIDE_ROW = 1.5;
  virtual const int *row(int i, double h, double &h_row, int &n) = 0;
  virtual ~WideRows() = default;
};

struct GradhSettings {
  double hfact, tolerance;
  int max_iterations;
  NeighView full;         // the gather rows
  const double *hlist;    // the largest h each row of full serves
  WideRows *wide;         // rows for an h past hlist
  double h_cap;           // the largest h the ghosts allow
  VelocitySums sums;
  bool pressure_energy;
  double gamma;
  // pair sph/astro/gravity's adaptive softening (3D; sph_astro_gravity_kernel.h): at the h
  // kept, S_i = sum_{j != i} m_j dphi(r_ij, h_i)/dh_i into dphidh_sum (null: not wanted), with
  // the softened potential of the kernel
  double *dphidh_sum = nullptr;
  const SoftenedKernel *softened = nullptr;
};
struct GradhStatistics {
  double iterations_sum = 0.0;
  int iterations_max = 0, particles = 0, failures = 0, capped = 0;
  // the first atom (by ID) that did not converge, and the first held at the cap (0: none)
  LAMMPS_NS::tagint first_failure = 0, first_capped = 0;
};
void density_gradh(const PassContext &ctx, const GradhSettings &s, GradhStatistics &stats);

// velocity sums over the half list (curl: dcurl; gradient: vgsum); two_h: averaged kernel
void velocity_sums(const PassContext &ctx, bool two_h, VelocitySums sums);
// div v, |curl v| and the Balsara factor of the owned atoms from dcurl (omega: grad-h)
void finish_curl(const PassContext &ctx, bool omega, bool balsara);
// symmetric grad v and the spacing of the owned atoms from vgsum; with curl, the div and curl
// sums follow from G
void finish_velocity_gradient(const PassContext &ctx, double trigger, bool curl);

// the force settings of a scene's options; gradh: fix sph/astro/h iterate; per_particle_alpha:
// a viscosity switch
ForceSettings force_settings(const PairOptions &o, bool gradh, bool per_particle_alpha);
// accelerations, du/dt and div v; two_h: grad-h or averaged kernel (average)
void force_pass(const PassContext &ctx, const ForceSettings &s, bool two_h, bool average);
// after the ghosts' parts are summed: div v (and, with pressure-energy, the P dV sum / e_i)
void finish_force(const PassContext &ctx, const ForceSettings &s);

// physical heat conduction into f->conduct; two_h: mean of dW/dr at h_i and h_j
void conduction_pass(const PassContext &ctx, double kappa, bool two_h);

// thermal entropy state: A, its prediction, dA/dt, and u (A from u)
struct EntropyArrays {
  double *A, *Aest, *dAdt;
  const double *u;
};
void equation_of_state(const PassContext &ctx, const EOS &eos, double h_cap,
                       bool density_continuity, const EntropyArrays *entropy, bool init_entropy);
void pressure_energy_density(const PassContext &ctx, const double *energy_sum);
void thermal_rates(const PassContext &ctx, const EOS &eos, bool omega, bool pdv_done, double *dAdt);

// XSPH drift correction over the half list (mean h): out_i = sum_j m_j/rho_ij (v_j - v_i) W_ij
// (with newton, the ghost rows hold parts of their owners' sums)
void xsph_pass(const PassContext &ctx, double **out);

}    // namespace SPHAstro

#endif
