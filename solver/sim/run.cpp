#include "solver/sim/run.hpp"

#include <omp.h>

#include <fstream>
#include <utility>

#include "solver/core/error.hpp"
#include "solver/dist/communicator.hpp"
#include "solver/io/output_directory.hpp"
#include "solver/sim/hybrid_run.hpp"
#include "solver/sim/mpm_run.hpp"
#include "solver/sim/pd_run.hpp"

namespace pdmpm::sim {
namespace {

void refuse_distributed(const io::Scene& scene, const RunOptions& options, const std::string& key,
                        const std::string& what) {
  if (options.comm && options.comm->size() > 1)
    throw InputError(scene.file, key,
                     what + " does not run distributed yet: start it without mpirun (docs/models/distributed.md)");
}

template <int D>
RunResult run_dim(const io::Scene& scene, const RunOptions& options) {
  switch (scene.method) {
    case io::Method::mpm: {
      auto setup = build_mpm<D>(scene, options.comm);
      return run_mpm<D>(scene, setup, options);
    }
    case io::Method::pd: {
      auto setup = build_pd<D>(scene, options.comm);
      return run_pd<D>(scene, setup, options);
    }
    case io::Method::hybrid:
      if constexpr (D >= 2) {
        refuse_distributed(scene, options, "hybrid", "the adaptive SBPD–MPM hybrid");
        auto setup = build_hybrid<D>(scene);
        return run_hybrid<D>(scene, *setup, options);
      }
      break;
  }
  throw InputError(scene.file, "discretization.dimension", "the adaptive SBPD–MPM hybrid needs dimension 2 or 3");
}

}  // namespace

RunResult uncommitted_run(std::string status, std::string message, nlohmann::json summary) {
  RunResult r;
  r.exit_code = status == "completed" ? 0 : status == "interrupted" ? kExitInterrupted : 3;
  r.status = std::move(status);
  r.message = std::move(message);
  r.summary = std::move(summary);
  return r;
}

RunResult commit_run(io::OutputDirectory& out, std::string status, std::string message, nlohmann::json summary) {
  RunResult r = uncommitted_run(std::move(status), std::move(message), std::move(summary));
  {
    std::ofstream js(out.path("summary.json"));
    js << r.summary.dump(2) << '\n';
  }
  out.commit();
  return r;
}

RunResult run_scene(const io::Scene& scene, const RunOptions& options) {
  if (options.threads > 0) omp_set_num_threads(options.threads);
  switch (scene.dimension) {
    case 1:
      return run_dim<1>(scene, options);
    case 2:
      return run_dim<2>(scene, options);
    default:
      return run_dim<3>(scene, options);
  }
}

}  // namespace pdmpm::sim
