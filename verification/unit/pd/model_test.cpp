// The model table: one row per model, and what tests may ask of it instead of a name.
#include "solver/pd/model.hpp"

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>

#include "solver/io/scene.hpp"

namespace pdmpm::pd {
namespace {

TEST(ModelTable, EveryRowMakesItsModelInEveryDimension) {
  std::set<std::string> names;
  for (const auto& info : model_table()) {
    EXPECT_TRUE(names.insert(info.name).second) << "duplicate model " << info.name;
    EXPECT_EQ(info.make<1>()->name(), info.name);
    EXPECT_EQ(info.make<2>()->name(), info.name);
    EXPECT_EQ(info.make<3>()->name(), info.name);
    EXPECT_EQ(make_model<3>(info.name)->name(), info.name);
    EXPECT_EQ(find_model(info.name), &info);
  }
  EXPECT_EQ(model_names().size(), model_table().size());
  EXPECT_EQ(find_model("mpm"), nullptr);
  EXPECT_EQ(make_model<2>("nonsense"), nullptr);
  EXPECT_THROW(model_info("nonsense"), std::invalid_argument);
}

TEST(ModelTable, PoissonRatioFollowsTheProperties) {
  for (const auto& info : model_table())
    for (core::Setting s : {core::Setting::bar1d, core::Setting::plane_stress, core::Setting::plane_strain, core::Setting::solid3d}) {
      const auto [lo, hi] = info.poisson_range(s);
      if (const auto nu = info.fixed_poisson(s)) {
        EXPECT_TRUE(info.pair_potential);
        EXPECT_EQ(lo, *nu);
        EXPECT_EQ(hi, *nu);
        EXPECT_EQ(*nu, s == core::Setting::plane_stress ? 1.0 / 3.0 : 0.25);
      } else {
        EXPECT_LT(lo, hi) << info.name;
        EXPECT_EQ(hi, 0.5);
      }
    }
  EXPECT_TRUE(model_info("pmb").pair_potential);
  EXPECT_FALSE(model_info("pmb").state_based);
  EXPECT_TRUE(model_info("lps").state_based);
  EXPECT_FALSE(model_info("lps").fixed_poisson(core::Setting::solid3d).has_value());
}

// A scene's method follows from its model: MPM for type "mpm", PD for a row of the table.
TEST(ModelTable, SceneMethodFollowsTheModelType) {
  const std::string head = "[scene]\nid = \"m\"\n[discretization]\ndimension = 2\nplane = \"strain\"\nspacing = 1e-3\n"
                           "horizon_ratio = 3.015\nthickness = 1e-3\n[[shape]]\ntype = \"box\"\nmin = [0, 0]\n"
                           "max = [0.01, 0.01]\n[material]\ndensity = 7850\nyoungs_modulus = 200e9\n"
                           "poissons_ratio = 0.25\n[time]\nsteps = 1\n[model]\ntype = ";
  for (const auto& info : model_table())
    EXPECT_EQ(io::parse_scene_text(head + "\"" + info.name + "\"\n", "m.toml").method, io::Method::pd) << info.name;
  EXPECT_EQ(io::parse_scene_text(head + "\"mpm\"\n", "m.toml").method, io::Method::mpm);
}

}  // namespace
}  // namespace pdmpm::pd
