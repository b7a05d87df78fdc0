#include "solver/sim/run_recorder.hpp"

#include <omp.h>

#include <iostream>
#include <utility>

#include "solver/core/build_info.hpp"
#include "solver/sim/output_schedule.hpp"
#include "solver/sim/run_metrics.hpp"

namespace pdmpm::sim {

RunRecorder::RunRecorder(const io::Scene& scene, const RunOptions& options)
    : scene_(scene), options_(options), t0_(std::chrono::steady_clock::now()) {}

void RunRecorder::plan(std::int64_t total_steps, double time_per_step) {
  total_steps_ = total_steps;
  history_every_ = history_interval(scene_.output, total_steps);
  frame_steps_ = frame_steps(scene_.output, total_steps, time_per_step);
}

void RunRecorder::start(const std::vector<std::string>& columns, int dimension, double progress_end_time,
                        const std::string& counter) {
  out_ = std::make_unique<io::OutputDirectory>(options_.out_dir);
  history_ = std::make_unique<io::HistoryWriter>(out_->path("history.csv"), columns);
  if (options_.write_fields)
    fields_ = std::make_unique<io::FieldsWriter>(out_->path("fields.h5"), out_->path("fields.xdmf"), "fields.h5",
                                                 dimension);
  if (options_.progress) {
    progress_ = std::make_unique<io::Progress>(std::cerr, io::Progress::stderr_is_terminal(), total_steps_,
                                               progress_end_time, scene_.id);
    progress_->set_counter_name(counter);
  }
}

bool RunRecorder::frame_due(std::int64_t step) {
  if (next_frame_ < frame_steps_.size() && frame_steps_[next_frame_] == step) {
    ++next_frame_;
    return true;
  }
  return false;
}

void RunRecorder::stop(std::string status, std::string message) {
  status_ = std::move(status);
  message_ = std::move(message);
}

RunResult RunRecorder::finish(std::int64_t steps_done, double t, std::int64_t count, Index particles,
                              nlohmann::json method_keys) {
  if (progress_) progress_->finish(steps_done, t, count);
  if (fields_) fields_->close();
  history_.reset();
  const double wall = seconds_since(t0_);
  nlohmann::json summary = std::move(method_keys);
  summary.update({{"scene", scene_.id},
                  {"file", scene_.file},
                  {"description", scene_.description},
                  {"status", status_},
                  {"message", message_},
                  {"steps", steps_done},
                  {"steps_requested", total_steps_},
                  {"threads", omp_get_max_threads()},
                  {"wall_time_s", wall},
                  {"peak_memory_bytes", peak_memory_bytes()},
                  {"particle_steps_per_second",
                   wall > 0 ? static_cast<double>(particles) * static_cast<double>(steps_done) / wall : 0.0},
                  {"provenance",
                   {{"git_sha", build_info::git_sha()}, {"compiler", build_info::compiler()}, {"flags", build_info::flags()}}}});
  return commit_run(*out_, status_, message_, std::move(summary));
}

}  // namespace pdmpm::sim
