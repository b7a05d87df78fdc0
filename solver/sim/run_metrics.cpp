#include "solver/sim/run_metrics.hpp"

#include <sys/resource.h>

namespace pdmpm::sim {

double peak_memory_bytes() {
  rusage r{};
  getrusage(RUSAGE_SELF, &r);
  return static_cast<double>(r.ru_maxrss) * 1024.0;  // ru_maxrss is in KiB on Linux
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

const char* axis_name(int a) { return a == 0 ? "x" : a == 1 ? "y" : "z"; }

}  // namespace pdmpm::sim
