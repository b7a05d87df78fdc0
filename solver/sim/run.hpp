#pragma once
// Runs a validated scene and writes its outputs (fields.h5 + fields.xdmf,
// history.csv, summary.json) into the output directory, all or nothing.
#include <filesystem>
#include <iosfwd>
#include <string>

#include <nlohmann/json.hpp>

#include "solver/io/output_directory.hpp"
#include "solver/io/scene.hpp"

namespace pdmpm::sim {

struct RunOptions {
  std::filesystem::path out_dir = "out";
  int threads = 0;          // 0: OpenMP's default
  bool progress = true;     // progress bar / periodic lines on stderr
  bool write_fields = true;
};

struct RunResult {
  std::string status;       // completed | unstable | not_converged
  std::string message;
  nlohmann::json summary;
  int exit_code = 0;        // 0 completed, 3 unstable or not converged
};

// Writes summary.json into the staged output directory and commits it (the last
// step of every run, PD or MPM); exit code 0 for "completed", 3 otherwise.
RunResult commit_run(io::OutputDirectory& out, std::string status, std::string message, nlohmann::json summary);

// Throws InputError for problems found while building the model (before any
// output exists); run-time failures are reported in the result.
RunResult run_scene(const io::Scene& scene, const RunOptions& options);

}  // namespace pdmpm::sim
