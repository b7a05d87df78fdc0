#pragma once
// Non-local average of a particle field (after Burghardt, Brannon & Guilkey 2012):
//   ⟨a⟩_p = Σ_q w(|x_p − x_q|) V_q a_q / Σ_q w V_q,  w(r) = exp(−(r/ℓ)²), r ≤ 3ℓ,
// over the particles flagged in `use`. Neighbours come from a cell list of cell size
// 3ℓ; each particle gathers its own sum in a fixed order (deterministic, no atomics).
#include <cstdint>
#include <vector>

#include "solver/core/types.hpp"

namespace pdmpm::mpm {

template <int D>
void nonlocal_average(const std::vector<Vec<D>>& x, const std::vector<double>& volume, const std::vector<double>& a,
                      const std::vector<std::uint8_t>& use, double length, std::vector<double>& out);

}  // namespace pdmpm::mpm
