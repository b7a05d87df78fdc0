#pragma once
// Runs a validated scene and writes its outputs (fields.h5 + fields.xdmf,
// history.csv, summary.json) into the output directory, all or nothing.
#include <filesystem>
#include <iosfwd>
#include <string>

#include <nlohmann/json.hpp>

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

// Throws InputError for problems found while building the model (before any
// output exists); run-time failures are reported in the result.
RunResult run_scene(const io::Scene& scene, const RunOptions& options);

}  // namespace pdmpm::sim
