#pragma once
// The MPM's lane functions (lanes.hpp) come in one version per instruction set;
// the widest the machine runs is used, or the one PDMPM_SIMD names (as for the PD
// bond kernels). The tests compare every version with the scalar code.
#include <cstdlib>
#include <cstring>
#include <vector>

namespace pdmpm::mpm {

// One version of a lane function per instruction set the machine runs.
template <class Function>
struct LaneVariant {
  const char* name;  // "sse2", "avx2", "avx512"
  Function function;
};

// The versions this machine runs, narrowest first.
template <class Function>
std::vector<LaneVariant<Function>> lane_variants(Function sse2, Function avx2, Function avx512) {
  std::vector<LaneVariant<Function>> v{{"sse2", sse2}};
  if (__builtin_cpu_supports("avx2")) v.push_back({"avx2", avx2});
  if (__builtin_cpu_supports("avx512f")) v.push_back({"avx512", avx512});
  return v;
}

// The widest version, or the one PDMPM_SIMD names (as for the PD bond kernels).
template <class Function>
Function choose_lane_variant(const std::vector<LaneVariant<Function>>& variants) {
  if (const char* want = std::getenv("PDMPM_SIMD"))
    for (const auto& v : variants)
      if (std::strcmp(want, v.name) == 0) return v.function;
  return variants.back().function;
}

}  // namespace pdmpm::mpm
