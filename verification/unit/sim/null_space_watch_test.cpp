#include "solver/sim/null_space_watch.hpp"

#include <gtest/gtest.h>

namespace pdmpm::sim {
namespace {

const GridSampling kOnePerCell{1.0, 1.0};

// Kinetic energy 1 J, strain energy 10 J; the grid sees 1 − share of it.
std::optional<std::string> check(NullSpaceWatch& w, double share, std::int64_t step) {
  return w.check(1.0, 1.0 - share, 10.0, step, 1e-9 * static_cast<double>(step), kOnePerCell);
}

TEST(NullSpaceWatch, WarnsOnlyOnceTheShareHasStayedHighForTheSustainTime) {
  NullSpaceWatch w;
  EXPECT_FALSE(check(w, 0.1, 10));
  for (std::int64_t step = 20; step < 20 + kNullSpaceSustainSteps; step += 10)
    EXPECT_FALSE(check(w, 0.5, step)) << step;
  const auto warning = check(w, 0.5, 20 + kNullSpaceSustainSteps);
  ASSERT_TRUE(warning);
  EXPECT_NE(warning->find("from step 20 (t = 2e-08 s) to step 120 (t = 1.2e-07 s)"), std::string::npos) << *warning;
  EXPECT_NE(warning->find("50 % now"), std::string::npos) << *warning;
  EXPECT_NE(warning->find("cell_factor"), std::string::npos) << *warning;
}

TEST(NullSpaceWatch, ADipBelowTheLimitStartsTheCountAgain) {
  NullSpaceWatch w;
  EXPECT_FALSE(check(w, 0.5, 10));
  EXPECT_FALSE(check(w, 0.1, 20));
  EXPECT_FALSE(check(w, 0.5, 30));
  EXPECT_FALSE(check(w, 0.5, 10 + kNullSpaceSustainSteps));
  EXPECT_TRUE(check(w, 0.5, 30 + kNullSpaceSustainSteps));
}

TEST(NullSpaceWatch, ABodyNearlyAtRestIsNotWarnedOf) {
  NullSpaceWatch w;
  for (std::int64_t step = 10; step <= 10 * kNullSpaceSustainSteps; step += 10)  // all of it unseen, but 1e-6 J of 10 J
    EXPECT_FALSE(w.check(1e-6, 0.0, 10.0, step, 0.0, kOnePerCell));
}

}  // namespace
}  // namespace pdmpm::sim
