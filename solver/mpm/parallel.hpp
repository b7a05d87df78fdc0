#pragma once
// Loops shorter than this run on one thread: an OpenMP team costs a fork and a
// barrier per loop, which dominates small bodies (and, on a loaded machine with
// spinning waits, can cost milliseconds each). Results do not depend on it: every
// loop here is gather-only or summed in a fixed order.
#include "solver/core/types.hpp"

namespace pdmpm::mpm {

inline constexpr Index kParallelMin = 4096;

// The particle loops run in the scatter schedule's order: cell block by cell block, so
// consecutive particles are runs of a lattice row (8 in 2D at two sites per cell), too
// short for the hardware prefetcher. Each loop asks for the arrays of the particle this
// many positions on (16 and 32 measured no faster on the 200² plate).
inline constexpr Index kPrefetchAhead = 8;

}  // namespace pdmpm::mpm
