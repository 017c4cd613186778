/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Compute sph/astro/sink: a global array of the sinks of a fix sph/astro/sink, one row per sink
// in ID order, columns
//   1 ID, 2 mass M, 3-5 spin S (angular momentum about the sink's centre of mass, the accreted
//   gas's: Bate, Bonnell & Price 1995, MNRAS 277, 362, sec. 2.2), 6 accreted mass M_acc,
//   7 accretion rate dM_acc/dt = (M_acc(t) - M_acc(t_prev)) / (t - t_prev) since the compute's
//   previous evaluation (0 at a sink's first)

#include "compute_sph_astro_sink.h"

#include "fix_sph_astro_sink.h"

#include "error.h"
#include "memory.h"
#include "modify.h"
#include "update.h"

using namespace LAMMPS_NS;

ComputeSPHAstroSink::ComputeSPHAstroSink(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg)
{
  if (narg != 4)
    error->all(FLERR,
               "compute sph/astro/sink takes one argument, the ID of a fix sph/astro/sink (got {})",
               narg - 3);
  fix_id_ = arg[3];
  array_flag = 1;
  size_array_cols = 7;
  size_array_rows = 0;
  size_array_rows_variable = 1;
  extarray = 0;
}

ComputeSPHAstroSink::~ComputeSPHAstroSink()
{
  memory->destroy(array);
}

void ComputeSPHAstroSink::init()
{
  Fix *fix = modify->get_fix_by_id(fix_id_);
  if (!fix) error->all(FLERR, "compute sph/astro/sink: no fix with ID {}", fix_id_);
  fix_ = dynamic_cast<FixSPHAstroSink *>(fix);
  if (!fix_)
    error->all(FLERR, "compute sph/astro/sink: fix {} is a fix {}, not sph/astro/sink", fix_id_,
               fix->style);
}

void ComputeSPHAstroSink::compute_array()
{
  invoked_array = update->ntimestep;
  if (!fix_) init();    // (evaluated before the first run)
  const auto &sinks = fix_->gather_sinks();
  const int n = static_cast<int>(sinks.size());
  if (n != nrows_ || !array) {
    memory->destroy(array);
    nrows_ = n;
    memory->create(array, n > 0 ? n : 1, size_array_cols, "sph/astro/sink:array");
  }
  size_array_rows = n;
  const double now = update->atime + (update->ntimestep - update->atimestep) * update->dt;
  for (int k = 0; k < n; k++) {
    const auto &s = sinks[k];
    double rate = 0.0;
    auto it = previous_.find(s.tag);
    if (it != previous_.end()) {
      Sample &p = it->second;
      if (now > p.time) {
        rate = (s.macc - p.macc) / (now - p.time);
        p = {now, s.macc, rate};
      } else
        rate = p.rate;    // evaluated again at the same time
    } else
      previous_[s.tag] = {now, s.macc, 0.0};
    double *row = array[k];
    row[0] = static_cast<double>(s.tag);
    row[1] = s.m;
    row[2] = s.spin[0];
    row[3] = s.spin[1];
    row[4] = s.spin[2];
    row[5] = s.macc;
    row[6] = rate;
  }
}

double ComputeSPHAstroSink::memory_usage()
{
  return static_cast<double>(nrows_) * size_array_cols * sizeof(double) +
      previous_.size() * (sizeof(tagint) + sizeof(Sample));
}
