// Influence functions (Deryugin et al. 2023 table 4.1, plus ω = δ/r): values at the ends
// and the middle of the horizon, and name parsing.
#include "solver/pd/influence.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace pdmpm::pd {
namespace {

constexpr double delta = 3e-3;

struct Expected {
  Influence w;
  double at0, at_half, at_delta;
};

TEST(Influence, ValuesAtZeroHalfAndFullHorizon) {
  const double inf = std::numeric_limits<double>::infinity();
  const Expected table[] = {
      {Influence::constant, 1.0, 1.0, 1.0},
      {Influence::triangular, 1.0, 0.5, 0.0},
      {Influence::quadratic, 1.0, 0.5625, 0.0},  // (1 − 1/4)²
      {Influence::semi_elliptical, 1.0, 0.75, 0.0},
      {Influence::exponential, 1.0, std::exp(-0.5), std::exp(-1.0)},
      {Influence::gaussian, 1.0, std::exp(-0.25), std::exp(-1.0)},
      {Influence::inverse_distance, inf, 2.0, 1.0},  // δ/r
  };
  for (const auto& e : table) {
    SCOPED_TRACE(std::string(name(e.w)));
    EXPECT_DOUBLE_EQ(influence(e.w, 0.0, delta), e.at0);
    EXPECT_DOUBLE_EQ(influence(e.w, 0.5 * delta, delta), e.at_half);
    EXPECT_NEAR(influence(e.w, delta, delta), e.at_delta, 1e-15);
  }
}

TEST(Influence, DependsOnlyOnRatio) {
  for (Influence w : all_influences)
    EXPECT_DOUBLE_EQ(influence(w, 0.3 * delta, delta), influence(w, 0.3, 1.0)) << name(w);
}

TEST(Influence, NonIncreasingOverTheHorizon) {
  for (Influence w : all_influences) {
    double prev = influence(w, 1e-6 * delta, delta);
    for (int k = 1; k <= 100; ++k) {
      const double v = influence(w, 0.01 * k * delta, delta);
      EXPECT_LE(v, prev) << name(w) << " at r/δ = " << 0.01 * k;
      EXPECT_GE(v, 0.0) << name(w);
      prev = v;
    }
  }
}

TEST(Influence, NamesRoundTrip) {
  for (Influence w : all_influences) {
    const auto parsed = find_enum<Influence>(name(w));
    ASSERT_TRUE(parsed.has_value()) << name(w);
    EXPECT_EQ(*parsed, w);
    EXPECT_NE(enum_names<Influence>().find(std::string(name(w))), std::string::npos);
  }
  EXPECT_EQ(name(Influence::inverse_distance), "inverse_distance");
}

TEST(Influence, UnknownNamesAreRejected) {
  EXPECT_FALSE(find_enum<Influence>("").has_value());
  EXPECT_FALSE(find_enum<Influence>("Constant").has_value());  // case matters
  EXPECT_FALSE(find_enum<Influence>("spherical").has_value());
  EXPECT_FALSE(find_enum<Influence>("gaussian ").has_value());
}

}  // namespace
}  // namespace pdmpm::pd
