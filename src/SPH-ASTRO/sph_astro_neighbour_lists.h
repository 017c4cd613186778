/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// The neighbour lists of pair sph/astro, made by the package's own search over LAMMPS' owned
// and ghost atoms (sph_astro_neighbour_tree.h); LAMMPS still decomposes the domain, exchanges
// atoms, makes the ghosts and decides when atoms have moved too far (neighbor skin).
//
// With hl_i = min(growth h_i, h_cap) the largest h the lists serve (growth 1 with fixed h),
// R the kernel's support radius and pad the skin, the lists hold for each owned SPH atom i
//   half list:  j with r_ij < R max(hl_i, hl_j) + pad, each pair once (LAMMPS' half-list rule
//               for newton on and off, sph_astro_neigh_view.h)
//   full list:  j with r_ij < R hl_i + pad (the gather rows of the h-rho iteration; grad-h only)
// They are made when LAMMPS has built its neighbour structures (reneighbouring: no atom has
// moved more than skin/2 since, pad = skin). When h outgrows hl inside a step (pad = 2 skin:
// atoms have moved up to skin/2 before and up to skin/2 after, relative to LAMMPS' last
// build), the lists are extended: the grown atoms get hl = growth h, and the pairs their wider
// reach finds are added to the rows that hold them by the half rule at the build's positions
// (as the build decided, on every rank alike); when more than EXTEND_LIMIT of the atoms grew,
// they are made anew instead. While every h <= hl, every pair inside a kernel support is in the lists,
// so each sum over them is the sum over all particles. h_cap follows LAMMPS' ghost cutoff:
// (cutoff - skin) / R, the largest support inside which all particles are owned or ghosts.
//
// Individual timesteps with newton on (SearchSettings::active_only): a step evaluates only the
// pairs with an active atom, and most atoms are active in few of the intervals between LAMMPS'
// builds. The build then makes the tree only; the rows of a tree leaf are made the first time
// one of its owned atoms is active, from the positions and pad of the build (the same pairs an
// eager build finds, with the radii of the extensions since). These reach rows hold both
// directions of a pair, j with r_ij < R max(hl_i, hl_j) + pad, and a step's pairs are taken
// from its active atoms' rows: (i, j) with i active is evaluated in i's row when j is inactive,
// and by the half rule when both are active (i < j for owned j; for a ghost j the rule at the
// current positions, which both ranks hold alike and by which j's owner decides the reverse).
// Each pair is then evaluated once on one rank, and with every atom active at the build the
// pairs and their order are those of the half list. With newton off a rank must also evaluate
// its inactive atoms' pairs with active ghosts, so the lists are made whole and the due pairs
// selected from the half list (DuePairs).

#ifndef LMP_SPH_ASTRO_NEIGHBOUR_LISTS_H
#define LMP_SPH_ASTRO_NEIGHBOUR_LISTS_H

#include "pointers.h"
#include "sph_astro_due_pairs.h"
#include "sph_astro_neigh_view.h"
#include "sph_astro_neighbour_tree.h"
#include "sph_astro_wide_rows.h"

#include <memory>
#include <utility>
#include <vector>

namespace SPHAstro {

// rows of ints in chunks that never move once written: memory grows with the entries kept
class RowStore {
 public:
  void reset();
  int *append(const int *row, int n);
  std::size_t entries() const { return entries_; }
  double memory_usage() const;

 private:
  static constexpr std::size_t CHUNK = 1 << 16;
  std::vector<std::unique_ptr<int[]>> chunks_;
  std::vector<std::size_t> sizes_;
  std::size_t current_ = 0, used_ = 0, entries_ = 0;
};

// one list: rows of the atoms ilist[0..inum)
struct SearchList {
  std::vector<int> numneigh;
  std::vector<int *> firstneigh;
  RowStore rows;
  NeighView view(int inum, const int *ilist) const
  {
    return {inum, ilist, numneigh.data(), firstneigh.data()};
  }
};

struct SearchSettings {
  double kernel_radius;    // R
  double growth;           // hl = growth h (1 with fixed h)
  double h_cap;            // hl <= h_cap
  bool full;               // gather rows of the h-rho iteration
  bool newton;
  const int *sph_type;         // per type: 1 if the pair style acts on it
  bool active_only = false;    // individual steps: rows only where an atom is active (newton on)
};

struct SearchStatistics {
  LAMMPS_NS::bigint builds = 0;             // list builds after LAMMPS' builds
  LAMMPS_NS::bigint step_builds = 0;        // builds inside a step because many h outgrew the lists
  LAMMPS_NS::bigint extensions = 0;         // lists extended inside a step for the h that grew
  LAMMPS_NS::bigint extended_atoms = 0;     // atoms whose hl grew in the extensions
  LAMMPS_NS::bigint extension_pairs = 0;    // pairs the extensions added to the half list
  LAMMPS_NS::bigint wide_rows = 0;          // h iterations that went past their row's limit
  double half_entries = 0.0, full_entries = 0.0;    // per atom, latest build (this rank)
  int atoms = 0;                                    // owned SPH atoms, latest build
  // active_only: rows made (reach rows, both directions of each pair) and the rows an eager
  // build would have made (atoms x builds); reach_entries and full_entries per made row since
  // the latest build (extensions included)
  LAMMPS_NS::bigint rows_made = 0, rows_eager = 0;
  double reach_entries = 0.0;
};

class NeighbourLists : protected LAMMPS_NS::Pointers {
 public:
  explicit NeighbourLists(LAMMPS_NS::LAMMPS *lmp) : Pointers(lmp) {}

  // make the lists after LAMMPS' build if not yet made for it
  void update(const double *h, const SearchSettings &s);
  // a run begins (its setup rebuilds LAMMPS' structures, possibly at the same step)
  void invalidate() { stale_ = true; }
  // the half list (not with active_only), extended (or made again) first if an h (owned or
  // ghost) outgrew its hl; collective: every rank decides alike
  NeighView half(const double *h);
  static constexpr double EXTEND_LIMIT =
      0.1;    // share of grown atoms above which lists are made anew
  // the gather rows; with active_only, of the atoms prepare() was given
  NeighView full() const { return full_.view(inum_, ilist_.data()); }
  // individual steps: the rows of the active atoms (owned and ghost flags) made, if not yet
  void prepare(const char *active);
  // individual steps: the pairs with an active atom, each once, after the extension half()
  // makes (collective)
  NeighView due(const double *h, const char *active);
  // the largest h each row serves (owned and ghost)
  const double *limits() const { return hl_.data(); }

  // every j with r_ij < R h_row, h_row = min(1.5 h, h_cap) (the rows of an h iteration past
  // its list's limit; WideRows)
  const int *row(int i, double h, double &h_row, int &n);
  WideRows *wide_rows() { return &wide_; }

  const SearchStatistics &statistics() const { return stats_; }
  double memory_usage() const;

 private:
  bool built_ = false;
  bool stale_ = true;
  LAMMPS_NS::bigint build_step_ = -1;    // the step of the latest build after LAMMPS'
  SearchSettings settings_{};
  double motion_ = 0.0;    // how far atoms may be from where the tree saw them
  NeighbourTree tree_;
  std::vector<double> hl_, radius_;
  std::vector<int> ilist_, members_, scratch_, full_scratch_;
  int inum_ = 0;
  SearchList half_, full_;    // half_: the half rows, or with active_only the reach rows
  SearchStatistics stats_;
  DuePairs due_;
  bool due_indexed_ = false;    // due_ holds the index of the current half list
  bool active_only_ = false;    // the lists were made with active_only
  double pad_ = 0.0;            // the pad of the latest build (rows made later use it)
  LAMMPS_NS::bigint rows_since_build_ = 0;
  std::vector<char> leaf_made_;    // per tree leaf: its owned atoms' rows are made
  std::vector<int> leaf_of_;       // per owned SPH atom: its tree leaf
  std::vector<int> due_ilist_, due_numneigh_, due_entries_;
  std::vector<int *> due_firstneigh_;
  struct Wide : WideRows {
    NeighbourLists *lists;
    explicit Wide(NeighbourLists *l) : lists(l) {}
    const int *row(int i, double h, double &h_row, int &n) override
    {
      return lists->row(i, h, h_row, n);
    }
  } wide_{this};

  void build(const double *h, double pad);
  // the rows of the owned atoms of tree leaf l (half or reach rows, and gather rows)
  void make_leaf_rows(int l);
  // the extension or new build when an h outgrew its hl (collective)
  void follow_growth(const double *h);
  void extend(const double *h, double pad);
  bool row_made(int i) const { return !active_only_ || leaf_made_[leaf_of_[i]]; }
  // active_only: the due pairs from the reach rows of the active atoms
  NeighView due_from_reach_rows(const char *active);
  // the owned atom whose half-list row holds pair (a, b) by the half rule at the build's
  // positions, and its partner; false if no row on this rank holds it
  bool row_of_pair(int a, int b, int &row, int &partner) const;
  HalfFromFull half_rule_{0, false, false, 0.0};
  std::vector<int> grown_;
  std::vector<std::pair<int, int>> inserts_;
  std::vector<int> merged_;
};

}    // namespace SPHAstro

#endif
