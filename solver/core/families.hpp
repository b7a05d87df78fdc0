#pragma once
// Families in CSR form: bonds of particle i are [offsets[i], offsets[i+1]).
// Per bond: the neighbour (int32) and the stencil offset it came from (uint16),
// 6 bytes; lengths, influence and partial volume are looked up per offset.
#include <cstdint>
#include <vector>

#include "solver/core/particles.hpp"
#include "solver/core/stencil.hpp"

namespace pdmpm::core {

// Entries past the last bond in every per-bond array (read, never used, by the
// SIMD bond kernels, which load blocks of 8 bonds).
inline constexpr BondIndex kBondPadding = 8;

template <int D>
struct Families {
  Stencil<D> stencil;
  std::vector<BondIndex> offsets;       // size n_real + 1
  std::vector<Index> neighbor;          // j of each bond
  std::vector<std::uint16_t> shape;     // stencil index of each bond

  BondIndex n_bonds() const { return offsets.empty() ? 0 : offsets.back(); }
  Index n_owners() const { return offsets.empty() ? 0 : static_cast<Index>(offsets.size() - 1); }
  BondIndex begin(Index i) const { return offsets[i]; }
  BondIndex end(Index i) const { return offsets[i + 1]; }

  // Families of every real particle: all particles (ghosts included) within
  // `ratio` lattice spacings. O(N · stencil size), deterministic order.
  static Families build(const Particles<D>& p, double ratio);
};

}  // namespace pdmpm::core
