#pragma once
// Integer types for particle and bond indices (no other dependencies, so the
// SIMD kernel translation units can include it without Eigen).
#include <cstdint>

namespace pdmpm {

using Index = std::int32_t;      // particle index (families store int32 to save bytes per bond)
using BondIndex = std::int64_t;  // position in the CSR bond arrays (10^9 bonds must fit)

}  // namespace pdmpm
