// Scene parsing of [[initial]] tables: what a valid table becomes, and the
// message (file, key, reason) of each kind of mistake. The end-to-end check that
// such scenes exit with status 2 and write nothing is the broken-scene corpus
// (verification/scenes/broken, run by app/run_command_test.cpp).
#include <gtest/gtest.h>

#include <string>

#include "solver/core/error.hpp"
#include "solver/io/scene.hpp"
#include "verification/support/scene_text.hpp"

namespace pdmpm::io {
namespace {

io::Scene with_initial(const std::string& tables, const std::string& time = "steps = 1") {
  return test::SceneText{.time = time, .tables = tables}.parse("initial.toml");
}

// Parses and expects an InputError naming the file and `key`, whose message holds `fragment`.
void expect_error(const std::string& tables, const std::string& key, const std::string& fragment,
                  const std::string& time = "steps = 1") {
  try {
    with_initial(tables, time);
    ADD_FAILURE() << "accepted:\n" << tables;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "initial.toml");
    EXPECT_EQ(e.key(), key) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(SceneInitial, TablesKeepFileOrderRegionsAndComponents) {
  const auto s = with_initial(R"toml(
[[initial]]
velocity = [1.5, "free"]
[[initial]]
region = [{ type = "box", min = [0, 0], max = [0.01, 0.015] }, { type = "disk", center = [0.02, 0.0075], radius = 0.002 }]
displacement = ["1e-3 * sin(pi * x / 0.03)", 0]
velocity = ["free", "-2 * y"]
)toml");
  ASSERT_EQ(s.initials.size(), 2u);
  const auto& a = s.initials[0];
  EXPECT_EQ(a.key, "initial[0]");
  EXPECT_TRUE(a.region.empty());  // the whole body
  EXPECT_EQ(a.velocity, (std::vector<std::string>{"1.5", "free"}));
  EXPECT_TRUE(a.displacement.empty());
  const auto& b = s.initials[1];
  ASSERT_EQ(b.region.size(), 2u);
  EXPECT_EQ(b.region[0].type, "box");
  EXPECT_EQ(b.region[1].type, "ball");
  EXPECT_EQ(b.displacement, (std::vector<std::string>{"1e-3 * sin(pi * x / 0.03)", "0"}));
  EXPECT_EQ(b.velocity, (std::vector<std::string>{"free", "-2 * y"}));
}

TEST(SceneInitial, AdrTakesADisplacementOnly) {
  const std::string adr = "integrator = \"adr\"";
  EXPECT_EQ(with_initial("[[initial]]\ndisplacement = [\"1e-6 * x\", 0]\n", adr).initials.size(), 1u);
  expect_error("[[initial]]\nvelocity = [1, 0]\n", "initial[0].velocity", "not used by integrator = \"adr\"", adr);
}

TEST(SceneInitial, MistakesNameTheTableAndKey) {
  expect_error("[[initial]]\nvelocty = [1, 0]\n", "initial[0].velocty", "unknown key");
  expect_error("[[initial]]\nvelocity = [1, 0, 0]\n", "initial[0].velocity", "exactly 2 components");
  expect_error("[[initial]]\nvelocity = 1\n", "initial[0].velocity", "a list of 2 components");
  expect_error("[[initial]]\ndisplacement = [\"1e-3 *\", 0]\n", "initial[0].displacement", "at character");
  expect_error("[[initial]]\ndisplacement = [\"1e-3 * t\", 0]\n", "initial[0].displacement",
               "initial values are at t = 0");
  expect_error("[[initial]]\nregion = { type = \"box\", min = [0, 0], max = [1, 1] }\n", "initial[0]",
               "needs velocity, displacement or both");
  expect_error("[[initial]]\nvelocity = [\"free\", \"free\"]\n", "initial[0].velocity", "the table sets nothing");
  expect_error("[[initial]]\nvelocity = [0, 0]\n[[initial]]\nregion = { type = \"hexagon\" }\nvelocity = [1, 0]\n",
               "initial[1].region.type", "must be one of box");
  expect_error("[[initial]]\nregion = { type = \"box\", min = [0], max = [1, 1] }\nvelocity = [1, 0]\n",
               "initial[0].region.min", "exactly 2 numbers");
}

}  // namespace
}  // namespace pdmpm::io
