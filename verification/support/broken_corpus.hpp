#pragma once
// The broken-scene corpus (verification/scenes/broken): each scene with what its
// first line says the rejection must contain, `# expect: <key path> | <fragment>`.
#include <filesystem>
#include <string>
#include <vector>

namespace pdmpm::test {

struct BrokenScene {
  std::filesystem::path path;
  bool has_expectation = false;  // the first line is an `# expect:` line
  std::string key;               // the key the message must name ('' if the line gives none)
  std::string fragment;          // text the message must contain
};

// Every .toml of the corpus, in file-name order.
std::vector<BrokenScene> broken_corpus();

}  // namespace pdmpm::test
