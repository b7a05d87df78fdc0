#pragma once
// Command-line settings of the performance driver (benchmarks/perf/perf_main.cpp).
#include <cstdint>
#include <filesystem>
#include <set>
#include <string>

namespace pdmpm::perf {

struct Options {
  int refine = 3;           // problem size (perf_problem.hpp): 3 → 10⁷ bond sides
  int reps = 5;             // interleaved repetitions of every timing
  std::int64_t steps = 20;  // time steps per LAMMPS-comparison repetition
  int kernel_calls = 5;     // force evaluations per kernel timing sample
  // MPM step samples start after this many steps of the pulled plate: the middle of the
  // 400-step run issue 19 measured, where part of the plate has yielded.
  std::int64_t mpm_warmup = 200;
  std::set<std::string> parts{"memory", "kernels", "plastic", "hpd", "mpm", "lammps"};
  std::filesystem::path results;  // <results>/bench/perf/*.json, gates/, data/performance/
};

}  // namespace pdmpm::perf
