#pragma once
// Z-order (Morton) keys of lattice sites: sorting particles by them puts a
// particle's family close in memory, which is what the bond loops live on.
#include <cstdint>

#include "solver/core/types.hpp"

namespace pdmpm::core {

// Spread the low 21 bits of v so that two zero bits separate each (3D), or
// the low 32 bits with one zero bit between each (2D).
inline std::uint64_t spread_bits_3(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

inline std::uint64_t spread_bits_2(std::uint64_t v) {
  v &= 0xffffffffULL;
  v = (v | v << 16) & 0x0000ffff0000ffffULL;
  v = (v | v << 8) & 0x00ff00ff00ff00ffULL;
  v = (v | v << 4) & 0x0f0f0f0f0f0f0f0fULL;
  v = (v | v << 2) & 0x3333333333333333ULL;
  v = (v | v << 1) & 0x5555555555555555ULL;
  return v;
}

// Key of a site relative to the lowest site of the body (all coordinates ≥ 0).
template <int D>
std::uint64_t morton_key(const IVec<D>& site, const IVec<D>& lowest) {
  const IVec<D> s = site - lowest;
  if constexpr (D == 1) return static_cast<std::uint64_t>(s[0]);
  if constexpr (D == 2) return spread_bits_2(s[0]) | spread_bits_2(s[1]) << 1;
  if constexpr (D == 3) return spread_bits_3(s[0]) | spread_bits_3(s[1]) << 1 | spread_bits_3(s[2]) << 2;
}

}  // namespace pdmpm::core
