#include "solver/pd/kernels/bond_kernels.hpp"

#include <cstdlib>
#include <cstring>

#include "solver/pd/kernels/kernel_set.hpp"

namespace pdmpm::pd::kernels {
namespace {

const KernelSet& choose() {
  const bool avx512 =
      __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq");
  const bool avx2 = __builtin_cpu_supports("avx2");
  if (const char* want = std::getenv("PDMPM_SIMD")) {
    if (std::strcmp(want, "sse2") == 0) return kernels_sse2;
    if (std::strcmp(want, "avx2") == 0 && avx2) return kernels_avx2;
    if (std::strcmp(want, "avx512") == 0 && avx512) return kernels_avx512;
  }
  if (avx512) return kernels_avx512;
  if (avx2) return kernels_avx2;
  return kernels_sse2;
}

const KernelSet& active() {
  static const KernelSet& set = choose();
  return set;
}

}  // namespace

template <int D>
std::int64_t pmb_forces(const PmbArgs& a) {
  return active().pmb[D - 1][a.energy != nullptr](a);
}
template <int D>
std::int64_t lps_dilatation(const LpsArgs& a) {
  return active().lps_dilatation[D - 1](a);
}
template <int D>
std::int64_t lps_forces(const LpsArgs& a) {
  return active().lps_forces[D - 1][a.energy != nullptr](a);
}
template <int D>
std::int64_t lps_plastic_extension(const LpsPlasticArgs& a) {
  return active().lps_plastic_extension[D - 1](a);
}
template <int D>
std::int64_t lps_plastic_forces(const LpsPlasticArgs& a) {
  return active().lps_plastic_forces[D - 1][a.lps.energy != nullptr](a);
}
const char* simd_level() { return active().name; }

template std::int64_t pmb_forces<1>(const PmbArgs&);
template std::int64_t pmb_forces<2>(const PmbArgs&);
template std::int64_t pmb_forces<3>(const PmbArgs&);
template std::int64_t lps_dilatation<1>(const LpsArgs&);
template std::int64_t lps_dilatation<2>(const LpsArgs&);
template std::int64_t lps_dilatation<3>(const LpsArgs&);
template std::int64_t lps_forces<1>(const LpsArgs&);
template std::int64_t lps_plastic_extension<1>(const LpsPlasticArgs&);
template std::int64_t lps_plastic_forces<1>(const LpsPlasticArgs&);
template std::int64_t lps_forces<2>(const LpsArgs&);
template std::int64_t lps_plastic_extension<2>(const LpsPlasticArgs&);
template std::int64_t lps_plastic_forces<2>(const LpsPlasticArgs&);
template std::int64_t lps_forces<3>(const LpsArgs&);
template std::int64_t lps_plastic_extension<3>(const LpsPlasticArgs&);
template std::int64_t lps_plastic_forces<3>(const LpsPlasticArgs&);

}  // namespace pdmpm::pd::kernels
