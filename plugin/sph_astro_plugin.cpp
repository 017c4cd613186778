/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO plugin entry point: registers the package's styles with LAMMPS.
   Built by cmake/CMakeLists.txt against an installed LAMMPS; the package
   built into LAMMPS (-D PKG_SPH-ASTRO=on) does not use this file.
------------------------------------------------------------------------- */

#include "lammpsplugin.h"
#include "sph_astro_plugin_sizes.h"
#include "version.h"

#include "compute_sph_astro_atom.h"
#include "compute_sph_astro_global.h"
#include "compute_sph_astro_sink.h"
#include "compute_sph_astro_gravity_direct.h"
#include "fix_sph_astro.h"
#include "fix_sph_astro_h.h"
#include "fix_sph_astro_owned.h"
#include "fix_sph_astro_sink.h"
#include "fix_sph_astro_snapshot.h"
#include "fix_sph_astro_switch.h"
#include "msm_sph_astro_gravity.h"
#include "pair_sph_astro.h"
#include "pair_sph_astro_gravity.h"
#include "pppm_sph_astro_gravity.h"
#include "sph_astro_state_command.h"
#include "tree_sph_astro_gravity.h"

using namespace LAMMPS_NS;

static Pair *pair_sph_astro_creator(LAMMPS *lmp)
{
  return new PairSPHAstro(lmp);
}

static Pair *pair_sph_astro_gravity_creator(LAMMPS *lmp)
{
  return new PairSPHAstroGravity(lmp);
}

static KSpace *pppm_sph_astro_gravity_creator(LAMMPS *lmp)
{
  return new PPPMSPHAstroGravity(lmp);
}

static KSpace *msm_sph_astro_gravity_creator(LAMMPS *lmp)
{
  return new MSMSPHAstroGravity(lmp);
}

static KSpace *tree_sph_astro_gravity_creator(LAMMPS *lmp)
{
  return new TreeSPHAstroGravity(lmp);
}

static Compute *compute_sph_astro_gravity_direct_creator(LAMMPS *lmp, int narg, char **arg)
{
  return new ComputeSPHAstroGravityDirect(lmp, narg, arg);
}

static Fix *fix_sph_astro_creator(LAMMPS *lmp, int narg, char **arg)
{
  return new FixSPHAstro(lmp, narg, arg);
}

static Fix *fix_sph_astro_h_creator(LAMMPS *lmp, int narg, char **arg)
{
  return new FixSPHAstroH(lmp, narg, arg);
}

static Fix *fix_sph_astro_owned_creator(LAMMPS *lmp, int narg, char **arg)
{
  return new FixSPHAstroOwned(lmp, narg, arg);
}

static Fix *fix_sph_astro_sink_creator(LAMMPS *lmp, int narg, char **arg)
{
  return new FixSPHAstroSink(lmp, narg, arg);
}

static Compute *compute_sph_astro_sink_creator(LAMMPS *lmp, int narg, char **arg)
{
  return new ComputeSPHAstroSink(lmp, narg, arg);
}

static Fix *fix_sph_astro_switch_creator(LAMMPS *lmp, int narg, char **arg)
{
  return new FixSPHAstroSwitch(lmp, narg, arg);
}

static Fix *fix_sph_astro_snapshot_creator(LAMMPS *lmp, int narg, char **arg)
{
  return new FixSPHAstroSnapshot(lmp, narg, arg);
}

static Compute *compute_sph_astro_atom_creator(LAMMPS *lmp, int narg, char **arg)
{
  return new ComputeSPHAstroAtom(lmp, narg, arg);
}

static Compute *compute_sph_astro_global_creator(LAMMPS *lmp, int narg, char **arg)
{
  return new ComputeSPHAstroGlobal(lmp, narg, arg);
}

static Command *state_command_creator(LAMMPS *lmp)
{
  return new SPHAstroStateCommand(lmp);
}

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  sph_astro_check_integer_sizes(lmp);

  lammpsplugin_t plugin;
  auto register_plugin = (lammpsplugin_regfunc) regfunc;

  plugin.version = LAMMPS_VERSION;
  plugin.author = "SPH-ASTRO developers";
  plugin.handle = handle;

  plugin.style = "pair";
  plugin.name = "sph/astro";
  plugin.info = "SPH-ASTRO hydrodynamics: density, EOS, pressure force, artificial viscosity";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &pair_sph_astro_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.name = "sph/astro/gravity";
  plugin.info = "SPH-ASTRO kernel-softened self-gravity (short-range part with a kspace)";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &pair_sph_astro_gravity_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.style = "kspace";
  plugin.name = "pppm/sph/astro/gravity";
  plugin.info = "SPH-ASTRO long-range self-gravity, PPPM (periodic)";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &pppm_sph_astro_gravity_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.name = "msm/sph/astro/gravity";
  plugin.info = "SPH-ASTRO long-range self-gravity, MSM (open boundaries)";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &msm_sph_astro_gravity_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.name = "tree/sph/astro/gravity";
  plugin.info = "SPH-ASTRO self-gravity on a quadrupole tree (open boundaries)";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &tree_sph_astro_gravity_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.style = "fix";
  plugin.name = "sph/astro";
  plugin.info = "SPH-ASTRO kick-drift-kick integrator with adaptive timestep";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &fix_sph_astro_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.name = "sph/astro/h";
  plugin.info = "SPH-ASTRO variable smoothing length: dh/dt or h-rho iteration with grad-h";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &fix_sph_astro_h_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.name = "sph/astro/owned";
  plugin.info = "SPH-ASTRO custom per-atom properties of the owned atoms only (no ghost slots)";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &fix_sph_astro_owned_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.name = "sph/astro/switch";
  plugin.info = "SPH-ASTRO per-particle viscosity alpha: Morris-Monaghan or Cullen-Dehnen";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &fix_sph_astro_switch_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.name = "sph/astro/snapshot";
  plugin.info = "SPH-ASTRO HDF5 snapshots in the SWIFT/GADGET layout (yt, h5py) every N steps";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &fix_sph_astro_snapshot_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.name = "sph/astro/sink";
  plugin.info = "SPH-ASTRO sink particles: accretion (mass, momentum, spin), creation, timestep";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &fix_sph_astro_sink_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.style = "compute";
  plugin.name = "sph/astro/atom";
  plugin.info = "SPH-ASTRO per-atom density, h, pressure, sound speed, u, neighbours";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &compute_sph_astro_atom_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.name = "sph/astro/global";
  plugin.info = "SPH-ASTRO mass, momentum, angular momentum, energies, energy error";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &compute_sph_astro_global_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.name = "sph/astro/sink";
  plugin.info = "SPH-ASTRO sinks of a fix sph/astro/sink: ID, mass, spin, accreted mass, rate";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &compute_sph_astro_sink_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.name = "sph/astro/gravity/direct";
  plugin.info = "SPH-ASTRO reference self-gravity: direct (open) or Ewald (periodic) sums";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &compute_sph_astro_gravity_direct_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.style = "command";
  plugin.name = "sph/astro/state";
  plugin.info = "SPH-ASTRO: define the per-particle state now (before read_data)";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &state_command_creator;
  (*register_plugin)(&plugin, lmp);
}
