// A scene fuzzer: the project's own valid scenes, mutated the ways users and tools
// break files (a deleted line, two values swapped, an extreme number, truncation,
// stray bytes, a duplicated line), each handed to `pdmpm check`, and the small
// ones to `pdmpm run`. Whatever the text, pdmpm must answer with exit status 0
// (valid), 2 (bad input, nothing written) or 3 (the run failed): never a signal,
// never an internal error (exit 4), never a hang. Deterministic: a fixed seed, so a
// failure names a mutation that can be replayed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "verification/support/command_line.hpp"
#include "verification/support/scratch_dir.hpp"
#include "verification/support/output_files.hpp"

namespace {

namespace fs = std::filesystem;

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream ss(text);
  for (std::string line; std::getline(ss, line);) lines.push_back(line);
  return lines;
}

std::string join_lines(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

class Mutator {
 public:
  explicit Mutator(unsigned seed) : rng_(seed) {}

  // One mutation of `text`; `what` says which (for the failure message).
  std::string mutate(const std::string& text, std::string& what) {
    std::vector<std::string> lines = split_lines(text);
    if (lines.empty()) lines.push_back("");
    const std::size_t i = pick(lines.size());
    switch (pick(6)) {
      case 0:
        what = "deleted line " + std::to_string(i + 1);
        lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(i));
        return join_lines(lines);
      case 1: {
        static const std::regex number(R"(-?\d+(\.\d+)?([eE][-+]?\d+)?)");
        static const std::vector<std::string> extremes = {"-1e308", "1e308", "0",          "-0",
                                                          "1e-300", "-1",    "nan",        "inf",
                                                          "-inf",   "1e30",  "2147483648", "-9223372036854775809",
                                                          "\"x\"",  "[]",    "true"};
        std::smatch m;
        if (!std::regex_search(lines[i], m, number)) return mutate(text, what);
        const std::string e = extremes[pick(extremes.size())];
        what = "line " + std::to_string(i + 1) + ": " + m.str() + " → " + e;
        lines[i] = m.prefix().str() + e + m.suffix().str();
        return join_lines(lines);
      }
      case 2: {
        const std::size_t j = pick(lines.size());
        const auto a = lines[i].find('='), b = lines[j].find('=');
        if (a == std::string::npos || b == std::string::npos || i == j) return mutate(text, what);
        what = "values of lines " + std::to_string(i + 1) + " and " + std::to_string(j + 1) + " swapped";
        const std::string va = lines[i].substr(a), vb = lines[j].substr(b);
        lines[i] = lines[i].substr(0, a) + vb;
        lines[j] = lines[j].substr(0, b) + va;
        return join_lines(lines);
      }
      case 3: {
        const std::size_t cut = pick(text.size() + 1);
        what = "truncated at byte " + std::to_string(cut);
        return text.substr(0, cut);
      }
      case 4: {
        const std::size_t at = pick(text.size() + 1);
        std::string bytes;
        for (std::size_t k = 0, n = 1 + pick(7); k < n; ++k) bytes += static_cast<char>(pick(256));
        what = std::to_string(bytes.size()) + " random bytes at byte " + std::to_string(at);
        return text.substr(0, at) + bytes + text.substr(at);
      }
      default:
        what = "line " + std::to_string(i + 1) + " duplicated";
        lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(i), lines[i]);
        return join_lines(lines);
    }
  }

 private:
  std::size_t pick(std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng_); }
  std::mt19937 rng_;
};

// pdmpm under `timeout` (a hang is a failure too): exit status and output. The limits catch
// hangs, not slowness: PDMPM_TEST_TIME_SCALE (set by ci/sanitize.sh, whose instrumented pdmpm
// runs ~12× slower: a check of 1.4 s took 17 s) multiplies them.
pdmpm::test::CommandResult pdmpm_with_timeout(const std::string& args, int seconds) {
  const char* scale = std::getenv("PDMPM_TEST_TIME_SCALE");
  const int limit = seconds * (scale ? std::max(1, std::atoi(scale)) : 1);
  return pdmpm::test::run_command("timeout " + std::to_string(limit) + " " + PDMPM_BINARY_DIR + "/pdmpm " + args);
}

// The 240 mutants are checked in four shards of 60, separate tests so that ctest runs
// them side by side (under ci/sanitize.sh's instrumented pdmpm one test of all 240 took
// five minutes, the longest of that tier). Each shard replays the mutator from the
// start, so mutant n is the same whichever shard checks it.
constexpr int kMutations = 240;  // say so in the README if you change it
constexpr int kShards = 4;

void fuzz_shard(int shard) {
  const fs::path src = PDMPM_SOURCE_DIR;
  // Small scenes (each builds in well under a second): the demos (also run) and
  // verification scenes covering symmetry planes, MPM, the hybrid and plasticity.
  const std::vector<fs::path> demos = {src / "scenes/demo_bar_pulse.toml", src / "scenes/demo_plate_hole.toml",
                                       src / "scenes/demo_cube_impact.toml"};
  const std::vector<fs::path> others = {src / "verification/scenes/hole_concentration_quarter.toml",
                                        src / "verification/scenes/mpm/plate_tension_j2.toml",
                                        src / "verification/scenes/hybrid/precracked_plate.toml",
                                        src / "verification/scenes/plastic_strip.toml"};
  constexpr int per_shard = kMutations / kShards;
  const int first = shard * per_shard, last = first + per_shard;
  const pdmpm::test::ScratchDir scratch("scene_fuzz_" + std::to_string(shard));
  Mutator mutator(20261126);
  int checked = 0, ran = 0, valid = 0;
  for (int n = 0; n < last; ++n) {
    const bool demo = n % 3 == 0;
    const fs::path& seed = demo ? demos[static_cast<std::size_t>(n / 3) % demos.size()]
                                : others[static_cast<std::size_t>(n) % others.size()];
    std::string what, what2;
    std::string text = mutator.mutate(pdmpm::test::read_text(seed), what);
    if (n % 2) text = mutator.mutate(text, what2), what += "; " + what2;
    if (n < first) continue;  // an earlier shard's mutant: only the mutator's state matters
    const fs::path scene = scratch.path() / ("mutant" + std::to_string(n) + ".toml");
    std::ofstream(scene, std::ios::binary) << text;
    const std::string label = seed.filename().string() + " (" + what + ")";

    const auto c = pdmpm_with_timeout("check " + scene.string() + " --calibration-seconds 0 --threads 1", 30);
    ++checked;
    valid += c.status == 0;
    EXPECT_TRUE(c.status == 0 || c.status == 2 || c.status == 3) << label << ": check exit " << c.status << "\n"
                                                                 << c.output;
    EXPECT_EQ(c.output.find("internal error"), std::string::npos) << label << "\n" << c.output;
    if (!demo) continue;
    const fs::path out = scratch.fresh("out" + std::to_string(n));
    const auto r = pdmpm_with_timeout("run " + scene.string() + " --out " + out.string() + " --quiet --no-fields", 60);
    ++ran;
    EXPECT_TRUE(r.status == 0 || r.status == 2 || r.status == 3) << label << ": run exit " << r.status << "\n"
                                                                 << r.output;
    EXPECT_EQ(r.output.find("internal error"), std::string::npos) << label << "\n" << r.output;
    if (r.status == 2) {
      EXPECT_FALSE(fs::exists(out)) << label << ": output written on bad input";
    }
  }
  // The mix must exercise both answers, or the mutations are too weak or too strong.
  EXPECT_GT(valid, per_shard / 20);
  EXPECT_LT(valid, per_shard * 9 / 10);
  std::cout << "scene fuzzer, mutants " << first << "-" << last - 1 << ": " << checked << " checks, " << ran
            << " runs, " << valid << " mutants valid\n";
}

TEST(SceneFuzz, MutatedScenesGiveOnlyTheDocumentedExitStatuses1) { fuzz_shard(0); }
TEST(SceneFuzz, MutatedScenesGiveOnlyTheDocumentedExitStatuses2) { fuzz_shard(1); }
TEST(SceneFuzz, MutatedScenesGiveOnlyTheDocumentedExitStatuses3) { fuzz_shard(2); }
TEST(SceneFuzz, MutatedScenesGiveOnlyTheDocumentedExitStatuses4) { fuzz_shard(3); }

}  // namespace
