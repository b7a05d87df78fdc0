// Adaptive quadrature helpers: known integrals, horizon measures, and GSL
// errors coming back as exceptions (never an abort).
#include "solver/pd/constants_quadrature.hpp"

#include <gsl/gsl_errno.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace pdmpm::pd::quadrature {
namespace {

constexpr double pi = std::numbers::pi;

TEST(ConstantsQuadrature, KnownIntegrals) {
  const auto s = integrate([](double x) { return std::sin(x); }, 0.0, pi);
  EXPECT_NEAR(s.value, 2.0, 1e-14);
  EXPECT_LE(s.abserr, 1e-11);
  // Integrable endpoint singularity: ∫₀¹ x^{-1/2} dx = 2.
  EXPECT_NEAR(integrate([](double x) { return 1.0 / std::sqrt(x); }, 0.0, 1.0).value, 2.0, 1e-11);
}

TEST(ConstantsQuadrature, HorizonMeasures) {
  const double d = 2e-3, h = 1e-3, A = 1e-6;
  auto one = [](double, const Eigen::Vector3d&) { return 1.0; };
  EXPECT_NEAR(integrate_horizon(core::Setting::bar1d, d, A, one).value / (2.0 * d * A), 1.0, 1e-13);
  EXPECT_NEAR(integrate_horizon(core::Setting::plane_stress, d, h, one).value / (pi * d * d * h), 1.0, 1e-13);
  EXPECT_NEAR(integrate_horizon(core::Setting::solid3d, d, 1.0, one).value / (4.0 / 3.0 * pi * d * d * d), 1.0, 1e-13);
  // Direction average: ∫ n_x² dΩ = 4π/3 over the sphere, π over the circle.
  auto nx2 = [](double, const Eigen::Vector3d& n) { return n.x() * n.x(); };
  EXPECT_NEAR(integrate_horizon(core::Setting::solid3d, 1.0, 1.0, nx2).value, 4.0 * pi / 9.0, 1e-13);
  EXPECT_NEAR(integrate_horizon(core::Setting::plane_strain, 1.0, 1.0, nx2).value, pi / 2.0, 1e-13);
}

TEST(ConstantsQuadrature, PmbEnergyUnderShearMatchesClassical3d) {
  // PMB at ν = 1/4 reproduces the classical energy for any small strain, not
  // only the isotropic one the constant was fitted to.
  const core::Elastic m{200e9, 0.25, 7850.0};
  const double d = 3e-3;
  const double c = pmb_micromodulus(Influence::quadratic, core::Setting::solid3d, m, d, 1.0).value;
  Strain eps = Strain::Zero();
  eps(0, 2) = eps(2, 0) = 1e-3;
  const double W = pmb_energy_density(Influence::quadratic, core::Setting::solid3d, c, eps, d, 1.0).value;
  EXPECT_NEAR(W / (m.shear() * (eps.array() * eps.array()).sum()), 1.0, 1e-10);
}

TEST(ConstantsQuadrature, GslErrorsBecomeExceptions) {
  // ∫₀¹ 1/x diverges: GSL reports an error, which must come back as an exception.
  EXPECT_THROW(integrate([](double x) { return 1.0 / x; }, 0.0, 1.0), QuadratureError);
  // Too few subintervals for a tight tolerance on an oscillating integrand.
  Options few;
  few.limit = 2;
  EXPECT_THROW(integrate([](double x) { return std::sin(200.0 * x); }, 0.0, 10.0, few), QuadratureError);
}

TEST(ConstantsQuadrature, IntegrandExceptionsPropagateThroughNesting) {
  auto bad = [](double r, const Eigen::Vector3d&) -> double {
    if (r > 0.5) throw std::domain_error("integrand refused");
    return 1.0;
  };
  EXPECT_THROW(integrate_horizon(core::Setting::solid3d, 1.0, 1.0, bad), std::domain_error);
}

int count_calls = 0;
void counting_handler(const char*, const char*, int, int) { ++count_calls; }

TEST(ConstantsQuadrature, PreviousGslHandlerIsRestored) {
  gsl_error_handler_t* before = gsl_set_error_handler(&counting_handler);
  EXPECT_THROW(integrate([](double x) { return 1.0 / x; }, 0.0, 1.0), QuadratureError);
  EXPECT_EQ(count_calls, 0);  // ours was in place during the call
  EXPECT_EQ(gsl_set_error_handler(before), &counting_handler);
}

}  // namespace
}  // namespace pdmpm::pd::quadrature
