#include "solver/sim/run_recorder.hpp"

#include <omp.h>

#include <fmt/format.h>

#include <algorithm>
#include <csignal>
#include <iostream>
#include <utility>

#include "solver/core/build_info.hpp"
#include "solver/core/error.hpp"
#include "solver/dist/communicator.hpp"
#include "solver/sim/interrupt.hpp"
#include "solver/sim/output_schedule.hpp"
#include "solver/sim/run_metrics.hpp"

namespace pdmpm::sim {

RunRecorder::RunRecorder(const io::Scene& scene, const RunOptions& options)
    : scene_(scene), options_(options), t0_(std::chrono::steady_clock::now()), last_checkpoint_(t0_) {}

void RunRecorder::plan(std::int64_t total_steps, double time_per_step) {
  total_steps_ = total_steps;
  history_every_ = history_interval(scene_.output, total_steps);
  frame_steps_ = frame_steps(scene_.output, total_steps, time_per_step);
}

bool RunRecorder::distributed() const { return options_.comm && options_.comm->size() > 1; }
bool RunRecorder::writer() const { return !distributed() || options_.comm->rank() == 0; }

std::filesystem::path RunRecorder::own_checkpoint() const {
  return options_.out_dir / checkpoint_file(distributed() ? options_.comm->rank() : 0);
}

void RunRecorder::start(const std::vector<std::string>& columns, int dimension, double progress_end_time,
                        const std::string& counter) {
  check_checkpoint_options();
  if (resuming())  // the frames after the checkpoint's step are still to come (on every process)
    next_frame_ = static_cast<std::size_t>(std::upper_bound(frame_steps_.begin(), frame_steps_.end(), resume_step()) -
                                           frame_steps_.begin());
  if (!distributed()) {
    open_outputs(columns, dimension, progress_end_time, counter);
    return;
  }
  if (!writer() && resuming()) {  // what process 0 reads of its own file, read here too
    std::int64_t rows = 0;
    options_.resume->state.sync("recorder/history_rows", rows);
    options_.resume->state.sync("recorder/wall_seconds", earlier_wall_seconds_);
  }
  // Process 0 opens the outputs; every process learns whether it could, so an output
  // directory that cannot be written stops them all before the first step.
  std::exception_ptr failure;
  if (writer()) {
    try {
      open_outputs(columns, dimension, progress_end_time, counter);
    } catch (...) {
      failure = std::current_exception();
    }
  }
  dist::agree_on_failure(*options_.comm, failure);
}

void RunRecorder::open_outputs(const std::vector<std::string>& columns, int dimension, double progress_end_time,
                               const std::string& counter) {
  out_ = std::make_unique<io::OutputDirectory>(options_.out_dir);
  if (resuming()) {
    open_resumed_outputs(columns, dimension);
  } else {
    history_ = std::make_unique<io::HistoryWriter>(out_->path("history.csv"), columns);
    if (options_.write_fields)
      fields_ = std::make_unique<io::FieldsWriter>(out_->path("fields.h5"), out_->path("fields.xdmf"), "fields.h5",
                                                   dimension);
  }
  if (options_.progress) {
    progress_ = std::make_unique<io::Progress>(std::cerr, io::Progress::stderr_is_terminal(), total_steps_,
                                               progress_end_time, scene_.id);
    progress_->set_counter_name(counter);
  }
}

void RunRecorder::check_checkpoint_options() const {
  const bool periodic = options_.checkpoint_every_steps > 0 || options_.checkpoint_every_seconds > 0.0;
  if ((periodic || resuming()) && !state_)
    throw InputError(scene_.file, "", fmt::format("this run cannot write checkpoints: {}", no_checkpoint_reason_));
}

std::int64_t RunRecorder::resume_step() const { return resuming() ? options_.resume->info.step : 0; }

// The outputs of the checkpointed run are copied into this run's staging directory,
// cut back to the checkpoint (rows and frames written after it go), and continued.
void RunRecorder::open_resumed_outputs(const std::vector<std::string>& columns, int dimension) {
  auto& a = options_.resume->state;
  const auto source = options_.resume->outputs();
  std::int64_t rows = 0;
  a.sync("recorder/history_rows", rows);
  a.sync("recorder/wall_seconds", earlier_wall_seconds_);
  history_ = std::make_unique<io::HistoryWriter>(io::HistoryWriter::resume(
      source / "history.csv", out_->path("history.csv"), columns, static_cast<std::size_t>(rows)));
  if (options_.write_fields)
    fields_ = std::make_unique<io::FieldsWriter>(io::FieldsWriter::resume(
        source / "fields.h5", out_->path("fields.h5"), out_->path("fields.xdmf"), "fields.h5", dimension, a));
}

void RunRecorder::restore() {
  auto& a = options_.resume->state;
  state_(a);
  if (const auto left = a.unread(); !left.empty())
    throw core::StateMismatch(fmt::format("the checkpoint holds state this run does not have ('{}', …)", left.front()));
}

void RunRecorder::write_checkpoint(std::int64_t step, const std::filesystem::path& path, const std::string& outputs) {
  core::StateArchive a(core::StateArchive::Mode::save);
  CheckpointInfo info{build_info::git_sha(),
                      scene_.file,
                      scene_.text,
                      outputs,
                      step,
                      options_.write_fields,
                      distributed() ? options_.comm->size() : 1};
  sync_info(a, info);
  auto rows = history_ ? static_cast<std::int64_t>(history_->rows()) : 0;
  double wall = earlier_wall_seconds_ + seconds_since(t0_);
  a.sync("recorder/history_rows", rows);
  a.sync("recorder/wall_seconds", wall);
  if (fields_) fields_->checkpoint(a);
  state_(a);
  write_checkpoint_file(a, path);
  last_checkpoint_ = std::chrono::steady_clock::now();
}

bool RunRecorder::after_step(std::int64_t step, double t) {
  if (step == options_.interrupt_at_step) request_interrupt(SIGINT);
  int signal = interrupt_requested();
  // Every process stops after the same step, whichever received the signal.
  if (distributed()) signal = static_cast<int>(options_.comm->max(signal));
  if (signal) {
    clear_interrupt();  // handled: a later run in this process starts afresh
    const char* name = signal == SIGTERM ? "SIGTERM" : "SIGINT";
    if (state_) {
      // Into the staging directory: the checkpoint is committed with the outputs it continues
      // (the other processes' files go beside the outputs: a commit moves files one by one).
      write_checkpoint(step, writer() ? out_->path(kCheckpointFile) : own_checkpoint(), "");
      const std::string launcher = distributed() ? fmt::format("mpirun -n {} ", options_.comm->size()) : "";
      stop("interrupted",
           fmt::format("interrupted by {} after step {} (t = {:.6g}); continue with: {}pdmpm resume {}", name, step, t,
                       launcher, options_.out_dir.string()));
    } else {
      stop("interrupted",
           fmt::format("interrupted by {} after step {} (t = {:.6g}); no checkpoint: {}", name, step, t,
                       no_checkpoint_reason_));
    }
    return true;
  }
  if (!state_ || step >= total_steps_) return false;
  bool due = (options_.checkpoint_every_steps > 0 && step % options_.checkpoint_every_steps == 0) ||
      (options_.checkpoint_every_seconds > 0.0 && seconds_since(last_checkpoint_) >= options_.checkpoint_every_seconds);
  // A wall-time interval: when one process's clock says so, every process writes its file.
  if (distributed()) due = options_.comm->max(due ? 1.0 : 0.0) > 0.0;
  if (due) write_checkpoint(step, own_checkpoint(), writer() ? out_->staging().filename().string() : std::string());
  return false;
}

bool RunRecorder::frame_due(std::int64_t step) {
  if (next_frame_ < frame_steps_.size() && frame_steps_[next_frame_] == step) {
    ++next_frame_;
    return true;
  }
  return false;
}

void RunRecorder::write_frame(std::int64_t step, double t, const std::vector<double>& positions,
                              const std::vector<io::Field>& fields) {
  if (!options_.write_fields) return;
  if (!distributed()) {
    fields_->write_frame(step, t, positions, fields);
    return;
  }
  // Own particles are a contiguous range of the global order: gathered in rank order,
  // the frame is the one-process frame.
  const auto& comm = *options_.comm;
  std::vector<io::Field> all;
  all.reserve(fields.size());
  for (const auto& f : fields) all.push_back({f.name, f.kind, comm.gather(f.values)});
  const auto all_positions = comm.gather(positions);
  if (fields_) fields_->write_frame(step, t, all_positions, all);
}

void RunRecorder::stop(std::string status, std::string message) {
  status_ = std::move(status);
  message_ = std::move(message);
}

void RunRecorder::warn(const std::string& key, const std::string& text, std::int64_t step, double t) {
  for (const Warning& w : warnings_)
    if (w.key == key) return;
  warnings_.push_back({key, text, step, t});
  if (writer()) std::cerr << "\npdmpm: warning: " << text << "\n";
}

RunResult RunRecorder::finish(std::int64_t steps_done, double t, std::int64_t count, Index particles,
                              nlohmann::json method_keys) {
  if (progress_) progress_->finish(steps_done, t, count);
  if (fields_) fields_->close();
  history_.reset();
  const double wall = earlier_wall_seconds_ + seconds_since(t0_);
  nlohmann::json warnings = nlohmann::json::array();
  for (const Warning& w : warnings_)
    warnings.push_back({{"key", w.key}, {"step", w.step}, {"time", w.time}, {"text", w.text}});
  nlohmann::json summary = std::move(method_keys);
  summary.update(
      {{"scene", scene_.id},
       {"file", scene_.file},
       {"description", scene_.description},
       {"status", status_},
       {"message", message_},
       {"warnings", warnings},
       {"steps", steps_done},
       {"steps_requested", total_steps_},
       {"threads", omp_get_max_threads()},
       {"processes", distributed() ? options_.comm->size() : 1},
       {"wall_time_s", wall},
       {"peak_memory_bytes", peak_memory_bytes()},
       {"particle_steps_per_second",
        wall > 0 ? static_cast<double>(particles) * static_cast<double>(steps_done) / wall : 0.0},
       {"provenance",
        {{"git_sha", build_info::git_sha()}, {"compiler", build_info::compiler()}, {"flags", build_info::flags()}}}});
  std::error_code ignored;
  if (!writer()) {
    if (status_ != "interrupted") std::filesystem::remove(own_checkpoint(), ignored);
    return uncommitted_run(status_, message_, std::move(summary));
  }
  RunResult result = commit_run(*out_, status_, message_, std::move(summary));
  // What the committed outputs replace: a periodic checkpoint (the run has ended; one
  // that stopped at a signal has just committed its own) and the staging directory
  // of a killed run that this one continued.
  if (status_ != "interrupted") std::filesystem::remove(own_checkpoint(), ignored);
  if (resuming() && options_.resume->info.outputs.starts_with(".partial-"))
    std::filesystem::remove_all(options_.out_dir / options_.resume->info.outputs, ignored);
  return result;
}

}  // namespace pdmpm::sim
