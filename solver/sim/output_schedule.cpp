#include "solver/sim/output_schedule.hpp"

#include <algorithm>
#include <cmath>

namespace pdmpm::sim {

StepPlan plan_steps(const io::TimeSpec& time, double dt) {
  StepPlan p;
  p.dt = dt;
  if (time.steps) {
    p.steps = *time.steps;
  } else {
    p.steps = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(*time.end_time / dt * (1.0 - 1e-12))));
    p.dt = *time.end_time / static_cast<double>(p.steps);  // land exactly on end_time
  }
  p.end_time = p.dt * static_cast<double>(p.steps);
  return p;
}

std::int64_t history_interval(const io::OutputSpec& out, std::int64_t total_steps) {
  return out.history_every.value_or(std::max<std::int64_t>(1, total_steps / 1000));
}

std::vector<std::int64_t> frame_steps(const io::OutputSpec& out, std::int64_t total_steps, double time_per_step) {
  std::vector<std::int64_t> steps;
  if (out.every) {
    for (std::int64_t s = 0; s <= total_steps; s += *out.every) steps.push_back(s);
  } else if (!out.frame_times.empty()) {
    steps.push_back(0);
    for (double t : out.frame_times)
      steps.push_back(std::clamp<std::int64_t>(std::llround(t / time_per_step), 0, total_steps));
  } else {
    const std::int64_t frames = out.frames.value_or(std::min<std::int64_t>(11, total_steps + 1));
    for (std::int64_t k = 0; k < frames; ++k)
      steps.push_back(frames == 1 ? total_steps : (k * total_steps) / (frames - 1));
  }
  std::sort(steps.begin(), steps.end());
  steps.erase(std::unique(steps.begin(), steps.end()), steps.end());
  if (steps.empty() || steps.back() != total_steps) steps.push_back(total_steps);
  return steps;
}

}  // namespace pdmpm::sim
