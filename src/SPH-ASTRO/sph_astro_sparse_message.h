/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// A sparse message of LAMMPS' forward or reverse communication over n atoms (a swap's list or
// range): the count of the chosen atoms, then each one's position k in the list or range and
// its width values. Nothing at all for n = 0: comm_style tiled sends what pack returns, and
// its receiver expects n x size. A message holds at most 1 + n (width + 1) values, so the
// size passed to LAMMPS is width + 2.

#ifndef LMP_SPH_ASTRO_SPARSE_MESSAGE_H
#define LMP_SPH_ASTRO_SPARSE_MESSAGE_H

namespace SPHAstro {

// chosen(k): is atom k sent; values(k, out) writes its width values; returns the message size
template <class CHOSEN, class VALUES>
int pack_sparse(int n, int width, double *buf, CHOSEN &&chosen, VALUES &&values)
{
  if (n == 0) return 0;
  double *out = buf + 1;
  for (int k = 0; k < n; k++) {
    if (!chosen(k)) continue;
    *out++ = k;
    values(k, out);
    out += width;
  }
  buf[0] = static_cast<double>((out - buf - 1) / (width + 1));
  return static_cast<int>(out - buf);
}

// take(k, in) reads the width values of the atom at position k
template <class TAKE> void unpack_sparse(int n, int width, const double *buf, TAKE &&take)
{
  if (n == 0) return;
  const int count = static_cast<int>(buf[0]);
  const double *in = buf + 1;
  for (int e = 0; e < count; e++, in += width + 1) take(static_cast<int>(in[0]), in + 1);
}

}    // namespace SPHAstro

#endif
