#pragma once
// Where the performance driver's numbers go: raw results as JSON under
// <results>/bench/perf/ (a folder of its own: <results>/bench/*.json is Google
// Benchmark output, which the report reads as such), targets as gates of the
// report's "performance" problem, plots and tables as its evidence.
#include <nlohmann/json.hpp>
#include <string>

#include "benchmarks/perf/stats.hpp"
#include "verification/support/gate.hpp"

namespace pdmpm::perf {

inline constexpr const char* problem = "performance";

void write_result(const std::string& name, const nlohmann::json& j);  // <results>/bench/perf/<name>.json
// Writes the gate, prints its verdict line, returns passes().
bool target(test::Gate g);
nlohmann::json to_json(const Ratio& r);

}  // namespace pdmpm::perf
