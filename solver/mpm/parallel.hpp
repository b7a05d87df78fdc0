#pragma once
// Loops shorter than this run on one thread: an OpenMP team costs a fork and a
// barrier per loop, which dominates small bodies (and, on a loaded machine with
// spinning waits, can cost milliseconds each). Results do not depend on it: every
// loop here is gather-only or summed in a fixed order.
#include <algorithm>
#include <limits>

#include "solver/core/types.hpp"

namespace pdmpm::mpm {

inline constexpr Index kParallelMin = 4096;

// The particle loops run in the scatter schedule's order: cell block by cell block, so
// consecutive particles are runs of a lattice row (8 in 2D at two sites per cell), too
// short for the hardware prefetcher. Each loop asks for the arrays of the particle this
// many positions on (16 and 32 measured no faster on the 200² plate).
inline constexpr Index kPrefetchAhead = 8;

// Groups 0 … groups − 1 of particles in a static OpenMP loop, each group's lane inputs
// gathered one group ahead: gather(g, buffer) fills buffer with group g's inputs, then
// compute(g, buffer) runs the lane functions on them and returns the lowest bad particle
// (or kNoParticle). A lane function's first vector load of eight scalar stores made just
// before waits until they retire (store forwarding fails); gathered a group ahead they
// have. Returns the lowest bad particle of all groups.
inline constexpr Index kNoParticle = std::numeric_limits<Index>::max();
template <class Buffer, class Gather, class Compute>
Index for_each_group_gathered_ahead(Index groups, bool parallel, Gather&& gather, Compute&& compute) {
  Index bad = kNoParticle;
#pragma omp parallel reduction(min : bad) if (parallel)
  {
    Buffer buffer[2];
    Index ready = -1;  // the group gathered into buffer[ready & 1] ahead
#pragma omp for schedule(static)
    for (Index g = 0; g < groups; ++g) {
      if (ready != g) gather(g, buffer[g & 1]);  // the first group of this thread's run
      if (g + 1 < groups) {
        gather(g + 1, buffer[(g + 1) & 1]);
        ready = g + 1;
      }
      bad = std::min(bad, compute(g, buffer[g & 1]));
    }
  }
  return bad;
}

}  // namespace pdmpm::mpm
