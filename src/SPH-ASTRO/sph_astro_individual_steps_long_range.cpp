/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The long-range force of IndividualSteps (fix sph/astro longrange sync;
// sph_astro_individual_steps.h): computed where every particle ends its step and integrated on
// the intervals between those points.

#include "sph_astro_individual_steps.h"

#include "atom.h"
#include "fix.h"

#include <algorithm>
#include <cmath>

using namespace LAMMPS_NS;

namespace SPHAstro {

void IndividualSteps::split_long_range(double displacement, double force_factor)
{
  long_range_ = true;
  long_displacement_ = displacement;
  long_force_factor_ = force_factor;
}

void IndividualSteps::long_range_before()
{
  const int nlocal = atom->nlocal;
  f_before_.resize(3 * static_cast<std::size_t>(nlocal));
  if (nlocal > 0) std::copy_n(atom->f[0], 3 * nlocal, f_before_.begin());
}

void IndividualSteps::long_range_after(double split_scale)
{
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  double **f = atom->f;
  double **along = atom->darray[accel_long_];
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & owner_->groupbit)) continue;
    const double m = mass(i);
    for (int d = 0; d < 3; d++) along[i][d] = (f[i][d] - f_before_[3 * i + d]) / m;
  }
  long_split_ = split_scale;
  long_evaluations_ += 1.0;
}

void IndividualSteps::long_range_discard()
{
  const int nlocal = atom->nlocal;
  if (nlocal > 0) std::copy_n(f_before_.begin(), 3 * nlocal, atom->f[0]);
}

// dt_long = min(C_d r_s / max|v|, C_f r_s^(1/2) / max|a_long|^(1/2)): in one interval no
// particle moves more than C_d r_s, across which the long-range field is smooth (as GADGET-2
// bounds the particles' rms displacement in a PM step against its split scale), and its
// long-range acceleration changes its velocity by at most C_f (r_s |a_long|)^(1/2)
double IndividualSteps::long_range_step() const
{
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  double **v = atom->v;
  double **along = atom->darray[accel_long_];
  double local[2] = {0.0, 0.0}, all[2];    // the largest |v|^2 and |a_long|^2
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & owner_->groupbit)) continue;
    local[0] = std::max(local[0], v[i][0] * v[i][0] + v[i][1] * v[i][1] + v[i][2] * v[i][2]);
    local[1] =
        std::max(local[1],
                 along[i][0] * along[i][0] + along[i][1] * along[i][1] + along[i][2] * along[i][2]);
  }
  MPI_Allreduce(local, all, 2, MPI_DOUBLE, MPI_MAX, world);
  if (!(long_split_ > 0.0)) return INFINITY;
  double dt = INFINITY;
  if (all[0] > 0.0) dt = long_displacement_ * long_split_ / std::sqrt(all[0]);
  if (all[1] > 0.0)
    dt = std::min(dt, long_force_factor_ * std::sqrt(long_split_ / std::sqrt(all[1])));
  return dt;
}

// the earliest begin and the latest end of a particle step, in ticks (collective; +inf and
// -inf for an empty group)
void IndividualSteps::interval_ticks(double &first_begin, double &last_end) const
{
  const int *mask = atom->mask;
  const double *begin = atom->dvector[idx_.begin];
  const double *end = atom->dvector[idx_.end];
  double local[2] = {-INFINITY, -INFINITY}, all[2];    // the latest end, - the earliest begin
  for (int i = 0; i < atom->nlocal; i++)
    if (mask[i] & owner_->groupbit) {
      local[0] = std::max(local[0], end[i]);
      local[1] = std::max(local[1], -begin[i]);
    }
  MPI_Allreduce(local, all, 2, MPI_DOUBLE, MPI_MAX, world);
  last_end = all[0];
  first_begin = -all[1];
}

// the interval between synchronisation points that holds this LAMMPS step runs from the
// earliest begin of a particle step to the latest end (the longest steps'); where every
// particle begins its step (the first step of a hierarchy, or after a synchronisation point),
// it opens: v += a_long Delta / 2
void IndividualSteps::long_range_interval()
{
  double first, last;
  interval_ticks(first, last);
  long_middle_ = 0.5 * (first + last);
  if (!std::isfinite(last) || first != ti_now_) return;
  const double half = 0.5 * (last - ti_now_) * tick();
  const int *mask = atom->mask;
  double **v = atom->v;
  double **along = atom->darray[accel_long_];
  for (int i = 0; i < atom->nlocal; i++)
    if (mask[i] & owner_->groupbit)
      for (int d = 0; d < 3; d++) v[i][d] += half * along[i][d];
}

// a wake of the limiter may end the interval earlier: when it shortened the longest steps, the
// interval's opening kick and the drift since take the shorter interval,
// v += a_long (T_new - T_old) / 2 and x += a_long (T_new - T_old) / 2 (t - t_begin)
void IndividualSteps::long_range_woken(double last_end_before)
{
  double first, after;
  interval_ticks(first, after);
  if (!(after < last_end_before) || !std::isfinite(first)) return;
  const double t = tick();
  const double dv = 0.5 * (after - last_end_before) * t, dx = dv * (ti_now_ - first) * t;
  const int *mask = atom->mask;
  double **x = atom->x;
  double **v = atom->v;
  double **along = atom->darray[accel_long_];
  for (int i = 0; i < atom->nlocal; i++)
    if (mask[i] & owner_->groupbit)
      for (int d = 0; d < 3; d++) {
        v[i][d] += dv * along[i][d];
        x[i][d] += dx * along[i][d];
      }
}

}    // namespace SPHAstro
