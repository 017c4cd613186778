/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS
   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Golden-value regression tests of pair_style sph/astro and its fixes, in the manner of LAMMPS'
// unittest/force-styles YAML tests. Each system (a small periodic lattice of 144-160 particles,
// randomly displaced, with a jump in density and energy and a deterministic velocity field with
// compression and shear, so that the viscosity, the conductivities and the switches all act) is
// run for 5 steps on one MPI rank; per-atom fx fy fz du/dt rho h after the setup of the first
// run (run 0) and after the 5 steps are compared with unittest/golden/<system>.yaml:
//
//   NewtonOn   the run with newton on, as the references were made
//   NewtonOff  the same commands with newton off (ghost pairs evaluated on both sides)
//   Restart    run 2 steps, write_restart; a new instance reads it, re-defines the fixes and
//              the neighbour settings as a user would (pair_style comes from the file); its
//              setup forces (run 0) must equal those of the writer at the end of step 2, and
//              after 3 more steps it must reproduce the reference's after_steps (round-off:
//              the restarted run wraps and re-neighbours at its setup)
//   DataFile   (a) a data file written before the first run (write_data, with the package's
//              state sections) read into a new instance with the same pair style and fixes
//              reproduces the reference after_setup and after_steps;
//              (b) a data file written after 2 steps restores x, v and the per-atom state
//              exactly, and its setup forces and the 3 steps that follow equal those of the
//              writing instance after the same re-definition of the integrator (fix sph/astro
//              etc. defined anew). A data file does not hold fix sph/astro's global state, so
//              the predictions d2_vest, d_uest (and d_rhoest, the entropic function A) start
//              from v, u, rho (doc/sph_astro_state.rst): the continuation is a new run from
//              the stored state, not the uninterrupted one, and (b) tests exactly that.
//              The reader defines, before read_data, every fix property/atom of the package
//              that the writer had (SPH_ASTRO_ALPHA, _DIVV_PREV, _CONTINUITY, _ENTROPY): the
//              data file holds a section for each, and read_data stops at an unknown one.
//
// Tolerance: each field is compared relative to the largest |value| of that field in the
// reference (TOLERANCE). The largest relative deviation of every check is printed also when it
// passes. Regenerate the references (when a change is meant to move them) with
//
//   SPH_ASTRO_GOLDEN_REGENERATE=1 build/unittest/test_golden
//
// which rewrites SPH_ASTRO_GOLDEN_DIR/<system>.yaml (unittest/golden in the source tree) from
// the newton-on run; see unittest/golden/README.md. The plugin is SPH_ASTRO_PLUGIN unless the
// environment variable SPH_ASTRO_PLUGIN_PATH names another one.
//
// Physics of the systems: Monaghan (1992, ARA&A 30, 543) for the classic viscosity and the M4
// kernel; Monaghan (1997, J. Comput. Phys. 136, 298) for the signal-velocity viscosity;
// Morris & Monaghan (1997, J. Comput. Phys. 136, 41) and Cullen & Dehnen (2010, MNRAS 408, 669)
// for the switches; Balsara (1995, J. Comput. Phys. 121, 357); Price (2008, J. Comput. Phys.
// 227, 10040) for the artificial conductivity; Cleary & Monaghan (1999, J. Comput. Phys. 148,
// 227) for the physical conduction; Springel & Hernquist (2002, MNRAS 333, 649) for the
// grad-h equations and the entropy formulation; Saitoh & Makino (2013, ApJ 768, 44) and
// Hopkins (2013, MNRAS 428, 2840) for pressure-energy; Frontiere, Raskin & Owen (2017,
// J. Comput. Phys. 332, 160) and Rosswog (2020, MNRAS 498, 4230) for the reconstruction;
// Dehnen & Aly (2012, MNRAS 425, 1068) for the Wendland kernels; Price (2012, J. Comput.
// Phys. 231, 759) for the quintic kernel; Monaghan (1989, J. Comput. Phys. 82, 1) for XSPH.

#include "lammps_fixture.h"

#include "fix.h"
#include "force.h"
#include "modify.h"
#include "update.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace sph_astro_test;
using LAMMPS_NS::LAMMPS;

namespace {

// relative to the largest |value| of the field in the reference
constexpr double TOLERANCE = 1e-10;
constexpr int NSTEPS = 5;           // steps of the reference run
constexpr int KSTEPS = 2;           // steps before write_restart / write_data
constexpr int MAX_REPORTED = 10;    // failing values printed per check

const char *const FIELDS[] = {"fx", "fy", "fz", "dudt", "rho", "h"};
constexpr int NFIELDS = 6;

using Values = std::map<int, std::array<double, NFIELDS>>;

// ---------------------------------------------------------------- the systems

struct System {
  std::string name;
  std::string description;
  std::vector<std::string> geometry;     // box, atoms, types, masses, displacement
  std::string pair;                      // pair_style arguments
  std::vector<std::string> fixes;        // integrator and its companions (re-defined after
                                         // read_restart and read_data)
  std::vector<std::string> state;        // initial h, u, velocities, timestep
  std::vector<std::string> neighbour;    // neighbour settings (re-issued after read_restart)
  int dimension = 3;
};

const char *const GAMMA = "$(5.0/3.0)";

// 3D: periodic box of 4 x 3 x 3 fcc cells (lattice constant 1, 144 particles), type 1 (mass
// 0.25, rho 1) in x < 2, type 2 (mass 0.5, rho 2) in x >= 2; u 1.0 / 0.6 (pressure jump 1 : 1.2
// for the ideal gas) with 10 % deterministic scatter; v = a converging/expanding wave in x
// (div v < 0 around x = 0, > 0 around x = 2), a shear wave in y and small per-atom parts
std::vector<std::string> geometry3d()
{
  return {"units lj",
          "dimension 3",
          "atom_style atomic",
          "atom_modify map array sort 0 0.0",
          "boundary p p p",
          "lattice fcc 4.0",
          "region box block 0 4 0 3 0 3",
          "create_box 2 box",
          "create_atoms 1 box",
          "region right block 2 4 INF INF INF INF",
          "set region right type 2",
          "mass 1 0.25",
          "mass 2 0.5",
          "displace_atoms all random 0.05 0.05 0.05 4711 units box"};
}

// h = hfact (m/rho)^(1/3) = hfact 0.25^(1/3) on both sides, with +-10 % scatter
std::vector<std::string> state3d(double hfact)
{
  const double h = hfact * std::cbrt(0.25);
  return {"variable hset atom " + num(h) + "*(1.0+0.1*sin(5.3*id))",
          "set group all d_h v_hset",
          "variable uset atom ((type==1)*1.0+(type==2)*0.6)*(1.0+0.1*sin(11.1*id))",
          "set group all d_u v_uset",
          "variable vx atom -0.4*sin(2.0*PI*x/4.0)+0.05*sin(7.3*id)",
          "variable vy atom 0.2*cos(2.0*PI*x/4.0)+0.05*sin(3.1*id)",
          "variable vz atom 0.05*cos(5.7*id)",
          "velocity all set v_vx v_vy v_vz",
          "timestep 0.002"};
}

std::vector<std::string> neighbour3d(double hfact, double kernel_radius = 2.0)
{
  // skin 0.3 of the support of the mean h
  const double skin = 0.15 * kernel_radius * hfact * std::cbrt(0.25);
  return {"neighbor " + num(skin) + " bin", "neigh_modify every 1 delay 0 check yes"};
}

// 2D: 10 x 8 cells of the centred square lattice (lattice constant 1, 160 particles), masses
// 0.5 / 1.0 (rho 1 / 2), the same jump and velocity field as in 3D
std::vector<std::string> geometry2d()
{
  return {"units lj",
          "dimension 2",
          "atom_style atomic",
          "atom_modify map array sort 0 0.0",
          "boundary p p p",
          "lattice sq2 2.0",
          "region box block 0 10 0 8 -0.5 0.5",
          "create_box 2 box",
          "create_atoms 1 box",
          "region right block 5 10 INF INF INF INF",
          "set region right type 2",
          "mass 1 0.5",
          "mass 2 1.0",
          "displace_atoms all random 0.05 0.05 0.0 4711 units box"};
}

std::vector<std::string> state2d(double hfact)
{
  const double h = hfact * std::sqrt(0.5);
  return {"variable hset atom " + num(h) + "*(1.0+0.1*sin(5.3*id))",
          "set group all d_h v_hset",
          "variable uset atom ((type==1)*1.0+(type==2)*0.6)*(1.0+0.1*sin(11.1*id))",
          "set group all d_u v_uset",
          "variable vx atom -0.4*sin(2.0*PI*x/10.0)+0.05*sin(7.3*id)",
          "variable vy atom 0.2*cos(2.0*PI*x/10.0)+0.05*sin(3.1*id)",
          "velocity all set v_vx v_vy 0.0",
          "timestep 0.002"};
}

std::vector<std::string> neighbour2d(double hfact)
{
  const double skin = 0.3 * hfact * std::sqrt(0.5);
  return {"neighbor " + num(skin) + " bin", "neigh_modify every 1 delay 0 check yes"};
}

// the list with one more command; the systems with a switch start at d_alpha 0.5, between
// alpha_min and alpha_max, so that both its source and its decay act from the first step
std::vector<std::string> plus(std::vector<std::string> list, const std::string &command)
{
  list.push_back(command);
  return list;
}

const std::vector<System> &systems()
{
  static const std::vector<System> list = [] {
    const std::string ideal = std::string("eos ideal ") + GAMMA;
    std::vector<System> s;
    s.push_back({"m4_fixed_classic",
                 "M4 kernel, fixed h, classic viscosity (alpha 1, beta 2), 3D",
                 geometry3d(),
                 "sph/astro kernel m4 " + ideal + " viscosity classic 1.0 2.0",
                 {"fix gas all sph/astro courant 0.3"},
                 state3d(1.2),
                 neighbour3d(1.2)});
    s.push_back({"iterate_signal_cullen_dehnen_conductivity",
                 "fix sph/astro/h iterate (grad-h), signal-velocity viscosity, fix "
                 "sph/astro/switch cullen-dehnen, artificial conductivity 1",
                 geometry3d(),
                 "sph/astro kernel m4 " + ideal + " viscosity signal 1.0 conductivity 1.0",
                 {"fix gas all sph/astro courant 0.3", "fix hvar all sph/astro/h iterate hfact 1.2",
                  "fix av all sph/astro/switch cullen-dehnen 0.1 1.0 0.1"},
                 plus(state3d(1.2), "set group all d_alpha 0.5"),
                 neighbour3d(1.2)});
    s.push_back(
        {"dhdt_balsara_conduction",
         "fix sph/astro/h dhdt, classic viscosity with the Balsara limiter, physical "
         "heat conduction kappa 0.1",
         geometry3d(),
         "sph/astro kernel m4 " + ideal + " viscosity classic 1.0 2.0 balsara yes conduction 0.1",
         {"fix gas all sph/astro courant 0.3", "fix hvar all sph/astro/h dhdt"},
         state3d(1.2),
         neighbour3d(1.2)});
    s.push_back({"reconstruct_iterate_morris_monaghan",
                 "viscosity on reconstructed velocities (reconstruct yes), fix sph/astro/h "
                 "iterate, fix sph/astro/switch morris-monaghan, conductivity 0.5",
                 geometry3d(),
                 "sph/astro kernel m4 " + ideal +
                     " viscosity classic 1.0 2.0 reconstruct yes conductivity 0.5",
                 {"fix gas all sph/astro courant 0.3", "fix hvar all sph/astro/h iterate hfact 1.2",
                  "fix av all sph/astro/switch morris-monaghan 0.1 1.0 0.2"},
                 plus(state3d(1.2), "set group all d_alpha 0.5"),
                 neighbour3d(1.2)});
    s.push_back({"fixed_symmetrise_geometric_continuity",
                 "fixed h (varying per particle), symmetrise kernel, pressure geometric, "
                 "density continuity",
                 geometry3d(),
                 "sph/astro kernel m4 " + ideal +
                     " viscosity classic 1.0 2.0 symmetrise kernel pressure geometric density "
                     "continuity",
                 {"fix gas all sph/astro courant 0.3"},
                 state3d(1.3),
                 neighbour3d(1.3)});
    s.push_back(
        {"pressure_energy_iterate_conductivity",
         "formulation pressure-energy, fix sph/astro/h iterate, conductivity 1",
         geometry3d(),
         "sph/astro kernel m4 " + ideal +
             " viscosity classic 1.0 2.0 conductivity 1.0 formulation pressure-energy",
         {"fix gas all sph/astro courant 0.3", "fix hvar all sph/astro/h iterate hfact 1.2"},
         state3d(1.2),
         neighbour3d(1.2)});
    s.push_back(
        {"pressure_energy_fixed",
         "formulation pressure-energy, fixed h",
         geometry3d(),
         "sph/astro kernel m4 " + ideal + " viscosity classic 1.0 2.0 formulation pressure-energy",
         {"fix gas all sph/astro courant 0.3"},
         state3d(1.3),
         neighbour3d(1.3)});
    s.push_back({"entropy_iterate",
                 "fix sph/astro thermal entropy, fix sph/astro/h iterate",
                 geometry3d(),
                 "sph/astro kernel m4 " + ideal + " viscosity classic 1.0 2.0",
                 {"fix gas all sph/astro thermal entropy courant 0.3",
                  "fix hvar all sph/astro/h iterate hfact 1.2"},
                 state3d(1.2),
                 neighbour3d(1.2)});
    s.push_back(
        {"wendland_c4_2d_iterate",
         "2D (dimension 2), Wendland C4 kernel, fix sph/astro/h iterate hfact 1.5",
         geometry2d(),
         "sph/astro kernel wendland/c4 " + ideal + " viscosity classic 1.0 2.0",
         {"fix gas all sph/astro courant 0.3", "fix hvar all sph/astro/h iterate hfact 1.5"},
         state2d(1.5),
         neighbour2d(1.5),
         2});
    s.push_back({"quintic_polytropic",
                 "quintic (M6) kernel, eos polytropic K 0.5 gamma 2, fixed h (hfact 1.0)",
                 geometry3d(),
                 "sph/astro kernel m6 eos polytropic 0.5 2.0 viscosity classic 1.0 2.0",
                 {"fix gas all sph/astro courant 0.3"},
                 state3d(1.0),
                 neighbour3d(1.0, 3.0)});
    s.push_back({"gaussian_isothermal",
                 "Gaussian kernel (hfact 0.8), eos isothermal cs 1, fix sph/astro/h dhdt, "
                 "epsilon 0.02",
                 geometry3d(),
                 "sph/astro kernel gaussian eos isothermal 1.0 viscosity classic 1.0 2.0 "
                 "epsilon 0.02",
                 {"fix gas all sph/astro courant 0.3", "fix hvar all sph/astro/h dhdt"},
                 state3d(0.8),
                 neighbour3d(0.8, 3.0)});
    s.push_back({"xsph_wendland_c2",
                 "fix sph/astro xsph 0.5, Wendland C2 kernel, fixed h (hfact 1.4)",
                 geometry3d(),
                 "sph/astro kernel wendland/c2 " + ideal + " viscosity classic 1.0 2.0",
                 {"fix gas all sph/astro courant 0.3 xsph 0.5"},
                 state3d(1.4),
                 neighbour3d(1.4)});
    return s;
  }();
  return list;
}

const System &system_named(const std::string &name)
{
  for (const auto &sys : systems())
    if (sys.name == name) return sys;
  throw std::runtime_error("no golden system named " + name);
}

std::vector<std::string> system_names()
{
  std::vector<std::string> names;
  for (const auto &sys : systems()) names.push_back(sys.name);
  return names;
}

// the commands of the straight run up to (not including) the runs
std::vector<std::string> setup_commands(const System &sys, bool newton)
{
  std::vector<std::string> out = sys.geometry;
  // "newton" right after "units": before the box exists
  out.insert(out.begin() + 1, newton ? "newton on" : "newton off");
  out.push_back("pair_style " + sys.pair);
  out.push_back("pair_coeff * *");
  for (const auto &c : sys.fixes) out.push_back(c);
  for (const auto &c : sys.state) out.push_back(c);
  for (const auto &c : sys.neighbour) out.push_back(c);
  return out;
}

// the fix property/atom that the package's styles create, with their arguments: a data file
// holds a section for each that exists, and read_data needs each defined beforehand
const std::vector<std::pair<std::string, std::string>> &state_fixes()
{
  static const std::vector<std::pair<std::string, std::string>> list = {
      {"SPH_ASTRO_ALPHA", "property/atom d_alpha ghost yes"},
      {"SPH_ASTRO_DIVV_PREV", "property/atom d_divv_prev"},
      {"SPH_ASTRO_CONTINUITY", "property/atom d_rhoest d_drhodt ghost yes"},
      {"SPH_ASTRO_ENTROPY", "property/atom d_entropy d_entropy_est d_dentropy"}};
  return list;
}

// ---------------------------------------------------------------- LAMMPS access

std::string plugin_path()
{
  const char *env = std::getenv("SPH_ASTRO_PLUGIN_PATH");
  return (env && *env) ? env : SPH_ASTRO_PLUGIN;
}

// one instance at a time: LAMMPS unloads the process-wide plugin list when an instance is
// deleted (lammps_fixture.h)
std::unique_ptr<LAMMPS> open_instance()
{
  const char *args[] = {"sph_astro_golden", "-log", "none", "-screen", "none", "-nocite"};
  std::unique_ptr<LAMMPS> lmp(new LAMMPS(6, const_cast<char **>(args), MPI_COMM_WORLD));
  const std::string path = plugin_path();
  lmp->input->one("plugin load " + path);
  if (!lmp->force->pair_map->count("sph/astro"))
    throw std::runtime_error("plugin " + path + " did not provide pair_style sph/astro");
  return lmp;
}

double *custom(const std::unique_ptr<LAMMPS> &lmp, const char *name)
{
  int flag, cols;
  const int index = lmp->atom->find_custom(name, flag, cols);
  if (index < 0 || flag != 1 || cols != 0) return nullptr;
  return lmp->atom->dvector[index];
}

// fx fy fz du/dt rho h by atom ID (single rank)
Values snapshot(const std::unique_ptr<LAMMPS> &lmp)
{
  Values out;
  auto *atom = lmp->atom;
  const double *dudt = custom(lmp, "dudt");
  const double *rho = custom(lmp, "rho");
  const double *h = custom(lmp, "h");
  for (int i = 0; i < atom->nlocal; i++)
    out[static_cast<int>(atom->tag[i])] = {atom->f[i][0], atom->f[i][1], atom->f[i][2],
                                           dudt[i],       rho[i],        h[i]};
  return out;
}

// x (unwrapped), v and every per-atom value of the package's state fixes that exists, by atom
// ID: what a data file must carry back
std::map<std::string, std::map<int, double>> full_state(const std::unique_ptr<LAMMPS> &lmp)
{
  std::map<std::string, std::map<int, double>> out;
  for (int d = 0; d < 3; d++) {
    out[std::string("x") + char('1' + d)] = per_atom(lmp, "x", d);
    out[std::string("v") + char('1' + d)] = per_atom(lmp, "v", d);
  }
  for (const char *name : {"rho", "h", "u", "dudt", "uest", "alpha", "divv_prev", "rhoest",
                           "drhodt", "entropy", "entropy_est", "dentropy"})
    if (custom(lmp, name)) out[name] = per_atom(lmp, name);
  int flag, cols;
  const int vest = lmp->atom->find_custom("vest", flag, cols);
  if (vest >= 0 && flag == 1 && cols == 3)
    for (int i = 0; i < lmp->atom->nlocal; i++)
      for (int d = 0; d < 3; d++)
        out[std::string("vest") + char('1' + d)][static_cast<int>(lmp->atom->tag[i])] =
            lmp->atom->darray[vest][i][d];
  return out;
}

// ---------------------------------------------------------------- reference files

struct Reference {
  std::string description;
  std::vector<std::string> commands;
  Values after_setup, after_steps;
  double time_after_steps = 0.0;
};

std::string reference_path(const std::string &name)
{
  return std::string(SPH_ASTRO_GOLDEN_DIR) + "/" + name + ".yaml";
}

bool regenerate()
{
  const char *env = std::getenv("SPH_ASTRO_GOLDEN_REGENERATE");
  return env && *env && std::string(env) != "0";
}

std::string format_values(const Values &values)
{
  std::string out;
  char buf[64];
  for (const auto &[id, row] : values) {
    out += "  " + std::to_string(id);
    for (double v : row) {
      snprintf(buf, sizeof(buf), " %.17g", v);
      out += buf;
    }
    out += "\n";
  }
  return out;
}

void write_reference(const System &sys, const Reference &ref, const std::string &lammps_version)
{
  const std::string path = reference_path(sys.name);
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  char date[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(date, sizeof(date), "%Y-%m-%d", std::gmtime(&now));
  char tbuf[64];
  snprintf(tbuf, sizeof(tbuf), "%.17g", ref.time_after_steps);
  out << "# SPH-ASTRO golden values for unittest/test_golden.cpp (see README.md here).\n"
      << "# Generated, not edited: SPH_ASTRO_GOLDEN_REGENERATE=1 build/unittest/test_golden\n"
      << "---\n"
      << "system: " << sys.name << "\n"
      << "description: " << ref.description << "\n"
      << "lammps_version: " << lammps_version << "\n"
      << "date_generated: " << date << "\n"
      << "mpi_ranks: 1\n"
      << "newton: on (the test also runs the same commands with newton off)\n"
      << "nsteps: " << NSTEPS << "\n"
      << "commands:\n";
  for (const auto &c : ref.commands) out << "  - " << c << "\n";
  out << "columns: id fx fy fz dudt rho h\n"
      << "after_setup:\n"
      << format_values(ref.after_setup) << "time_after_steps: " << tbuf << "\n"
      << "after_steps:\n"
      << format_values(ref.after_steps) << "...\n";
  out.close();
  if (!out) throw std::runtime_error("writing " + path + " failed");
}

// the simple YAML-like format written above
Reference read_reference(const std::string &name)
{
  const std::string path = reference_path(name);
  std::ifstream in(path);
  if (!in)
    throw std::runtime_error("reference " + path +
                             " not found; generate it with SPH_ASTRO_GOLDEN_REGENERATE=1 "
                             "test_golden");
  Reference ref;
  std::string line, block;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line == "---" || line == "...") continue;
    if (line[0] != ' ') {    // key: value
      const auto colon = line.find(':');
      if (colon == std::string::npos) throw std::runtime_error(path + ": bad line: " + line);
      const std::string key = line.substr(0, colon);
      std::string value = line.substr(colon + 1);
      if (!value.empty() && value[0] == ' ') value.erase(0, 1);
      block = key;
      if (key == "description")
        ref.description = value;
      else if (key == "time_after_steps")
        ref.time_after_steps = std::stod(value);
      continue;
    }
    if (block == "commands") {
      const auto dash = line.find("- ");
      if (dash == std::string::npos) throw std::runtime_error(path + ": bad command: " + line);
      ref.commands.push_back(line.substr(dash + 2));
    } else if (block == "after_setup" || block == "after_steps") {
      std::istringstream fields(line);
      int id;
      std::array<double, NFIELDS> row;
      std::string word;
      if (!(fields >> id)) throw std::runtime_error(path + ": bad atom line: " + line);
      for (int k = 0; k < NFIELDS; k++) {
        if (!(fields >> word)) throw std::runtime_error(path + ": short atom line: " + line);
        row[k] = std::strtod(word.c_str(), nullptr);
      }
      (block == "after_setup" ? ref.after_setup : ref.after_steps)[id] = row;
    }
  }
  return ref;
}

std::vector<std::string> reference_commands(const System &sys)
{
  std::vector<std::string> c = setup_commands(sys, true);
  c.push_back("run 0");
  c.push_back("run " + std::to_string(NSTEPS));
  return c;
}

// the straight run: run 0 (after_setup), then run NSTEPS (after_steps)
Reference straight_run(const System &sys, bool newton, std::string *version = nullptr)
{
  Reference out;
  out.description = sys.description;
  out.commands = reference_commands(sys);
  auto lmp = open_instance();
  commands(lmp, setup_commands(sys, newton));
  commands(lmp, {"run 0"});
  out.after_setup = snapshot(lmp);
  commands(lmp, {"run " + std::to_string(NSTEPS)});
  out.after_steps = snapshot(lmp);
  out.time_after_steps =
      lmp->update->atime + (lmp->update->ntimestep - lmp->update->atimestep) * lmp->update->dt;
  if (version) *version = lmp->version;
  return out;
}

// the reference of a system: read from its file, or (regenerating) made by the newton-on run
// and written, once per system and test process
const Reference &reference(const std::string &name)
{
  static std::map<std::string, Reference> cache;
  auto found = cache.find(name);
  if (found != cache.end()) return found->second;
  const System &sys = system_named(name);
  Reference ref;
  if (regenerate()) {
    std::string version;
    ref = straight_run(sys, true, &version);
    write_reference(sys, ref, version);
    printf("[golden] %s: wrote %s\n", name.c_str(), reference_path(name).c_str());
  } else
    ref = read_reference(name);
  return cache[name] = ref;
}

// ---------------------------------------------------------------- comparison

struct Deviation {
  double worst = 0.0;
  int id = 0;
  int field = 0;
};

// every value against the reference, relative to the largest |value| of its field in the
// reference; failures name atom, field, value and reference; returns the largest deviation
Deviation compare(const Values &got, const Values &ref, const std::string &what)
{
  Deviation dev;
  EXPECT_EQ(got.size(), ref.size()) << what << ": number of atoms";
  std::array<double, NFIELDS> scale{};
  for (const auto &[id, row] : ref)
    for (int k = 0; k < NFIELDS; k++) scale[k] = std::max(scale[k], std::fabs(row[k]));
  int reported = 0, failed = 0;
  for (const auto &[id, row] : ref) {
    const auto it = got.find(id);
    if (it == got.end()) {
      ADD_FAILURE() << what << ": atom " << id << " is missing";
      continue;
    }
    for (int k = 0; k < NFIELDS; k++) {
      const double diff = std::fabs(it->second[k] - row[k]);
      double rel;
      if (scale[k] > 0.0)
        rel = diff / scale[k];
      else
        rel = diff == 0.0 ? 0.0 : INFINITY;    // a field that is 0 everywhere must stay 0
      if (std::isnan(rel)) rel = INFINITY;
      if (rel > dev.worst) dev = {rel, id, k};
      if (rel > TOLERANCE) {
        failed++;
        if (reported++ < MAX_REPORTED) {
          char buf[320];
          snprintf(buf, sizeof(buf),
                   "%s: atom %d %s = %.17g, reference %.17g (deviation %.3g of the largest |%s| "
                   "%.6g; tolerance %g)",
                   what.c_str(), id, FIELDS[k], it->second[k], row[k], rel, FIELDS[k], scale[k],
                   TOLERANCE);
          ADD_FAILURE() << buf;
        }
      }
    }
  }
  if (failed > MAX_REPORTED)
    ADD_FAILURE() << what << ": " << failed << " values outside the tolerance in all ("
                  << MAX_REPORTED << " shown)";
  return dev;
}

void report(const std::string &name, const std::string &check, const Deviation &dev)
{
  printf("[golden] %-42s %-28s largest relative deviation %.3e (%s, atom %d)\n", name.c_str(),
         check.c_str(), dev.worst, FIELDS[dev.field], dev.id);
  fflush(stdout);
}

Deviation worse(const Deviation &a, const Deviation &b)
{
  return b.worst > a.worst ? b : a;
}

// the reference file must come from the commands the test runs now
void expect_current_commands(const System &sys, const Reference &ref)
{
  const auto now = reference_commands(sys);
  const std::string hint = "unittest/golden/" + sys.name +
      ".yaml was made with other commands than test_golden.cpp gives now; "
      "regenerate it (unittest/golden/README.md) if the change is meant";
  for (size_t k = 0; k < std::max(now.size(), ref.commands.size()); k++) {
    const std::string file = k < ref.commands.size() ? ref.commands[k] : "(none)";
    const std::string test = k < now.size() ? now[k] : "(none)";
    if (file != test) {
      ADD_FAILURE() << hint << "\ncommand " << k + 1 << " in the file: " << file << "\ncommand "
                    << k + 1 << " of the test: " << test;
      return;
    }
  }
}

// one fixture per check, so that a single combination of system and check can be left out
class GoldenRun : public ::testing::TestWithParam<std::string> {};
class GoldenRestart : public ::testing::TestWithParam<std::string> {};
class GoldenDataFile : public ::testing::TestWithParam<std::string> {};

// ---------------------------------------------------------------- (a) newton on

TEST_P(GoldenRun, NewtonOn)
{
  const System &sys = system_named(GetParam());
  const Reference &ref = reference(sys.name);
  expect_current_commands(sys, ref);
  const Reference run = straight_run(sys, true);
  const Deviation d =
      worse(compare(run.after_setup, ref.after_setup, sys.name + " newton on, after_setup"),
            compare(run.after_steps, ref.after_steps, sys.name + " newton on, after_steps"));
  EXPECT_NEAR(run.time_after_steps, ref.time_after_steps, TOLERANCE * ref.time_after_steps);
  report(sys.name, "newton on", d);
}

// ---------------------------------------------------------------- (b) newton off

TEST_P(GoldenRun, NewtonOff)
{
  const System &sys = system_named(GetParam());
  const Reference &ref = reference(sys.name);
  const Reference run = straight_run(sys, false);
  const Deviation d =
      worse(compare(run.after_setup, ref.after_setup, sys.name + " newton off, after_setup"),
            compare(run.after_steps, ref.after_steps, sys.name + " newton off, after_steps"));
  EXPECT_NEAR(run.time_after_steps, ref.time_after_steps, TOLERANCE * ref.time_after_steps);
  report(sys.name, "newton off", d);
}

// ---------------------------------------------------------------- (c) restart

TEST_P(GoldenRestart, ContinuesTheStraightRun)
{
  const System &sys = system_named(GetParam());
  const Reference &ref = reference(sys.name);
  const std::string file = "test_golden_" + sys.name + ".restart";
  Values at_write;
  {
    auto lmp = open_instance();
    commands(lmp, setup_commands(sys, true));
    commands(lmp, {"run 0", "run " + std::to_string(KSTEPS)});
    at_write = snapshot(lmp);
    commands(lmp, {"write_restart " + file});
  }
  auto lmp = open_instance();
  commands(lmp, {"read_restart " + file});
  commands(lmp, sys.fixes);    // same IDs: the per-atom state comes back with them
  commands(lmp, sys.neighbour);
  commands(lmp, {"run 0"});
  const Deviation setup =
      compare(snapshot(lmp), at_write, sys.name + " restart, setup forces against the writer's");
  commands(lmp, {"run " + std::to_string(NSTEPS - KSTEPS)});
  const Deviation steps =
      compare(snapshot(lmp), ref.after_steps, sys.name + " restart, after_steps");
  const double time =
      lmp->update->atime + (lmp->update->ntimestep - lmp->update->atimestep) * lmp->update->dt;
  EXPECT_NEAR(time, ref.time_after_steps, TOLERANCE * ref.time_after_steps);
  EXPECT_EQ(lmp->update->ntimestep, NSTEPS);
  report(sys.name, "restart (setup vs writer)", setup);
  report(sys.name, "restart (after_steps)", steps);
  std::remove(file.c_str());
}

// ---------------------------------------------------------------- (d) data file

// a new instance with the data file and the system's styles, as the package's documentation
// tells a user to read it back (doc/sph_astro_state.rst)
std::unique_ptr<LAMMPS> read_data_instance(const System &sys, const std::string &file,
                                           const std::vector<std::string> &extra_fixes, double dt)
{
  auto lmp = open_instance();
  commands(lmp,
           {"units lj", "dimension " + std::to_string(sys.dimension), "newton on",
            "atom_style atomic", "atom_modify map array sort 0 0.0", "boundary p p p",
            "sph/astro/state"});
  std::string read = "read_data " + file + " fix SPH_ASTRO_STATE NULL SPH_ASTRO_STATE";
  for (const auto &[id, args] : state_fixes())
    if (std::find(extra_fixes.begin(), extra_fixes.end(), id) != extra_fixes.end()) {
      commands(lmp, {"fix " + id + " all " + args});
      read += " fix " + id + " NULL " + id;
    }
  commands(lmp, {read, "pair_style " + sys.pair, "pair_coeff * *"});
  commands(lmp, sys.fixes);
  commands(lmp, sys.neighbour);
  commands(lmp, {"timestep " + num(dt)});
  return lmp;
}

std::vector<std::string> existing_state_fixes(const std::unique_ptr<LAMMPS> &lmp)
{
  std::vector<std::string> out;
  for (const auto &[id, args] : state_fixes())
    if (lmp->modify->get_fix_by_id(id)) out.push_back(id);
  return out;
}

TEST_P(GoldenDataFile, RoundTrip)
{
  const System &sys = system_named(GetParam());
  const Reference &ref = reference(sys.name);
  const std::string file = "test_golden_" + sys.name + ".data";

  // (a) written before the first run: the file carries the whole initial state, and the run
  // from it is the reference run
  std::vector<std::string> extra;
  double dt;
  {
    auto lmp = open_instance();
    commands(lmp, setup_commands(sys, true));
    commands(lmp, {"write_data " + file});
    extra = existing_state_fixes(lmp);
    dt = lmp->update->dt;
  }
  Deviation initial;
  {
    auto lmp = read_data_instance(sys, file, extra, dt);
    commands(lmp, {"run 0"});
    initial =
        compare(snapshot(lmp), ref.after_setup, sys.name + " data file at step 0, after_setup");
    commands(lmp, {"run " + std::to_string(NSTEPS)});
    initial = worse(
        initial,
        compare(snapshot(lmp), ref.after_steps, sys.name + " data file at step 0, after_steps"));
  }
  report(sys.name, "data at step 0 (reference)", initial);

  // (b) written after KSTEPS steps: the state comes back exactly; the run from it equals the
  // writer's own continuation once the writer's integrator is defined anew (predictions from
  // v and u, as after read_data)
  std::map<std::string, std::map<int, double>> state_at_write;
  Values writer_setup, writer_steps;
  {
    auto lmp = open_instance();
    commands(lmp, setup_commands(sys, true));
    commands(lmp, {"run 0", "run " + std::to_string(KSTEPS), "write_data " + file});
    state_at_write = full_state(lmp);
    extra = existing_state_fixes(lmp);
    dt = lmp->update->dt;
    // the integrator anew: unfix in reverse order, define again in the same order
    for (auto it = sys.fixes.rbegin(); it != sys.fixes.rend(); ++it) {
      std::istringstream words(*it);
      std::string fix, id;
      words >> fix >> id;
      commands(lmp, {"unfix " + id});
    }
    commands(lmp, sys.fixes);
    commands(lmp, {"run 0"});
    writer_setup = snapshot(lmp);
    commands(lmp, {"run " + std::to_string(NSTEPS - KSTEPS)});
    writer_steps = snapshot(lmp);
  }
  auto lmp = read_data_instance(sys, file, extra, dt);
  // bit for bit, before any run
  const auto state = full_state(lmp);
  int differ = 0;
  for (const auto &[name, values] : state_at_write) {
    const auto it = state.find(name);
    if (it == state.end()) {
      ADD_FAILURE() << sys.name << " data file: per-atom " << name << " did not come back";
      continue;
    }
    for (const auto &[id, value] : values) {
      const auto got = it->second.find(id);
      const bool same = got != it->second.end() && got->second == value;
      if (!same && differ++ < MAX_REPORTED)
        ADD_FAILURE() << sys.name << " data file: atom " << id << " " << name << " = "
                      << (got == it->second.end() ? NAN : got->second) << ", written " << value;
    }
  }
  EXPECT_EQ(differ, 0) << sys.name << " data file: values that did not come back exactly";
  commands(lmp, {"run 0"});
  const Deviation setup =
      compare(snapshot(lmp), writer_setup, sys.name + " data file at step 2, setup forces");
  commands(lmp, {"run " + std::to_string(NSTEPS - KSTEPS)});
  const Deviation steps =
      compare(snapshot(lmp), writer_steps, sys.name + " data file at step 2, 3 steps");
  report(sys.name, "data at step 2 (setup)", setup);
  report(sys.name, "data at step 2 (3 steps)", steps);
  std::remove(file.c_str());
}

std::string param_name(const ::testing::TestParamInfo<std::string> &info)
{
  return info.param;
}

}    // namespace

INSTANTIATE_TEST_SUITE_P(SPHAstro, GoldenRun, ::testing::ValuesIn(system_names()), param_name);

INSTANTIATE_TEST_SUITE_P(SPHAstro, GoldenRestart, ::testing::ValuesIn(system_names()), param_name);

INSTANTIATE_TEST_SUITE_P(SPHAstro, GoldenDataFile, ::testing::ValuesIn(system_names()), param_name);
