#pragma once
// The force kernels alone (the model's compute_forces, no contact, no breaking)
// on the 10⁷-bond problem, measured interleaved with a memory-bandwidth triad in
// the same process:
//  - thread scaling: seconds per evaluation on 1 and 2 threads, ratio of medians;
//  - roofline: bond sides per second × bytes per bond side (bytes_per_bond.hpp)
//    against the triad's bandwidth on as many threads, and the same kernel on the
//    refine-1 problem (3.5 k particles, every array in the last-level cache): if
//    the in-cache rate is no higher, memory is not what limits the kernel.
#include <nlohmann/json.hpp>

#include "benchmarks/perf/perf_options.hpp"

namespace pdmpm::perf {

// Records the thread-scaling and bandwidth targets and their evidence; returns the raw results.
nlohmann::json kernel_scaling(const Options& options);

}  // namespace pdmpm::perf
