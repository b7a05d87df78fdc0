#pragma once
// Sums whose value does not depend on the number of OpenMP threads: fixed-size
// chunks summed in parallel, chunk sums added in order.
#include <algorithm>
#include <vector>

#include "solver/core/types.hpp"
#include "solver/mpm/parallel.hpp"

namespace pdmpm::mpm {

// Terms per chunk (a distributed run continues the chunks across processes).
inline constexpr Index kSumChunk = 1024;

template <class T, class Fn>
T deterministic_sum(Index n, T zero, Fn&& term) {
  constexpr Index kChunk = kSumChunk;
  const Index chunks = (n + kChunk - 1) / kChunk;
  std::vector<T> partial(static_cast<std::size_t>(chunks), zero);
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (Index c = 0; c < chunks; ++c) {
    T s = zero;
    const Index end = std::min(n, (c + 1) * kChunk);
    for (Index i = c * kChunk; i < end; ++i) s += term(i);
    partial[c] = s;
  }
  T total = zero;
  for (const T& s : partial) total += s;
  return total;
}

}  // namespace pdmpm::mpm
