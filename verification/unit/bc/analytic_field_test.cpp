#include "solver/bc/analytic_field.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace pdmpm::bc {
namespace {

TEST(AnalyticField, AffineAppliesH) {
  const core::Elastic m{1e9, 0.25, 1000};
  auto f = make_analytic_field<2>("affine", {{"h_xx", 0.1}, {"h_xy", 0.2}}, m, core::Setting::plane_strain);
  Vec<2> u, v;
  f->evaluate(Vec<2>(1, 2), 0.0, u, v);
  EXPECT_DOUBLE_EQ(u[0], 0.1 + 0.4);
  EXPECT_DOUBLE_EQ(u[1], 0.0);
  EXPECT_EQ(v, Vec<2>::Zero());
}

TEST(AnalyticField, SphericalWaveIsRadialAndMatchesTheSourceAtR0) {
  const core::Elastic m{200e9, 0.25, 7850};
  auto f = make_analytic_field<3>("spherical_wave", {{"r0", 0.01}, {"period", 1e-5}, {"amplitude", 1e-4}}, m,
                                  core::Setting::solid3d);
  Vec<3> u, v;
  const Vec<3> x(0.006, 0.008, 0.0);  // r = r0
  const double t = 0.3e-5;
  f->evaluate(x, t, u, v);
  EXPECT_NEAR(u.norm(), 1e-4 * std::abs(std::sin(2 * M_PI * t / 1e-5)), 1e-16);
  EXPECT_NEAR(u.normalized().dot(x.normalized()), 1.0, 1e-12);
}

TEST(AnalyticField, ParametersAreChecked) {
  EXPECT_THROW(check_analytic_parameters("spherical_wave", {{"r0", 0.01}}), std::invalid_argument);
  EXPECT_THROW(check_analytic_parameters("affine", {{"bogus", 1}}), std::invalid_argument);
  EXPECT_NO_THROW(check_analytic_parameters("affine", {{"h_zz", 1}}));
}

}  // namespace
}  // namespace pdmpm::bc
