#pragma once
// pdmpm next to LAMMPS' PERI package on the same problem (perf_problem.hpp), one
// core each: `reps` repetitions, alternating pdmpm and `lmp` (a child process),
// each `steps` time steps with output off (LAMMPS dumps only the first and last
// step, to check agreement). Compared: LAMMPS' "Pair" time from its log (its force
// computation: bond forces plus its short-range contact loop) against pdmpm's
// force time (the model's bond kernels plus its short-range contact), as bond
// evaluations (bond sides × steps) per second per core, and the ratio of medians
// with a bootstrap 95 % interval. The displacement fields must agree as in the
// LAMMPS gate (verification/gates/lammps_comparison_gate.cpp).
#include <nlohmann/json.hpp>
#include <string>

#include "benchmarks/perf/perf_options.hpp"

namespace pdmpm::perf {

// model: "pmb" or "lps". Records its gates and evidence; returns the raw results.
nlohmann::json lammps_side_by_side(const std::string& model, const Options& options);

}  // namespace pdmpm::perf
