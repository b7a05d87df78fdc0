#include "solver/sim/initial_from_scene.hpp"

#include <gtest/gtest.h>

#include "solver/core/error.hpp"
#include "solver/sim/geometry_from_scene.hpp"
#include "verification/support/scene_text.hpp"

namespace pdmpm::sim {
namespace {

// A 10 × 5 plate of Δx = 1 mm (sites at 0.5, 1.5, … mm) with the given tables.
io::Scene plate(const std::string& tables) {
  return test::SceneText{.max = {0.01, 0.005}, .tables = tables}.parse("initial.toml");
}

TEST(InitialFromScene, RegionsSelectByReferencePositionAndNoRegionIsTheBody) {
  const auto scene = plate(R"(
[[initial]]
velocity = ["free", 3]
[[initial]]
region = [{ type = "box", min = [0, 0], max = [0.002, 0.005] }, { type = "box", min = [0, 0], max = [0.002, 0.001], operation = "subtract" }]
displacement = ["1e-3 * x", "free"]
)");
  auto p = fill_body<2>(scene);
  ASSERT_EQ(p.n_real, 50);
  const auto initial = make_initial_conditions<2>(scene, p);
  ASSERT_EQ(initial.size(), 2u);
  EXPECT_EQ(initial[0].particles.size(), 50u);
  EXPECT_FALSE(initial[0].velocity[0]);
  ASSERT_TRUE(initial[0].velocity[1]);
  EXPECT_FALSE(initial[0].displacement[0] || initial[0].displacement[1]);
  // Columns x = 0.5 and 1.5 mm without the bottom row: 2 × 4 particles.
  EXPECT_EQ(initial[1].particles.size(), 8u);
  for (Index i : initial[1].particles) EXPECT_TRUE(p.x0[i][0] < 0.002 && p.x0[i][1] > 0.001);

  bc::apply_initial_conditions<2>(initial, p);
  for (Index i = 0; i < p.n_real; ++i) {
    EXPECT_EQ(p.v[i], Vec<2>(0, 3));
    const bool moved = p.x0[i][0] < 0.002 && p.x0[i][1] > 0.001;
    EXPECT_DOUBLE_EQ(p.u[i][0], moved ? 1e-3 * p.x0[i][0] : 0.0);
    EXPECT_EQ(p.u[i][1], 0.0);
  }
}

TEST(InitialFromScene, ARegionWithoutParticlesIsAnInputError) {
  const auto scene = plate(R"(
[[initial]]
velocity = [1, 0]
[[initial]]
region = { type = "disk", center = [0.5, 0.5], radius = 0.01 }
velocity = [2, 0]
)");
  const auto p = fill_body<2>(scene);
  try {
    make_initial_conditions<2>(scene, p);
    ADD_FAILURE() << "an empty region was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "initial[1].region");
    EXPECT_NE(std::string(e.what()).find("selects no particle"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace pdmpm::sim
