#include "verification/support/broken_corpus.hpp"

#include <algorithm>
#include <fstream>

namespace pdmpm::test {

std::vector<BrokenScene> broken_corpus() {
  const std::filesystem::path dir = std::filesystem::path(PDMPM_SOURCE_DIR) / "verification/scenes/broken";
  std::vector<BrokenScene> out;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".toml") continue;
    BrokenScene s{entry.path()};
    std::ifstream in(entry.path());
    std::string first;
    std::getline(in, first);
    const std::string tag = "# expect: ";
    s.has_expectation = first.rfind(tag, 0) == 0;
    if (s.has_expectation) {
      const std::string expect = first.substr(tag.size());
      const auto bar = expect.find(" | ");
      s.key = bar == std::string::npos ? "" : expect.substr(0, bar);
      s.fragment = bar == std::string::npos ? expect : expect.substr(bar + 3);
    }
    out.push_back(s);
  }
  std::sort(out.begin(), out.end(), [](const BrokenScene& a, const BrokenScene& b) { return a.path < b.path; });
  return out;
}

}  // namespace pdmpm::test
