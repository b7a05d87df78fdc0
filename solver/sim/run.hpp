#pragma once
// Runs a validated scene and writes its outputs (fields.h5 + fields.xdmf,
// history.csv, summary.json) into the output directory, all or nothing.
#include <filesystem>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "solver/io/output_directory.hpp"
#include "solver/io/scene.hpp"

namespace pdmpm::dist {
class Communicator;
}

namespace pdmpm::sim {

struct Resume;

struct RunOptions {
  std::filesystem::path out_dir = "out";
  int threads = 0;       // 0: OpenMP's default
  bool progress = true;  // progress bar / periodic lines on stderr
  bool write_fields = true;
  // Periodic checkpoints (sim/checkpoint.hpp) every so many steps and/or wall seconds; 0: none.
  std::int64_t checkpoint_every_steps = 0;
  double checkpoint_every_seconds = 0.0;
  std::int64_t interrupt_at_step = 0;  // behave as if SIGINT arrived during this step (--stop-after, tests)
  std::shared_ptr<Resume> resume;      // continue this checkpoint's run (pdmpm resume)
  // The processes of a distributed run (mpirun; PD only): each moves its share of the
  // body, process 0 writes the outputs. Null or one process: a run of one process.
  const dist::Communicator* comm = nullptr;
};

// Exit status of a run stopped by SIGINT/SIGTERM (its checkpoint written, if the run has one).
inline constexpr int kExitInterrupted = 5;

struct RunResult {
  std::string status;  // completed | unstable | not_converged | interrupted
  std::string message;
  nlohmann::json summary;
  int exit_code = 0;  // 0 completed, 3 unstable or not converged, 5 interrupted
};

// Writes summary.json into the staged output directory and commits it (the last
// step of every run, PD or MPM); exit code 0 for "completed", 5 for "interrupted", 3 otherwise.
RunResult commit_run(io::OutputDirectory& out, std::string status, std::string message, nlohmann::json summary);
// The same result without outputs: the processes of a distributed run other than 0.
RunResult uncommitted_run(std::string status, std::string message, nlohmann::json summary);

// Throws InputError for problems found while building the model (before any
// output exists); run-time failures are reported in the result.
RunResult run_scene(const io::Scene& scene, const RunOptions& options);

}  // namespace pdmpm::sim
