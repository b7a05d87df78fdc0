#pragma once
// A gate is one claim with a number: id, "shall" sentence, measured, expected,
// tolerance, verdict and source. record_gate() writes it to
// <build>/results/gates/<id>.json (one file per gate, so tests may run in
// parallel) and asserts it; the report reads these files and nothing else.
#include <nlohmann/json.hpp>
#include <string>

namespace pdmpm::test {

enum class Compare {
  abs,       // |measured − expected| ≤ tolerance
  rel,       // |measured − expected| ≤ tolerance · |expected|
  at_most,   // measured ≤ expected  (tolerance unused, expected is the bound)
  at_least,  // measured ≥ expected
};

struct Gate {
  std::string id;          // unique, dotted: "constants.pmb.3d.quadratic"
  std::string claim;       // "shall" sentence a reader can check
  double measured = 0.0;
  double expected = 0.0;
  double tolerance = 0.0;
  Compare compare = Compare::rel;
  std::string tolerance_reason;  // why this tolerance (required)
  std::string source;            // paper / equation / derivation
  std::string unit;              // "" for dimensionless
  std::string problem;           // report section this gate belongs to
};

bool passes(const Gate& g);
// Writes the gate file and fails the current GoogleTest test if the gate fails.
void record_gate(const Gate& g);
// Writes the gate file only and returns passes(g): for programs that are not
// GoogleTest tests (benchmarks/perf records its targets this way, since a timing
// is not a unit test). `writer` names the program in the file's "test" field.
bool write_gate(const Gate& g, const std::string& writer);

// Evidence for the report (tables, curves): <build>/results/data/<problem>/<name>.json
void record_data(const std::string& problem, const std::string& name, const nlohmann::json& data);

// Directory results are written to: $PDMPM_RESULTS_DIR, else <build>/results.
std::string results_dir();

}  // namespace pdmpm::test
