#include "solver/sim/run_metrics.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <fstream>
#include <thread>
#include <vector>

namespace pdmpm::sim {

double peak_memory_bytes() {
  rusage r{};
  getrusage(RUSAGE_SELF, &r);
  return static_cast<double>(r.ru_maxrss) * 1024.0;  // ru_maxrss is in KiB on Linux
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double other_running_processes() {
  std::vector<double> samples;
  for (int k = 0; k < 5; ++k) {
    if (k > 0) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    std::ifstream in("/proc/loadavg");
    double l1 = 0.0, l5 = 0.0, l15 = 0.0;
    long running = 0;
    char slash = 0;
    if (!(in >> l1 >> l5 >> l15 >> running >> slash) || slash != '/') return -1.0;
    samples.push_back(static_cast<double>(running - 1));
  }
  std::nth_element(samples.begin(), samples.begin() + 2, samples.end());
  return samples[2];
}

bool cores_taken(double others, int cores, int threads) { return others >= 0.0 && others > cores - threads; }

const char* axis_name(int a) { return a == 0 ? "x" : a == 1 ? "y" : "z"; }

}  // namespace pdmpm::sim
