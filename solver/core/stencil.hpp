#pragma once
// The integer offsets that reach every lattice neighbour within a radius of
// `ratio` lattice spacings. Families are built from it, and each bond stores the
// index of its offset, so bond length and direction are exact table look-ups.
#include <vector>

#include "solver/core/types.hpp"

namespace pdmpm::core {

template <int D>
struct Stencil {
  std::vector<IVec<D>> offset;  // sorted by length, then lexicographically
  std::vector<int> length2;     // squared integer length of each offset

  // All non-zero offsets with |offset| ≤ ratio. The comparison is done on the
  // integer squared length with a relative slack of 1e-10, so that a ratio
  // computed as δ/Δx = 2.9999999999999996 still reaches the bond of length 3.
  static Stencil build(double ratio);
  int size() const { return static_cast<int>(offset.size()); }
};

}  // namespace pdmpm::core
