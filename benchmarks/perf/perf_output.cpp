#include "benchmarks/perf/perf_output.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>

namespace pdmpm::perf {
namespace fs = std::filesystem;

void write_result(const std::string& name, const nlohmann::json& j) {
  const fs::path path = fs::path(test::results_dir()) / "bench" / "perf" / (name + ".json");
  fs::create_directories(path.parent_path());
  const fs::path tmp = path.string() + ".tmp";  // a reader never sees half a file
  {
    std::ofstream out(tmp);
    out << j.dump(2) << '\n';
  }
  fs::rename(tmp, path);
}

bool target(test::Gate g) {
  const bool ok = test::write_gate(g, "pdmpm_perf");
  fmt::print("  {} {}: measured {:.4g}{}, target {} {:.4g}\n", ok ? "PASS" : "FAIL", g.id, g.measured,
             g.unit.empty() ? "" : " " + g.unit, g.compare == test::Compare::at_least ? "≥" : "≤", g.expected);
  return ok;
}

nlohmann::json to_json(const Ratio& r) { return {{"value", r.value}, {"ci95", {r.lo, r.hi}}}; }

}  // namespace pdmpm::perf
