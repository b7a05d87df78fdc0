#include "verification/support/provenance.hpp"
#include "solver/core/build_info.hpp"
#include "solver/pd/kernels/bond_kernels.hpp"
#include "verification/support/command_line.hpp"

#include <omp.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <string>

namespace pdmpm::test {
namespace {

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

// "dirty" if the source tree has uncommitted changes, "clean" if not, "unknown" without git.
std::string tree_state() {
  const CommandResult r = run_command(std::string("git -C '") + PDMPM_SOURCE_DIR + "' status --porcelain 2>/dev/null");
  if (r.status != 0) return "unknown";
  return r.output.empty() ? "clean" : "dirty";
}

}  // namespace

nlohmann::json provenance() {
  const std::time_t now = std::time(nullptr);
  char date[64];
  std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return {{"git_sha", build_info::git_sha()},
          {"tree", tree_state()},
          {"date", date},
          {"compiler", build_info::compiler()},
          {"flags", build_info::flags()},
          {"cpu", cpu_model()},
          {"threads", omp_get_max_threads()},
          // The vector instruction set the PD kernels and the MPM lanes run: timings and the
          // hybrid's saving depend on it (docs/models/mpm.md, "Cost").
          {"simd", pd::kernels::simd_level()}};
}

}  // namespace pdmpm::test
