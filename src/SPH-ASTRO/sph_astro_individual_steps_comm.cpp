/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Individual timesteps (sph_astro_individual_steps.h): the communication stages of the
// hierarchy, forward (step times, active flags, changed bins to the ghosts) and reverse (the
// pair kicks' sums of the ghosts in a pair, and the bins their neighbours require of the
// owners, for the limiter).

#include "sph_astro_individual_steps.h"

#include "sph_astro_sparse_message.h"

#include "atom.h"

#include <algorithm>
#include <cmath>

using namespace LAMMPS_NS;

namespace SPHAstro {

int IndividualSteps::pack_forward_comm(int n, int *list, double *buf)
{
  switch (comm_) {
    case Comm::TIMES:
      for (int k = 0; k < n; k++)
        for (int c = 0; c < NTIMES; c++) buf[NTIMES * k + c] = times_[NTIMES * list[k] + c];
      return NTIMES * n;
    case Comm::TIMES_CHANGED:
      return pack_sparse(
          n, NTIMES, buf,
          [&](int k) {
            return times_changed_[list[k]] != 0;
          },
          [&](int k, double *out) {
            std::copy_n(&times_[NTIMES * list[k]], NTIMES, out);
          });
    case Comm::ACTIVE:
      return pack_sparse(
          n, 0, buf,
          [&](int k) {
            return active_[list[k]] != 0;
          },
          [](int, double *) {
          });
    case Comm::BINS_CHANGED:
      return pack_sparse(
          n, 1, buf,
          [&](int k) {
            return bins_changed_[list[k]] != 0;
          },
          [&](int k, double *out) {
            *out = bins_[list[k]];
          });
    default:
      for (int k = 0; k < n; k++) buf[k] = bins_[list[k]];
      return n;
  }
}

void IndividualSteps::unpack_forward_comm(int n, int first, const double *buf)
{
  switch (comm_) {
    case Comm::TIMES:
      std::copy_n(buf, NTIMES * n, &times_[NTIMES * first]);
      return;
    case Comm::TIMES_CHANGED:
      unpack_sparse(n, NTIMES, buf, [&](int k, const double *in) {
        std::copy_n(in, NTIMES, &times_[NTIMES * (first + k)]);
        times_changed_[first + k] = 1;    // (a ghost that a later swap passes on)
      });
      return;
    case Comm::ACTIVE:
      std::fill_n(active_.begin() + first, n, 0);
      unpack_sparse(n, 0, buf, [&](int k, const double *) {
        active_[first + k] = 1;
      });
      return;
    case Comm::BINS_CHANGED:
      unpack_sparse(n, 1, buf, [&](int k, const double *in) {
        bins_[first + k] = *in;
        bins_changed_[first + k] = 1;    // (a ghost that a later swap passes on)
      });
      return;
    default:
      for (int k = 0; k < n; k++) bins_[first + k] = buf[k];
  }
}

int IndividualSteps::pack_reverse_comm(int n, int first, double *buf)
{
  if (comm_ == Comm::SUMS) {    // the ghosts with pairs only: k + n (0, or 1 with the extra)
    if (n == 0) return 0;       // (sph_astro_sparse_message.h)
    double *out = buf + 1;
    int count = 0;
    for (int k = 0; k < n; k++) {
      const int i = first + k;
      if (!touched_mark_[i]) continue;
      *out++ = k + (extra_at_[i] >= 0 ? n : 0);
      out = std::copy_n(&sums_[SUM_STRIDE * static_cast<std::size_t>(i)], nsum_, out);
      if (extra_at_[i] >= 0) out = std::copy_n(extra_sums(i), extra_width_, out);
      count++;
    }
    buf[0] = count;
    return static_cast<int>(out - buf);
  }
  return pack_sparse(    // REQUIRED: the ghosts in a pair (a bin, not the -1 of none)
      n, 1, buf,
      [&](int k) {
        return required_[first + k] >= 0.0;
      },
      [&](int k, double *out) {
        *out = required_[first + k];
      });
}

void IndividualSteps::unpack_reverse_comm(int n, const int *list, const double *buf)
{
  if (comm_ == Comm::SUMS) {
    if (n == 0) return;
    const int nlocal = atom->nlocal;
    const int count = static_cast<int>(buf[0]);
    const double *in = buf + 1;
    for (int e = 0; e < count; e++) {
      int k = static_cast<int>(*in++);
      const bool extra = k >= n;
      if (extra) k -= n;
      const int i = list[k];
      double *sum = &sums_[SUM_STRIDE * static_cast<std::size_t>(i)];
      for (int c = 0; c < nsum_; c++) sum[c] += *in++;
      touch(i, nlocal);    // (a ghost that a later swap passes on)
      if (!extra) continue;
      double *ext = extra_of(i);
      for (int c = 0; c < extra_width_; c++) {
        // (a pending slot's close is the same time from every part, or 0)
        if (opening_ && c % 4 == 3)
          ext[c] = std::max(ext[c], in[c]);
        else
          ext[c] += in[c];
      }
      in += extra_width_;
    }
    return;
  }
  unpack_sparse(n, 1, buf, [&](int k, const double *in) {
    required_[list[k]] = std::max(required_[list[k]], *in);
  });
}

}    // namespace SPHAstro
