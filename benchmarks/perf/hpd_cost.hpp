#pragma once
// The cost of the stabilized hybrid PD model (solver/pd/hpd.hpp) per bond side, against elastic
// LPS on the same cube: one thread, interleaved repetitions in one process, as plastic_cost.hpp.
// Both nD (linear_elastic, sub-horizon fits) and 1D (axial_1d, PMB's bond loop) laws.
#include <nlohmann/json.hpp>

#include "benchmarks/perf/perf_options.hpp"

namespace pdmpm::perf {

// Prints the ratios and returns the raw timings (no target: issue 16 sets none).
nlohmann::json hpd_cost(const Options& options);

}  // namespace pdmpm::perf
