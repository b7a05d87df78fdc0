// hybrid::Settings::validate: the paper's defaults pass; each bad value names its key.
#include "solver/hybrid/settings.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "solver/core/error.hpp"

namespace pdmpm::hybrid {
namespace {

void expect_rejected(const std::function<void(Settings&)>& change, const std::string& key) {
  Settings s;
  change(s);
  try {
    s.validate("scene.toml");
    ADD_FAILURE() << "accepted a bad " << key;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
  }
}

TEST(HybridSettings, DefaultsAreValid) { EXPECT_NO_THROW(Settings{}.validate("scene.toml")); }

TEST(HybridSettings, BadValuesNameTheirKey) {
  expect_rejected([](Settings& s) { s.radii.pd_radius = 0.0; }, "hybrid.pd_radius");
  expect_rejected([](Settings& s) { s.radii.expand_trigger = 8.0; }, "hybrid.expand_trigger");
  expect_rejected([](Settings& s) { s.shrink_every = 0; }, "hybrid.shrink_every");
  expect_rejected([](Settings& s) { s.tips.damage_threshold = 1.0; }, "hybrid.tips.damage_threshold");
  expect_rejected([](Settings& s) { s.tips.laplacian_threshold = 0.1; }, "hybrid.tips.laplacian_threshold");
  expect_rejected([](Settings& s) { s.tips.end_radius = 0.0; }, "hybrid.tips.end_radius");
  expect_rejected([](Settings& s) { s.tips.end_asymmetry = 1.0; }, "hybrid.tips.end_asymmetry");
  expect_rejected([](Settings& s) { s.tips.tip_offset = -1.0; }, "hybrid.tips.tip_offset");
  expect_rejected([](Settings& s) { s.tips.ridge_fraction = 1.5; }, "hybrid.tips.ridge_fraction");
  expect_rejected([](Settings& s) { s.tips.merge_radius = -3.0; }, "hybrid.tips.merge_radius");
  expect_rejected([](Settings& s) { s.tips.match_radius = 0.0; }, "hybrid.tips.match_radius");
  expect_rejected([](Settings& s) { s.revert_residual = -0.1; }, "hybrid.revert_residual");
  expect_rejected([](Settings& s) { s.revert_residual = 1.5; }, "hybrid.revert_residual");
}

}  // namespace
}  // namespace pdmpm::hybrid
