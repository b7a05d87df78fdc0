#include "verification/support/gate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <string>

#include <unistd.h>

#include "verification/support/provenance.hpp"

namespace pdmpm::test {
namespace fs = std::filesystem;

namespace {

const char* compare_name(Compare c) {
  switch (c) {
    case Compare::abs: return "abs";
    case Compare::rel: return "rel";
    case Compare::at_most: return "at_most";
    case Compare::at_least: return "at_least";
  }
  return "?";
}

// Write via a temporary name and rename, so a reader never sees half a file. The
// temporary name carries the process id: ctest runs tests side by side, and every
// test process writes provenance.json (one shared name let one process rename the
// other's file away, failing its test).
void write_json(const fs::path& path, const nlohmann::json& j) {
  fs::create_directories(path.parent_path());
  const fs::path tmp = path.string() + "." + std::to_string(::getpid()) + ".tmp";
  {
    std::ofstream out(tmp);
    out << j.dump(2) << '\n';
  }
  fs::rename(tmp, path);
}

void ensure_provenance() {
  static std::once_flag once;
  std::call_once(once, [] { write_json(fs::path(results_dir()) / "provenance.json", provenance()); });
}

}  // namespace

std::string results_dir() {
  if (const char* env = std::getenv("PDMPM_RESULTS_DIR")) return env;
#ifdef PDMPM_BINARY_DIR
  return std::string(PDMPM_BINARY_DIR) + "/results";
#else
  return "results";
#endif
}

bool passes(const Gate& g) {
  if (!std::isfinite(g.measured)) return false;
  switch (g.compare) {
    case Compare::abs: return std::abs(g.measured - g.expected) <= g.tolerance;
    case Compare::rel: return std::abs(g.measured - g.expected) <= g.tolerance * std::abs(g.expected);
    case Compare::at_most: return g.measured <= g.expected;
    case Compare::at_least: return g.measured >= g.expected;
  }
  return false;
}

bool write_gate(const Gate& g, const std::string& writer) {
  ensure_provenance();
  const bool ok = passes(g);
  nlohmann::json j = {{"id", g.id},
                      {"claim", g.claim},
                      {"measured", std::isfinite(g.measured) ? nlohmann::json(g.measured) : nlohmann::json("non-finite")},
                      {"expected", g.expected},
                      {"tolerance", g.tolerance},
                      {"compare", compare_name(g.compare)},
                      {"tolerance_reason", g.tolerance_reason},
                      {"source", g.source},
                      {"unit", g.unit},
                      {"problem", g.problem},
                      {"verdict", ok ? "PASS" : "FAIL"},
                      {"test", writer}};
  write_json(fs::path(results_dir()) / "gates" / (g.id + ".json"), j);
  return ok;
}

void record_gate(const Gate& g) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const bool ok =
      write_gate(g, info ? std::string(info->test_suite_name()) + "." + info->name() : std::string());
  EXPECT_TRUE(ok) << "gate " << g.id << " FAILED: " << g.claim << "\n  measured " << g.measured << ", expected "
                  << g.expected << " (" << compare_name(g.compare) << ", tolerance " << g.tolerance << ")";
  EXPECT_FALSE(g.tolerance_reason.empty()) << "gate " << g.id << " has no tolerance reason";
  EXPECT_FALSE(g.source.empty()) << "gate " << g.id << " has no source";
}

void record_data(const std::string& problem, const std::string& name, const nlohmann::json& data) {
  ensure_provenance();
  write_json(fs::path(results_dir()) / "data" / problem / (name + ".json"), data);
}

}  // namespace pdmpm::test
