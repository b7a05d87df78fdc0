// `pdmpm check`: a valid scene is described (particles, bonds, steps, an estimated
// wall time) and nothing is written; a broken one fails as `pdmpm run` fails.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "verification/support/broken_corpus.hpp"
#include "verification/support/command_line.hpp"
#include "verification/support/scene_text.hpp"
#include "verification/support/scratch_dir.hpp"

namespace {

namespace fs = std::filesystem;

using pdmpm::test::run_pdmpm;

int scratch_directories_left() {
  int n = 0;
  for (const auto& e : fs::directory_iterator(fs::temp_directory_path()))
    n += e.path().filename().string().rfind("pdmpm-check-", 0) == 0;
  return n;
}

TEST(CliCheck, DescribesAValidSceneAndEstimatesItsWallTimeWritingNothing) {
  const fs::path scene = fs::path(PDMPM_SOURCE_DIR) / "scenes/demo_plate_hole.toml";
  const pdmpm::test::ScratchDir scratch("cli_check_valid");
  const int left_before = scratch_directories_left();
  const auto r = pdmpm::test::run_command("cd " + scratch.path().string() + " && " + PDMPM_BINARY_DIR +
                                          "/pdmpm check " + scene.string() + " --threads 1 --calibration-seconds 0.2");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* fact : {"demo_plate_hole", "valid", "model lps", "plane_stress", "4792 particles", "bond sides",
                           "dt = 8.85e-08 s, 339 steps to t = 3e-05 s", "per step on 1 thread", "to build and start"})
    EXPECT_NE(r.output.find(fact), std::string::npos) << fact << "\n" << r.output;
  // The estimate is a positive time (its value depends on the machine).
  EXPECT_TRUE(std::regex_search(r.output, std::regex("about [0-9.:]+( s)? for the run"))) << r.output;
  EXPECT_TRUE(fs::is_empty(scratch.path())) << "check wrote into the working directory";
  EXPECT_EQ(scratch_directories_left(), left_before) << "calibration scratch left in the temporary directory";
}

TEST(CliCheck, WithoutCalibrationItValidatesAndDescribesOnly) {
  const fs::path scene = fs::path(PDMPM_SOURCE_DIR) / "scenes/demo_cube_impact.toml";
  const auto r = run_pdmpm("check " + scene.string() + " --calibration-seconds 0");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("2400 particles"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("60 steps"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("for the run"), std::string::npos) << r.output;
}

TEST(CliCheck, AQuasiStaticSceneGetsNoWallTimeEstimate) {
  const pdmpm::test::ScratchDir scratch("cli_check_adr");
  const pdmpm::test::SceneText text{.id = "adr_block",
                                    .dimension = 2,
                                    .plane = "stress",
                                    .min = {0.0, 0.0},
                                    .max = {0.01, 0.005},
                                    .poissons_ratio = "0.33",
                                    .model = "lps",
                                    .time = "integrator = \"adr\"\nload_steps = 4"};
  const fs::path scene = scratch.path() / "scene.toml";
  std::ofstream(scene) << text.toml();
  const auto r = run_pdmpm("check " + scene.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("quasi-static"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("4 load steps"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("no wall-time estimate"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("for the run"), std::string::npos) << r.output;
}

// Every scene of the broken corpus: exit 2 and the message `pdmpm run` gives.
TEST(CliCheck, EveryBrokenSceneFailsAsItsRunWould) {
  int count = 0;
  for (const auto& scene : pdmpm::test::broken_corpus()) {
    ++count;
    const auto r = run_pdmpm("check " + scene.path.string() + " --calibration-seconds 0.05");
    EXPECT_EQ(r.status, 2) << scene.path.filename() << ":\n" << r.output;
    EXPECT_NE(r.output.find(scene.fragment), std::string::npos) << scene.path.filename() << ":\n" << r.output;
  }
  EXPECT_GE(count, 40);
}

}  // namespace
