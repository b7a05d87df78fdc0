// The pdmpm command line end to end: the broken-scene corpus (every scene is
// rejected with exit status 2, a message naming the key, and no output), and
// small 2D and 3D runs of each model.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "solver/pd/model.hpp"
#include "verification/support/broken_corpus.hpp"
#include "verification/support/command_line.hpp"
#include "verification/support/scene_text.hpp"
#include "verification/support/scratch_dir.hpp"

namespace {

namespace fs = std::filesystem;

using pdmpm::test::run_pdmpm;

TEST(Cli, EveryBrokenSceneIsRejectedCleanly) {
  const pdmpm::test::ScratchDir scratch("cli_broken");
  int count = 0;
  for (const auto& scene : pdmpm::test::broken_corpus()) {
    ++count;
    const std::string name = scene.path.filename().string();
    ASSERT_TRUE(scene.has_expectation) << scene.path << ": the first line must be '# expect: key | fragment'";
    const fs::path out = scratch.fresh(scene.path.stem().string());
    const auto r = run_pdmpm("run " + scene.path.string() + " --out " + out.string() + " --quiet");
    EXPECT_EQ(r.status, 2) << name << ":\n" << r.output;
    if (!scene.key.empty()) {
      EXPECT_NE(r.output.find("'" + scene.key + "'"), std::string::npos) << name << ":\n" << r.output;
    }
    EXPECT_NE(r.output.find(scene.fragment), std::string::npos) << name << ": wanted \"" << scene.fragment << "\"\n"
                                                                << r.output;
    EXPECT_NE(r.output.find(name), std::string::npos) << "message must name the file";
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << "one line:\n" << r.output;
    EXPECT_FALSE(fs::exists(out) && !fs::is_empty(out)) << "output left behind for " << name;
  }
  EXPECT_GE(count, 40);
}

TEST(Cli, MissingSceneFileIsAnInputError) {
  const auto r = run_pdmpm("run /nonexistent/scene.toml --quiet");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("cannot open"), std::string::npos) << r.output;
}

TEST(Cli, UsageErrorsExitWithTwo) {
  EXPECT_EQ(run_pdmpm("").status, 2);
  EXPECT_EQ(run_pdmpm("frobnicate").status, 2);
  EXPECT_EQ(run_pdmpm("constants --format xml").status, 2);
}

// Started by mpirun (its environment), check refuses before writing anything: it works
// on one process (run and resume distribute a scene; verification/mpi/ runs them).
TEST(Cli, CheckUnderMpirunIsRefusedWithNothingWritten) {
  const pdmpm::test::ScratchDir dir("cli_mpirun");
  const auto scene = dir.path() / "plate.toml";
  std::ofstream(scene) << pdmpm::test::SceneText{}.toml();
  const std::string launcher = "OMPI_COMM_WORLD_SIZE=2 OMPI_COMM_WORLD_RANK=0 " + std::string(PDMPM_BINARY_DIR);
  const auto check = pdmpm::test::run_command(launcher + "/pdmpm check " + scene.string());
  EXPECT_EQ(check.status, 2) << check.output;
  EXPECT_NE(check.output.find("2 processes"), std::string::npos) << check.output;
  EXPECT_NE(check.output.find("start check without mpirun"), std::string::npos) << check.output;
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator{}), 1) << "only the scene";
}

// A tiny scene of each model in 2D and 3D runs and reports bond updates per second.
TEST(Cli, SmallScenesOfEachModelRun) {
  for (const auto& model : pdmpm::pd::model_names())
    for (int dim : {2, 3}) {
      const std::string box = dim == 2 ? "0.012, 0.008" : "0.008, 0.006, 0.006";
      const pdmpm::test::SceneText text{
          .id = "tiny_" + model + std::to_string(dim),
          .dimension = dim,
          .plane = "strain",
          .min = std::vector<double>(dim, 0.0),
          .max = dim == 2 ? std::vector<double>{0.012, 0.008} : std::vector<double>{0.008, 0.006, 0.006},
          .poissons_ratio = "0.25",
          .material_keys = pdmpm::test::flowing_keys(model),
          .model = model,
          .time = "steps = 20",
          .tables = "[[boundary]]\nkind = \"velocity\"\nvalue = [" +
              std::string(dim == 2 ? "\"1.0\", \"free\"" : "\"1.0\", \"free\", \"free\"") +
              "]\nregion = { type = \"box\", min = [" + (dim == 2 ? "0.0115, 0" : "0.0075, 0, 0") + "], max = [" + box +
              "] }\n"};
      const pdmpm::test::ScratchDir scratch("cli_tiny_" + model + std::to_string(dim));
      const fs::path dir = scratch.path();
      const fs::path scene = dir / "scene.toml";
      std::ofstream(scene) << text.toml();
      const auto r = run_pdmpm("run " + scene.string() + " --out " + (dir / "out").string() + " --quiet");
      ASSERT_EQ(r.status, 0) << r.output;
      for (const char* f : {"fields.h5", "fields.xdmf", "history.csv", "summary.json"})
        EXPECT_TRUE(fs::exists(dir / "out" / f)) << f;
      std::ifstream js(dir / "out" / "summary.json");
      const auto j = nlohmann::json::parse(js);
      EXPECT_EQ(j["status"], "completed");
      EXPECT_EQ(j["model"], model);
      EXPECT_EQ(j["dimension"], dim);
      EXPECT_EQ(j["steps"], 20);
      EXPECT_GT(j["bond_updates_per_second"].get<double>(), 0.0);
      EXPECT_GT(j["metrics"]["kinetic_energy"].get<double>(), 0.0);
    }
}

TEST(Cli, ConstantsPrintsEveryInfluenceFunction) {
  const auto r = run_pdmpm("constants --E 200e9 --nu 0.25 --delta 0.003 --format json");
  ASSERT_EQ(r.status, 0) << r.output;
  const auto j = nlohmann::json::parse(r.output);
  for (const char* s : {"1d", "plane_stress", "plane_strain", "3d"})
    EXPECT_EQ(j["settings"][s]["influence"].size(), 7u) << s;
  // Deryugin et al. 2023 table 4.2, constant ω: c = 6E / ((1 − 2ν) π δ⁴).
  const double c = j["settings"]["3d"]["influence"]["constant"]["pmb_micromodulus_c"];
  EXPECT_NEAR(c, 6 * 200e9 / (0.5 * M_PI * std::pow(0.003, 4)), 1e-6 * c);
  const auto table = run_pdmpm("constants --G0 100");
  EXPECT_EQ(table.status, 0);
  EXPECT_NE(table.output.find("quadratic"), std::string::npos);
  EXPECT_NE(table.output.find("s₀ from G₀"), std::string::npos);
}

}  // namespace
