#pragma once
// What every run writes, whichever method moves the body: the staged output
// directory (all or nothing), history.csv, fields.h5 + fields.xdmf, the frame
// and history schedule, progress, the status of a run that stops early, and the
// summary keys every run has. A method's run (pd_run, mpm_run, and the hybrid's
// later) is a thin adaptor: it owns the time loop and contributes its history
// columns and rows, its fields and its own summary keys.
//
// The adaptor calls the recorder, not the other way round: the loops of the
// methods differ (Verlet steps, ADR load steps, MPM steps; a hybrid step), and
// each already knows when it has a row or a frame to give.
//
// A distributed run (RunOptions::comm): every process calls the recorder at the
// same points with the whole body's values in history rows (the adaptor reduces
// them) and its own particles' in frames (gathered here, in the global order);
// process 0 alone writes the outputs, so they are those of one process. Each
// process writes its own checkpoint file (sim/checkpoint.hpp), at the same steps.
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "solver/core/error.hpp"
#include "solver/io/fields_writer.hpp"
#include "solver/io/history_writer.hpp"
#include "solver/io/output_directory.hpp"
#include "solver/io/progress.hpp"
#include "solver/io/scene.hpp"
#include "solver/sim/checkpoint.hpp"
#include "solver/sim/run.hpp"

namespace pdmpm::sim {

class RunRecorder {
 public:
  RunRecorder(const io::Scene& scene, const RunOptions& options);

  // The schedule: `total_steps` steps (or load steps), `time_per_step` to place
  // frames given by time. History every `history_every()` steps and at the last.
  void plan(std::int64_t total_steps, double time_per_step);
  std::int64_t total_steps() const { return total_steps_; }
  std::int64_t history_every() const { return history_every_; }
  bool history_due(std::int64_t step) const { return step % history_every_ == 0 || step == total_steps_; }

  // Stages the output directory and opens history (with these columns), the
  // fields writer (unless the run was asked not to write fields) and progress
  // (lines up to `progress_end_time`, 0 for a load factor; `counter` names the
  // count in each line).
  void start(const std::vector<std::string>& columns, int dimension, double progress_end_time,
             const std::string& counter = "broken");

  // Checkpoints (sim/checkpoint.hpp): before start(), the function that passes the
  // method's state through an archive, or why this run has none (then a checkpoint
  // interval is refused and an interrupt stops the run without one).
  using StateFn = std::function<void(core::StateArchive&)>;
  void checkpoints(StateFn state) { state_ = std::move(state); }
  void no_checkpoints(std::string why) { no_checkpoint_reason_ = std::move(why); }
  // A resumed run: the step its checkpoint was written after, and, after start(), the
  // restore of the method's state (core::StateMismatch if the checkpoint does not fit).
  bool resuming() const { return options_.resume != nullptr; }
  std::int64_t resume_step() const;
  void restore();
  // After every step, once its history row and frame are written: writes a checkpoint
  // when one is due; true when the run must stop (a signal asked), then with its
  // checkpoint written and status "interrupted".
  bool after_step(std::int64_t step, double t);

  void write_history(const std::vector<double>& row) {
    if (history_) history_->write_row(row);
  }
  // True once per scheduled frame step (then give it to write_frame()).
  bool frame_due(std::int64_t step);
  // False when the run was asked not to write fields (then skip building frames).
  bool writes_fields() const { return options_.write_fields; }
  // A frame of this process's particles: positions (3 per particle) and fields.
  void write_frame(std::int64_t step, double t, const std::vector<double>& positions,
                   const std::vector<io::Field>& fields);
  void progress(std::int64_t step, double t, std::int64_t count) {
    if (progress_) progress_->update(step, t, count);
  }

  // The run stops early: "unstable", "not_converged" or "failed", with the message for the user.
  void stop(std::string status, std::string message);
  // Advances the method by one step (step()). A RunError the step throws — a particle
  // left the MPM grid, an element inverted — stops the run as "failed" with its message,
  // and the outputs up to the last completed step are kept like an unstable run's:
  // false then.
  template <class Step>
  bool step_or_stop(Step&& step) {
    try {
      step();
      return true;
    } catch (const RunError& e) {
      stop("failed", e.what());
      return false;
    }
  }
  const std::string& status() const { return status_; }
  // A run of several processes, and whether this is the one that writes.
  bool distributed() const;
  bool writer() const;

  const std::string& message() const { return message_; }

  // A condition the user should know of that does not stop the run, found at `step` (time
  // t): printed once per key on stderr (by the writing process) and listed in summary.json
  // "warnings" with its key, step and time.
  void warn(const std::string& key, const std::string& text, std::int64_t step, double t);

  // Closes the outputs, writes summary.json — the method's keys plus the keys
  // every run has — and commits the directory. Exit code 0 when completed, 3 otherwise.
  RunResult finish(std::int64_t steps_done, double t, std::int64_t count, Index particles, nlohmann::json method_keys);

 private:
  void check_checkpoint_options() const;
  // This process's checkpoint file in the output directory (sim/checkpoint.hpp).
  std::filesystem::path own_checkpoint() const;
  void open_resumed_outputs(const std::vector<std::string>& columns, int dimension);
  // Writes a checkpoint after `step` to `path`; `outputs` says where its outputs are.
  void write_checkpoint(std::int64_t step, const std::filesystem::path& path, const std::string& outputs);

  const io::Scene& scene_;
  RunOptions options_;
  std::chrono::steady_clock::time_point t0_;
  std::int64_t total_steps_ = 0, history_every_ = 1;
  std::vector<std::int64_t> frame_steps_;
  std::size_t next_frame_ = 0;
  std::string status_ = "completed", message_;
  struct Warning {
    std::string key, text;
    std::int64_t step = 0;
    double time = 0.0;
  };
  std::vector<Warning> warnings_;
  StateFn state_;
  std::string no_checkpoint_reason_;
  std::chrono::steady_clock::time_point last_checkpoint_;
  double earlier_wall_seconds_ = 0.0;  // a resumed run: the wall time before its checkpoint

  void open_outputs(const std::vector<std::string>& columns, int dimension, double progress_end_time,
                    const std::string& counter);

  std::unique_ptr<io::OutputDirectory> out_;
  std::unique_ptr<io::HistoryWriter> history_;
  std::unique_ptr<io::FieldsWriter> fields_;
  std::unique_ptr<io::Progress> progress_;
};

}  // namespace pdmpm::sim
