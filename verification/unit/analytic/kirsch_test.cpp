#include "solver/analytic/kirsch.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace pdmpm::analytic {
namespace {

constexpr double pi = std::numbers::pi;

TEST(Kirsch, ConcentrationThreeAcrossTheLoad) {
  const Kirsch k{0.005, 10e6};
  EXPECT_NEAR(k.polar(k.radius, pi / 2)[1], 3 * k.stress, 1e-9 * k.stress);
  EXPECT_NEAR(k.polar(k.radius, 0.0)[1], -k.stress, 1e-9 * k.stress);
  const auto s = k.cartesian(k.radius, 0.0);  // on the x axis: across a load along y
  EXPECT_NEAR(s[1], 3 * k.stress, 1e-9 * k.stress);
  EXPECT_NEAR(s[0], 0.0, 1e-9 * k.stress);
  EXPECT_NEAR(s[2], 0.0, 1e-9 * k.stress);
}

TEST(Kirsch, HoleIsTractionFreeAndFarFieldIsUniaxial) {
  const Kirsch k{1.0, 1.0};
  for (double th = 0.0; th < 2 * pi; th += 0.3) {
    const auto p = k.polar(1.0, th);
    EXPECT_NEAR(p[0], 0.0, 1e-14);
    EXPECT_NEAR(p[2], 0.0, 1e-14);
    const auto far = k.cartesian(1e4 * std::sin(th), 1e4 * std::cos(th));
    EXPECT_NEAR(far[0], 0.0, 1e-7);
    EXPECT_NEAR(far[1], 1.0, 1e-7);
    EXPECT_NEAR(far[2], 0.0, 1e-7);
  }
}

TEST(Kirsch, CartesianFieldIsInEquilibrium) {
  // ∂σ_xx/∂x + ∂σ_xy/∂y = 0 and ∂σ_xy/∂x + ∂σ_yy/∂y = 0, central differences.
  const Kirsch k{1.0, 1.0};
  const double h = 1e-5;
  for (auto [x, y] : {std::pair{1.3, 0.4}, {-0.7, 1.9}, {2.5, -2.0}}) {
    const auto xp = k.cartesian(x + h, y), xm = k.cartesian(x - h, y);
    const auto yp = k.cartesian(x, y + h), ym = k.cartesian(x, y - h);
    EXPECT_NEAR((xp[0] - xm[0] + yp[2] - ym[2]) / (2 * h), 0.0, 1e-7);
    EXPECT_NEAR((xp[2] - xm[2] + yp[1] - ym[1]) / (2 * h), 0.0, 1e-7);
  }
}

TEST(Kirsch, FiniteWidthFitsAgreeAndTendToThree) {
  for (auto fit : {WidthCorrection::heywood, WidthCorrection::roark}) {
    EXPECT_NEAR(finite_width_kt(0.0, fit), 3.0, 1e-12);
    EXPECT_GT(finite_width_kt(0.2, fit), 3.0);
  }
  // Both approximate Howland's solution; at d/W = 0.2 they differ by 0.15 %.
  const double h = finite_width_kt(0.2, WidthCorrection::heywood), r = finite_width_kt(0.2, WidthCorrection::roark);
  EXPECT_NEAR(h, 3.14, 1e-12);
  EXPECT_NEAR(r / h - 1.0, 0.0, 2e-3);
  EXPECT_THROW(finite_width_kt(1.0, WidthCorrection::roark), std::invalid_argument);
}

}  // namespace
}  // namespace pdmpm::analytic
