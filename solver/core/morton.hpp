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

// The inverses: every second (2D) or third (3D) bit of v, packed.
inline std::uint64_t compact_bits_3(std::uint64_t v) {
  v &= 0x1249249249249249ULL;
  v = (v | v >> 2) & 0x10c30c30c30c30c3ULL;
  v = (v | v >> 4) & 0x100f00f00f00f00fULL;
  v = (v | v >> 8) & 0x1f0000ff0000ffULL;
  v = (v | v >> 16) & 0x1f00000000ffffULL;
  v = (v | v >> 32) & 0x1fffffULL;
  return v;
}

inline std::uint64_t compact_bits_2(std::uint64_t v) {
  v &= 0x5555555555555555ULL;
  v = (v | v >> 1) & 0x3333333333333333ULL;
  v = (v | v >> 2) & 0x0f0f0f0f0f0f0f0fULL;
  v = (v | v >> 4) & 0x00ff00ff00ff00ffULL;
  v = (v | v >> 8) & 0x0000ffff0000ffffULL;
  v = (v | v >> 16) & 0x00000000ffffffffULL;
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

// The site of a key (morton_key's inverse).
template <int D>
IVec<D> morton_site(std::uint64_t key, const IVec<D>& lowest) {
  IVec<D> s;
  if constexpr (D == 1) s[0] = static_cast<std::int32_t>(key);
  if constexpr (D == 2)
    s << static_cast<std::int32_t>(compact_bits_2(key)), static_cast<std::int32_t>(compact_bits_2(key >> 1));
  if constexpr (D == 3)
    s << static_cast<std::int32_t>(compact_bits_3(key)), static_cast<std::int32_t>(compact_bits_3(key >> 1)),
        static_cast<std::int32_t>(compact_bits_3(key >> 2));
  return s + lowest;
}

// Whether morton_key can encode the site (coordinates from `lowest` within its bits).
template <int D>
bool morton_encodable(const IVec<D>& site, const IVec<D>& lowest) {
  constexpr std::int64_t limit = D == 1 ? (std::int64_t{1} << 62) : D == 2 ? (std::int64_t{1} << 32) : (1 << 21);
  for (int a = 0; a < D; ++a) {
    const std::int64_t c = std::int64_t{site[a]} - lowest[a];
    if (c < 0 || c >= limit) return false;
  }
  return true;
}

}  // namespace pdmpm::core
