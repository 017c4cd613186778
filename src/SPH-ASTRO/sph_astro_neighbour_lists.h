/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The neighbour lists the passes of pair sph/astro walk: LAMMPS' lists, or those lists pruned
// to the kernel supports at each list build (keyword prune, sph_astro_pruned_list.h). With
// grad-h terms and prune yes, LAMMPS gives only the full list; the half list is made from it
// by LAMMPS' own half-from-full rule in the scan that prunes it.

#ifndef LMP_SPH_ASTRO_NEIGHBOUR_LISTS_H
#define LMP_SPH_ASTRO_NEIGHBOUR_LISTS_H

#include "pointers.h"
#include "sph_astro_pruned_list.h"

#include <vector>

namespace SPHAstro {

class NeighbourLists : protected LAMMPS_NS::Pointers {
 public:
  explicit NeighbourLists(LAMMPS_NS::LAMMPS *lmp) : Pointers(lmp) {}
  ~NeighbourLists() override;

  // LAMMPS' lists of this run: half (null with grad-h and prune), full (null without grad-h)
  void set_lammps_lists(LAMMPS_NS::NeighList *half, LAMMPS_NS::NeighList *full);
  LAMMPS_NS::NeighList *lammps_half() const { return lammps_half_; }
  LAMMPS_NS::NeighList *lammps_full() const { return lammps_full_; }

  // at a LAMMPS list build: prune to r_ij < R max(hl_i, hl_j) + skin (half list) and
  // r_ij < R hl_i + skin (full list), hl = min(growth h, the type's cap) (owned + ghost)
  void prune(const double *h, const double *hcap_type, double growth, double kernel_radius);
  // prune no
  void clear();

  // the pruned half list if it covers every h (owned + ghost), else LAMMPS' (or the half
  // list made from LAMMPS' full list by its rule)
  NeighView half(const double *h);
  // the full list of the h iteration (pruned where built), the largest h each row serves
  // (null: any) and LAMMPS' full list for rows whose h goes past it
  NeighView full() const;
  const double *full_limits() const { return pruned_full_.built() ? hprune_ : nullptr; }
  // the largest h atom i may take before the passes fall back to LAMMPS' lists
  double limit(int i) const;
  bool pruned() const { return pruned_half_.built(); }

  // force evaluations whose half list did not cover every h (they used LAMMPS' lists)
  LAMMPS_NS::bigint fallbacks() const { return fallbacks_; }
  // entries per atom of the latest pruned half and full list (0: none)
  double *lengths() { return lengths_; }
  double memory_usage() const;

 private:
  LAMMPS_NS::NeighList *lammps_half_ = nullptr, *lammps_full_ = nullptr;
  PrunedList pruned_half_, pruned_full_;
  PrunedList fallback_half_;                // grad-h with prune: unpruned half list, on demand
  std::vector<unsigned char> half_keep_;    // per full-list entry: in LAMMPS' half list
  double *hprune_ = nullptr;                // hl of owned and ghost atoms at the build
  int nmax_ = 0;
  LAMMPS_NS::bigint fallbacks_ = 0;
  double lengths_[2] = {0.0, 0.0};

  NeighView unpruned_half();
  HalfFromFull half_from_full() const;
  bool nothing_to_prune(double kernel_radius) const;
  void begin(PrunedList &list, const LAMMPS_NS::NeighList *src);
  int *row(PrunedList &list, int i);
};

}    // namespace SPHAstro

#endif
