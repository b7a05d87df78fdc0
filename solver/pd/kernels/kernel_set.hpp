#pragma once
// One set of bond-loop entry points per instruction set (see bond_kernels.hpp).
#include "solver/pd/kernels/bond_kernels.hpp"

namespace pdmpm::pd::kernels {

struct KernelSet {
  const char* name;
  // Index [D - 1][with energy].
  std::int64_t (*pmb[3][2])(const PmbArgs&);
  std::int64_t (*lps_dilatation[3])(const LpsArgs&);
  std::int64_t (*lps_forces[3][2])(const LpsArgs&);
  std::int64_t (*lps_plastic_extension[3])(const LpsPlasticArgs&);
  std::int64_t (*lps_plastic_forces[3][2])(const LpsPlasticArgs&);
};

extern const KernelSet kernels_sse2;
extern const KernelSet kernels_avx2;
extern const KernelSet kernels_avx512;

}  // namespace pdmpm::pd::kernels
