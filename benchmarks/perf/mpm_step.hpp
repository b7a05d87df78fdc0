#pragma once
// The premise of the adaptive hybrid, measured: an MPM particle-step (GIMP, MUSL,
// J2, the step a run takes) against a PD particle-step (velocity Verlet with elastic
// LPS, ω = 1/|ξ|, δ = 3.015Δx; and with elastoplastic LPS) on the same body — a
// plane-stress steel plate (100² and 200² particles) and a cube (20³ and 40³), its
// top and bottom pulled apart at 20 m/s so the material yields. Interleaved
// repetitions in one process, 1 and 2 threads; the MPM step split by phase.
#include <nlohmann/json.hpp>

#include "benchmarks/perf/perf_options.hpp"

namespace pdmpm::perf {

// Records the performance.mpm_* targets and the phase table; returns the raw timings.
nlohmann::json mpm_step(const Options& options);

}  // namespace pdmpm::perf
