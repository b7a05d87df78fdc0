#pragma once
// When a run writes history rows and field frames ([output] of the scene).
#include <cstdint>
#include <vector>

#include "solver/io/scene.hpp"

namespace pdmpm::sim {

// A fixed-step explicit run: `time.steps` steps of dt, or enough steps of at most
// dt to reach time.end_time, with dt shortened to land exactly on it.
struct StepPlan {
  double dt = 0.0;
  std::int64_t steps = 0;
  double end_time = 0.0;
};
StepPlan plan_steps(const io::TimeSpec& time, double dt);

// History cadence: output.history_every, else about 1000 rows per run.
std::int64_t history_interval(const io::OutputSpec& out, std::int64_t total_steps);

// Steps at which field frames are written, ascending, always including the last:
// every N steps, the steps nearest output.frame_times (time_per_step converts), or
// `frames` evenly spaced frames (default 11).
std::vector<std::int64_t> frame_steps(const io::OutputSpec& out, std::int64_t total_steps, double time_per_step);

}  // namespace pdmpm::sim
