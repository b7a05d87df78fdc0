#pragma once
// Checkpoints of a run (docs/checkpoints.md): DIR/checkpoint.pdmpm holds the
// state of every object that outlives a step (core/state_archive.hpp), the scene
// text, the build, and where the outputs written so far are — next to it (a run
// stopped by a signal commits its outputs with it) or in the staging directory
// of a run that was killed after a periodic checkpoint. `pdmpm resume DIR`
// rebuilds the run from the scene, restores the state and continues, so the
// outputs are those of an uninterrupted run, bit for bit.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "solver/core/state_archive.hpp"

namespace pdmpm::sim {

inline constexpr const char* kCheckpointFile = "checkpoint.pdmpm";
// A distributed run's checkpoint is one file per process: process 0's is kCheckpointFile
// (with the outputs), process r's "checkpoint.pdmpm.r" beside it (its share of the state).
std::string checkpoint_file(int rank);

struct CheckpointInfo {
  std::string build;       // build_info::git_sha() of the build that wrote it
  std::string scene_file;  // the scene's path, as the run named it
  std::string scene_text;  // the scene as parsed (resume parses this, not the file)
  std::string outputs;     // "" next to the checkpoint, else the staging directory's name in DIR
  std::int64_t step = 0;   // the last step done
  bool write_fields = true;
  std::int64_t processes = 1;  // the processes that wrote it (one file each)
};
void sync_info(core::StateArchive& a, CheckpointInfo& info);

struct Resume {
  std::filesystem::path dir;
  core::StateArchive state{core::StateArchive::Mode::restore};
  CheckpointInfo info;
  // Where the outputs to continue are.
  std::filesystem::path outputs() const { return info.outputs.empty() ? dir : dir / info.outputs; }
};

// Reads DIR/checkpoint.pdmpm, or process `rank`'s file of a distributed run of
// `processes`. InputError naming the file when it is missing, is not a checkpoint, is
// damaged, was written by another build or by another number of processes.
std::shared_ptr<Resume> read_checkpoint(const std::filesystem::path& dir, int rank = 0, int processes = 1);

// Writes the archive to `path` atomically (a temporary file in the same directory, then a rename).
void write_checkpoint_file(const core::StateArchive& a, const std::filesystem::path& path);

}  // namespace pdmpm::sim
