#include "solver/sim/checkpoint.hpp"

#include <unistd.h>

#include <fmt/format.h>

#include "solver/core/build_info.hpp"
#include "solver/core/error.hpp"

namespace pdmpm::sim {

void sync_info(core::StateArchive& a, CheckpointInfo& info) {
  a.sync("run/build", info.build);
  a.sync("run/scene_file", info.scene_file);
  a.sync("run/scene_text", info.scene_text);
  a.sync("run/outputs", info.outputs);
  a.sync("run/step", info.step);
  a.sync("run/write_fields", info.write_fields);
  a.sync("run/processes", info.processes);
}

std::string checkpoint_file(int rank) {
  return rank == 0 ? std::string(kCheckpointFile) : fmt::format("{}.{}", kCheckpointFile, rank);
}

std::shared_ptr<Resume> read_checkpoint(const std::filesystem::path& dir, int rank, int processes) {
  const auto path = dir / checkpoint_file(rank);
  if (!std::filesystem::exists(path))
    throw InputError(path.string(), "",
                     "no checkpoint here: a run writes one when it is interrupted (SIGINT, SIGTERM) or with "
                     "--checkpoint-every");
  auto r = std::make_shared<Resume>();
  r->dir = dir;
  try {
    r->state = core::StateArchive::read(path);
    sync_info(r->state, r->info);
  } catch (const core::StateMismatch& e) {
    throw InputError(path.string(), "", e.what());
  }
  if (r->info.build != build_info::git_sha())
    throw InputError(path.string(), "",
                     fmt::format("written by pdmpm {}, this is pdmpm {}: resume it with the build that wrote it, or "
                                 "run the scene again",
                                 r->info.build, build_info::git_sha()));
  if (r->info.processes != processes)
    throw InputError(path.string(), "",
                     fmt::format("written by a run of {} process(es): resume it with {}", r->info.processes,
                                 r->info.processes == 1 ? std::string("pdmpm resume (no mpirun)")
                                                        : fmt::format("mpirun -n {} pdmpm resume", r->info.processes)));
  return r;
}

void write_checkpoint_file(const core::StateArchive& a, const std::filesystem::path& path) {
  const auto temporary = path.parent_path() / fmt::format(".{}.{}.tmp", path.filename().string(), ::getpid());
  try {
    a.write(temporary);
    std::filesystem::rename(temporary, path);
  } catch (const std::exception& e) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw RunError(fmt::format("cannot write the checkpoint '{}': {}", path.string(), e.what()));
  }
}

}  // namespace pdmpm::sim
