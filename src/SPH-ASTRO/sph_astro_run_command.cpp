/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: the sph/astro/run command
------------------------------------------------------------------------- */

// sph/astro/run N [upto]
//
// Runs "run TARGET upto" (TARGET = N with upto, else the current step + N) and, as long as
// fix sph/astro/h with the rebuild keyword ended that run early for a neighbour-list rebuild,
// runs it again: every run sets the pair cutoffs anew from the current smoothing lengths
// (pair sph/astro: margin x the largest h of each type). It stops at TARGET, when a run ends
// for any other reason (fix sph/astro tend, a timeout, fix halt), or after 20 runs in a row that
// ended at their setup.

#include "sph_astro_run_command.h"

#include "comm.h"
#include "error.h"
#include "fix_sph_astro_h.h"
#include "input.h"
#include "modify.h"
#include "update.h"
#include "utils.h"

#include <cstring>

using namespace LAMMPS_NS;

void SPHAstroRunCommand::command(int narg, char **arg)
{
  if (narg < 1 || narg > 2)
    error->all(FLERR, "sph/astro/run takes N [upto] (got {} arguments)", narg);
  const bigint n = utils::bnumeric(FLERR, arg[0], false, lmp);
  bool upto = false;
  if (narg == 2) {
    if (strcmp(arg[1], "upto") != 0)
      error->all(FLERR, "sph/astro/run: unknown keyword '{}'; allowed: upto", arg[1]);
    upto = true;
  }
  if (n < 0) error->all(FLERR, "sph/astro/run: N = {} must be >= 0", n);
  const bigint target = upto ? n : update->ntimestep + n;
  if (target < update->ntimestep)
    error->all(FLERR, "sph/astro/run: step {} (upto) is before the current step {}", target,
               update->ntimestep);

  int runs = 0, idle = 0;
  while (true) {
    const bigint start = update->ntimestep;
    input->one(fmt::format("run {} upto", target));
    runs++;
    auto hfixes = modify->get_fix_by_style("^sph/astro/h$");
    auto *hfix = hfixes.empty() ? nullptr : dynamic_cast<FixSPHAstroH *>(hfixes.front());
    if (!hfix || !hfix->rebuild_requested()) break;
    hfix->clear_rebuild_request();
    if (update->ntimestep >= target) break;
    // a run may end at its setup (h far beyond the caps there); each new run raises the caps
    // to margin x the capped h, so a few such runs reach any h
    if (update->ntimestep == start && ++idle > 20)
      error->all(FLERR,
                 "sph/astro/run: 20 runs from step {} ended for a neighbour-list rebuild without "
                 "a single step (h grows without bound?)",
                 start);
    if (update->ntimestep > start) idle = 0;
    if (comm->me == 0)
      utils::logmesg(lmp, "sph/astro/run: continuing from step {} with rebuilt neighbour lists\n",
                     update->ntimestep);
  }
  if (comm->me == 0 && runs > 1)
    utils::logmesg(lmp, "sph/astro/run: {} runs, {} neighbour-list cutoff rebuilds\n", runs,
                   runs - 1);
}
