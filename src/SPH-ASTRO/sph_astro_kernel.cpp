/* ----------------------------------------------------------------------
   SPH-ASTRO - astrophysical SPH for LAMMPS

   This software is distributed under the GNU General Public License version 2
   (the same licence as LAMMPS); see the LICENSE file.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   SPH-ASTRO: run-time access to the kernels of sph_astro_kernel.h
------------------------------------------------------------------------- */

#include "sph_astro_kernel.h"

#include <cstring>

namespace SPHAstro {

namespace {
  template <class K, int DIM> double W_of(double r, double h)
  {
    const double hinv = 1.0 / h;
    return Kernel<K, DIM>::sigma() * inv_h_pow_dim<DIM>(hinv) * Kernel<K, DIM>::w(r * hinv);
  }
  template <class K, int DIM> double dW_of(double r, double h)
  {
    const double hinv = 1.0 / h;
    return Kernel<K, DIM>::sigma() * inv_h_pow_dim<DIM>(hinv) * hinv * Kernel<K, DIM>::dw(r * hinv);
  }
  template <class K> double W_dim(int dim, double r, double h)
  {
    return dim == 1 ? W_of<K, 1>(r, h) : (dim == 2 ? W_of<K, 2>(r, h) : W_of<K, 3>(r, h));
  }
  template <class K> double dW_dim(int dim, double r, double h)
  {
    return dim == 1 ? dW_of<K, 1>(r, h) : (dim == 2 ? dW_of<K, 2>(r, h) : dW_of<K, 3>(r, h));
  }
}    // namespace

double kernel_W(KernelType type, int dim, double r, double h)
{
  switch (type) {
    case KernelType::CUBIC:
      return W_dim<KernelCubic>(dim, r, h);
    case KernelType::QUINTIC:
      return W_dim<KernelQuintic>(dim, r, h);
    case KernelType::WENDLAND_C2:
      return W_dim<KernelWendlandC2>(dim, r, h);
    case KernelType::WENDLAND_C4:
      return W_dim<KernelWendlandC4>(dim, r, h);
    case KernelType::GAUSSIAN:
      return W_dim<KernelGaussian>(dim, r, h);
  }
  return 0.0;
}

double kernel_dWdr(KernelType type, int dim, double r, double h)
{
  switch (type) {
    case KernelType::CUBIC:
      return dW_dim<KernelCubic>(dim, r, h);
    case KernelType::QUINTIC:
      return dW_dim<KernelQuintic>(dim, r, h);
    case KernelType::WENDLAND_C2:
      return dW_dim<KernelWendlandC2>(dim, r, h);
    case KernelType::WENDLAND_C4:
      return dW_dim<KernelWendlandC4>(dim, r, h);
    case KernelType::GAUSSIAN:
      return dW_dim<KernelGaussian>(dim, r, h);
  }
  return 0.0;
}

double kernel_radius(KernelType type)
{
  switch (type) {
    case KernelType::CUBIC:
      return KernelCubic::radius;
    case KernelType::QUINTIC:
      return KernelQuintic::radius;
    case KernelType::WENDLAND_C2:
      return KernelWendlandC2::radius;
    case KernelType::WENDLAND_C4:
      return KernelWendlandC4::radius;
    case KernelType::GAUSSIAN:
      return KernelGaussian::radius;
  }
  return 0.0;
}

const char *kernel_name(KernelType type)
{
  switch (type) {
    case KernelType::CUBIC:
      return KernelCubic::name;
    case KernelType::QUINTIC:
      return KernelQuintic::name;
    case KernelType::WENDLAND_C2:
      return KernelWendlandC2::name;
    case KernelType::WENDLAND_C4:
      return KernelWendlandC4::name;
    case KernelType::GAUSSIAN:
      return KernelGaussian::name;
  }
  return "";
}

bool kernel_from_name(const char *name, KernelType &type)
{
  const KernelType all[] = {KernelType::CUBIC, KernelType::QUINTIC, KernelType::WENDLAND_C2,
                            KernelType::WENDLAND_C4, KernelType::GAUSSIAN};
  for (auto k : all)
    if (strcmp(name, kernel_name(k)) == 0) {
      type = k;
      return true;
    }
  if (strcmp(name, "cubic") == 0) {
    type = KernelType::CUBIC;
    return true;
  }
  if (strcmp(name, "quintic") == 0) {
    type = KernelType::QUINTIC;
    return true;
  }
  return false;
}

}    // namespace SPHAstro
