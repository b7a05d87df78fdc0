#pragma once
// Bytes an MPM step (MUSL, log-strain law) must move between memory and the core per
// particle, from the data layout: the memory-traffic floor of the step, to set
// against the triad's bandwidth.
//
// The account counts the particle arrays each pass streams, read and written
// (write-allocate reads not counted, as in STREAM): per pass the schedule index and
// the particle's stencil, then what the pass reads or writes of the particle state.
// The grid (a node per cell, 2–3 particles per cell side) is not counted: a block of
// cells stays in cache while its particles are scattered or gathered. The account
// follows solver/mpm/simulation.cpp; a change of layout there changes it here.
#include <string>
#include <utility>
#include <vector>

namespace pdmpm::perf {

struct MpmByteAccount {
  std::vector<std::pair<std::string, double>> phases;  // phase, bytes per particle-step
  double total = 0.0;
};

template <int D>
MpmByteAccount mpm_bytes_per_particle_step();

}  // namespace pdmpm::perf
