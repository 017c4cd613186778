/* -*- c++ -*- ----------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

#ifndef LMP_SPH_ASTRO_FIELDS_H
#define LMP_SPH_ASTRO_FIELDS_H

namespace LAMMPS_NS {
class Memory;
}

namespace SPHAstro {

// per-atom results of the passes (owned + ghost atoms); null where the scene does not need one
struct Fields {
  // the arrays a scene needs
  struct Needs {
    bool curl, balsara, signal, reconstruction, conductivity, pressure_factor, pressure_energy,
        energy_sum, conduction, dphidh_sum;
  };
  // (re)allocate for n atoms when n grew or an array became needed
  void grow(LAMMPS_NS::Memory *memory, int n, const Needs &needs);
  void destroy(LAMMPS_NS::Memory *memory);
  // bytes held
  double memory_usage() const;
  int nmax = 0;

  double *pressure = nullptr;      // P
  double *soundspeed = nullptr;    // c_s
  double *vdotgradw = nullptr;     // sum_j m_j v_ij . grad_i W_ij (= -rho_i div v_i)
  double *divv = nullptr;          // div v
  double *nneigh = nullptr;        // neighbours inside the kernel support
  double *omega = nullptr;         // grad-h factor Omega (1 without grad-h terms)
  double **dcurl = nullptr;        // sums for div v and curl v: v_ij . grad W, v_ij x grad W
  double *curlv = nullptr;         // |curl v|
  double *balsara = nullptr;       // Balsara factor of this step
  double *vsigmax = nullptr;       // max_j v_sig,ij (PairOptions::tracks_signal)
  double **vgsum = nullptr;        // reconstruction: the sums M, G of grad v = G M^-1
  double **vgrad = nullptr;        // reconstruction: symmetric grad v and spacing Delta
  double *condrate = nullptr;      // artificial conductivity: sum_j m_j k_ij |dW/dr| r
  double *pe_gradh = nullptr;      // pressure-energy with grad-h terms: C_i
  // the per-particle factor of the pressure term: sqrt(P)/rho (pressure geometric) or
  // e = (gamma-1) u = P/rho (pressure-energy)
  double *pressure_factor = nullptr;
  double *energy_sum = nullptr;    // pressure-energy with grad-h: sum_j m_j u_j W(h_i)
  double *prho = nullptr;          // the pressure term's P/(Omega rho^2), g or e/P (force pass)
  double *conduct = nullptr;       // physical heat conduction: du/dt of this step
  // adaptive gravitational softening: sum_{j != i} m_j dphi(r_ij, h_i)/dh_i (GradhSettings)
  double *dphidh_sum = nullptr;
};

}    // namespace SPHAstro

#endif
