#pragma once
// Loops shorter than this run on one thread: an OpenMP team costs a fork and a
// barrier per loop, which dominates small bodies (and, on a loaded machine with
// spinning waits, can cost milliseconds each). Results do not depend on it: every
// loop here is gather-only or summed in a fixed order.
#include "solver/core/types.hpp"

namespace pdmpm::mpm {

inline constexpr Index kParallelMin = 4096;

}  // namespace pdmpm::mpm
