#include "benchmarks/perf/memory_status.hpp"

#include <fstream>
#include <sstream>
#include <string>

namespace pdmpm::perf {

MemoryStatus memory_status() {
  MemoryStatus m;
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string key;
    double kib = 0.0;
    s >> key >> kib;  // "VmRSS:    123456 kB"
    if (key == "VmRSS:") m.resident_bytes = 1024.0 * kib;
    if (key == "VmHWM:") m.peak_bytes = 1024.0 * kib;
  }
  return m;
}

bool reset_peak() {
  std::ofstream out("/proc/self/clear_refs");
  out << "5";
  out.flush();
  return static_cast<bool>(out);
}

}  // namespace pdmpm::perf
