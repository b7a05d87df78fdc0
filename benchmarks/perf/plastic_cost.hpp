#pragma once
// The cost of plasticity in the PD force evaluation (issue 13's speed target):
// elastoplastic LPS against elastic LPS on the same cube, one thread, interleaved
// repetitions in one process. Two states of the plastic model: every bond side
// returning (σ_y far below the stress of the deformation) and the elastic range
// (σ_y far above it), the first being the target's case.
#include <nlohmann/json.hpp>

#include "benchmarks/perf/perf_options.hpp"

namespace pdmpm::perf {

// Records the "performance.plastic_cost" target; returns the raw timings.
nlohmann::json plastic_cost(const Options& options);

}  // namespace pdmpm::perf
