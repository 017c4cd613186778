/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

// Helpers for LAMMPS-driven tests: a LAMMPS instance with the SPH-ASTRO plugin
// loaded, and small standard particle systems.

#ifndef SPH_ASTRO_TEST_LAMMPS_FIXTURE_H
#define SPH_ASTRO_TEST_LAMMPS_FIXTURE_H

#include "atom.h"
#include "domain.h"
#include "exceptions.h"
#include "input.h"
#include "lammps.h"
#include "library.h"
#include "modify.h"
#include "update.h"

#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace sph_astro_test {

// deleted at the end of its scope, also when a test fails by an exception:
// LAMMPS unloads the process-wide plugin list when an instance is deleted, so
// instances must not leak
inline std::unique_ptr<LAMMPS_NS::LAMMPS> open_lammps()
{
  const char *args[] = {"sph_astro_test", "-log", "none", "-screen", "none", "-nocite"};
  std::unique_ptr<LAMMPS_NS::LAMMPS> lmp(
      new LAMMPS_NS::LAMMPS(6, const_cast<char **>(args), MPI_COMM_WORLD));
  lmp->input->one("plugin load " SPH_ASTRO_PLUGIN);
  return lmp;
}

inline void commands(const std::unique_ptr<LAMMPS_NS::LAMMPS> &lmp,
                     const std::vector<std::string> &lines)
{
  for (const auto &line : lines) lmp->input->one(line);
}

// the message of the LAMMPS error a command raises, "" if none
inline std::string error_of(const std::unique_ptr<LAMMPS_NS::LAMMPS> &lmp, const std::string &line)
{
  try {
    lmp->input->one(line);
  } catch (LAMMPS_NS::LAMMPSException &e) {
    return e.what();
  }
  return "";
}

// fcc lattice constant 1, mass 0.25 -> rho = 1; h = hfact (m/rho)^(1/3)
// shape "box": periodic cube of n cells; "ball": sphere of radius n/2 cells in
// vacuum full-precision number for an input line
inline std::string num(double value)
{
  char buf[32];
  snprintf(buf, sizeof(buf), "%.17g", value);
  return buf;
}

inline void gas(const std::unique_ptr<LAMMPS_NS::LAMMPS> &lmp, const std::string &shape, int n,
                const std::string &pair, const std::string &fix, double u = 1.0,
                double jitter = 0.04)
{
  const double hfact = 1.2;
  const double h = hfact * std::cbrt(0.25);
  commands(lmp, {"units lj", "atom_style atomic", "atom_modify map array sort 0 0.0"});
  if (shape == "box") {
    commands(lmp,
             {"boundary p p p", "lattice fcc 4.0",
              "region box block 0 " + std::to_string(n) + " 0 " + std::to_string(n) + " 0 " +
                  std::to_string(n),
              "create_box 1 box", "create_atoms 1 box"});
  } else {
    const double r = 0.5 * n;
    commands(lmp,
             {"boundary s s s", "lattice fcc 4.0",
              "region box block " + std::to_string(-r - 1) + " " + std::to_string(r + 1) + " " +
                  std::to_string(-r - 1) + " " + std::to_string(r + 1) + " " +
                  std::to_string(-r - 1) + " " + std::to_string(r + 1),
              "create_box 1 box", "region ball sphere 0 0 0 " + std::to_string(r) + " units box",
              "create_atoms 1 region ball"});
  }
  if (jitter > 0.0)
    commands(lmp,
             {"displace_atoms all random " + num(jitter) + " " + num(jitter) + " " + num(jitter) +
              " 4711 units box"});
  commands(lmp,
           {"mass 1 0.25", "velocity all create 0.001 8675309 dist gaussian", "pair_style " + pair,
            "pair_coeff * *", "fix gas all " + fix, "set group all d_h " + num(h),
            "variable urand atom " + num(u) + "*(1.0+0.2*random(-1,1,991))",
            "set group all d_u v_urand", "neighbor " + num(0.3 * h) + " bin",
            "neigh_modify every 1 delay 0 check yes", "compute sum all sph/astro/global",
            "thermo_style custom step c_sum[11]", "timestep 0.002"});
}

// sum of m |v| over the local atoms: the scale that momentum round-off is measured against
inline double momentum_scale(const std::unique_ptr<LAMMPS_NS::LAMMPS> &lmp)
{
  const auto *atom = lmp->atom;
  double sum = 0.0;
  for (int i = 0; i < atom->nlocal; i++) {
    const double m = atom->rmass ? atom->rmass[i] : atom->mass[atom->type[i]];
    const double *v = atom->v[i];
    sum += m * std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  }
  return sum;
}

// Newton's third law pair by pair: the total force on the local atoms vanishes to round-off
// (relative to sum |f|, which must be > 0); single rank
inline void expect_forces_sum_to_zero(const std::unique_ptr<LAMMPS_NS::LAMMPS> &lmp)
{
  double fsum[3] = {0, 0, 0}, fabs_sum = 0;
  for (int i = 0; i < lmp->atom->nlocal; i++)
    for (int d = 0; d < 3; d++) {
      fsum[d] += lmp->atom->f[i][d];
      fabs_sum += std::fabs(lmp->atom->f[i][d]);
    }
  ASSERT_GT(fabs_sum, 0.0);
  for (double fd : fsum) EXPECT_LT(std::fabs(fd), 1e-13 * fabs_sum);
}

// global vector of a compute, as last evaluated (thermo evaluates it on the
// last step)
inline std::vector<double> global_vector(const std::unique_ptr<LAMMPS_NS::LAMMPS> &lmp,
                                         const char *id, int n)
{
  auto *vec = static_cast<double *>(
      lammps_extract_compute(lmp.get(), id, LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR));
  if (!vec) return {};
  return std::vector<double>(vec, vec + n);
}

// per-atom double custom property or x (unwrapped)/v/f component by atom ID
// (single rank)
inline std::map<int, double> per_atom(const std::unique_ptr<LAMMPS_NS::LAMMPS> &lmp,
                                      const std::string &what, int col = 0)
{
  std::map<int, double> out;
  auto *atom = lmp->atom;
  for (int i = 0; i < atom->nlocal; i++) {
    double value;
    if (what == "x") {    // unwrapped: runs may re-neighbour (and wrap) at different steps
      double unwrap[3];
      lmp->domain->unmap(atom->x[i], atom->image[i], unwrap);
      value = unwrap[col];
    } else if (what == "xwrapped")
      value = atom->x[i][col];
    else if (what == "v")
      value = atom->v[i][col];
    else if (what == "f")
      value = atom->f[i][col];
    else {
      int flag, cols;
      const int index = atom->find_custom(what.c_str(), flag, cols);
      value = atom->dvector[index][i];
    }
    out[atom->tag[i]] = value;
  }
  return out;
}

// a small fcc box with no SPH styles yet, for tests of the errors bad input gives
class BadInputTest : public ::testing::Test {
 protected:
  std::unique_ptr<LAMMPS_NS::LAMMPS> lmp;
  void SetUp() override
  {
    lmp = open_lammps();
    commands(lmp,
             {"units lj", "atom_style atomic", "atom_modify map array", "lattice fcc 4.0",
              "region box block 0 2 0 2 0 2", "create_box 1 box", "create_atoms 1 box",
              "mass 1 0.25"});
  }
  // the command's error message must contain fragment
  void expect_error(const std::string &line, const std::string &fragment)
  {
    const std::string message = error_of(lmp, line);
    EXPECT_NE(message.find(fragment), std::string::npos)
        << "command: " << line << "\nmessage: " << message << "\nexpected: " << fragment;
  }
};

}    // namespace sph_astro_test

#endif
