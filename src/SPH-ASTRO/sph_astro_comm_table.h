/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// What one communication stage of pair sph/astro sends: a table of per-atom arrays (scalar or
// ncol columns). Forward: owned -> ghost copies; reverse: the ghosts' parts are summed into
// the owners (or the larger value kept: max). Null arrays are left out, so a stage names every
// array it may send and the scene's options decide which exist.
// A sparse stage sends only the atoms marked in chosen (per owned and ghost atom): a message is
// the count of its atoms, then each atom's position k in LAMMPS' list or range and its values;
// a message over no atoms is empty (comm_style tiled sends what pack returns). The marks must
// hold on every rank for the atoms whose values it needs and their sources (the owners, and the
// ghosts that a later swap passes on).

#ifndef LMP_SPH_ASTRO_COMM_TABLE_H
#define LMP_SPH_ASTRO_COMM_TABLE_H

#include "sph_astro_sparse_message.h"

#include <initializer_list>

namespace SPHAstro {

// one array of a stage
struct CommField {
  double *scalar;
  double **vector;
  int ncol;
  bool max;                 // reverse: keep the larger value instead of the sum
  bool velocity = false;    // forward: a velocity (fix deform remap v shifts it across boundaries)
};

class CommTable {
 public:
  using Field = CommField;
  static constexpr int MAX_FIELDS = 16;

  // the fields of the next stage; returns the values per atom it sends, or -1 for more than
  // MAX_FIELDS arrays
  int set(std::initializer_list<Field> fields, const char *chosen = nullptr)
  {
    chosen_ = chosen;
    n_ = 0;
    size_ = 0;
    for (const Field &field : fields)
      if (field.scalar || field.vector) {
        if (n_ == MAX_FIELDS) return -1;
        fields_[n_++] = field;
        size_ += field.ncol;
      }
    return size_;
  }

  // the buffer holds the fields one after the other (each for all n atoms); dv: the velocity
  // shift of the atoms with (mask & groupbit) across this boundary, or nullptr (as LAMMPS'
  // AtomVec::pack_comm_vel() with fix deform remap v)
  int pack(int n, const int *list, double *buf, const double *dv = nullptr,
           const int *mask = nullptr, int groupbit = 0) const
  {
    if (chosen_) return pack_chosen(n, list, buf, dv, mask, groupbit);
    int m = 0;
    for (int c = 0; c < n_; c++) {
      const Field &f = fields_[c];
      if (f.scalar)
        for (int k = 0; k < n; k++) buf[m++] = f.scalar[list[k]];
      else if (dv && f.velocity)
        for (int k = 0; k < n; k++) {
          const bool shift = (mask[list[k]] & groupbit) != 0;
          for (int d = 0; d < 3; d++) buf[m++] = f.vector[list[k]][d] + (shift ? dv[d] : 0.0);
        }
      else
        for (int k = 0; k < n; k++)
          for (int d = 0; d < f.ncol; d++) buf[m++] = f.vector[list[k]][d];
    }
    return m;
  }
  int pack_range(int first, int n, double *buf) const
  {
    if (chosen_) return pack_range_chosen(first, n, buf);
    int m = 0;
    for (int c = 0; c < n_; c++) {
      const Field &f = fields_[c];
      if (f.scalar)
        for (int i = first; i < first + n; i++) buf[m++] = f.scalar[i];
      else
        for (int i = first; i < first + n; i++)
          for (int d = 0; d < f.ncol; d++) buf[m++] = f.vector[i][d];
    }
    return m;
  }
  void unpack_range(int first, int n, const double *buf) const
  {
    if (chosen_) {
      unpack_sparse(n, size_, buf, [&](int k, const double *in) {
        get(first + k, in);
      });
      return;
    }
    int m = 0;
    for (int c = 0; c < n_; c++) {
      const Field &f = fields_[c];
      if (f.scalar)
        for (int i = first; i < first + n; i++) f.scalar[i] = buf[m++];
      else
        for (int i = first; i < first + n; i++)
          for (int d = 0; d < f.ncol; d++) f.vector[i][d] = buf[m++];
    }
  }
  void accumulate(int n, const int *list, const double *buf) const
  {
    if (chosen_) {
      unpack_sparse(n, size_, buf, [&](int k, const double *in) {
        const int i = list[k];
        for (int c = 0; c < n_; c++) {
          add(fields_[c], i, in);
          in += fields_[c].ncol;
        }
      });
      return;
    }
    int m = 0;
    for (int c = 0; c < n_; c++) {
      const Field &f = fields_[c];
      if (f.scalar && f.max)
        for (int k = 0; k < n; k++, m++) {
          double &value = f.scalar[list[k]];
          if (buf[m] > value) value = buf[m];
        }
      else if (f.scalar)
        for (int k = 0; k < n; k++) f.scalar[list[k]] += buf[m++];
      else
        for (int k = 0; k < n; k++)
          for (int d = 0; d < f.ncol; d++) f.vector[list[k]][d] += buf[m++];
    }
  }

 private:
  Field fields_[MAX_FIELDS];
  int n_ = 0, size_ = 0;
  const char *chosen_ = nullptr;    // a sparse stage: the atoms it sends

  static void add(const Field &f, int i, const double *in)
  {
    if (f.scalar && f.max) {
      if (in[0] > f.scalar[i]) f.scalar[i] = in[0];
    } else if (f.scalar)
      f.scalar[i] += in[0];
    else
      for (int d = 0; d < f.ncol; d++) f.vector[i][d] += in[d];
  }
  // one atom's values of the stage, one field after the other (put: with the velocity shift)
  void put(int i, double *out, const double *dv) const
  {
    for (int c = 0; c < n_; c++) {
      const Field &f = fields_[c];
      if (f.scalar)
        *out++ = f.scalar[i];
      else
        for (int d = 0; d < f.ncol; d++) *out++ = f.vector[i][d] + (dv && f.velocity ? dv[d] : 0.0);
    }
  }
  void get(int i, const double *in) const
  {
    for (int c = 0; c < n_; c++) {
      const Field &f = fields_[c];
      if (f.scalar)
        f.scalar[i] = *in++;
      else
        for (int d = 0; d < f.ncol; d++) f.vector[i][d] = *in++;
    }
  }
  int pack_chosen(int n, const int *list, double *buf, const double *dv, const int *mask,
                  int groupbit) const
  {
    return pack_sparse(
        n, size_, buf,
        [&](int k) {
          return chosen_[list[k]] != 0;
        },
        [&](int k, double *out) {
          const int i = list[k];
          put(i, out, dv && (mask[i] & groupbit) ? dv : nullptr);
        });
  }
  int pack_range_chosen(int first, int n, double *buf) const
  {
    return pack_sparse(
        n, size_, buf,
        [&](int k) {
          return chosen_[first + k] != 0;
        },
        [&](int k, double *out) {
          put(first + k, out, nullptr);
        });
  }
};

}    // namespace SPHAstro

#endif
