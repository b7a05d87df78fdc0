#include "solver/analytic/crack_tip.hpp"

#include <cmath>
#include <numbers>

namespace pdmpm::analytic {
namespace {

constexpr double pi = std::numbers::pi;

// Kolosov's constant κ of the setting.
double kolosov(const core::Elastic& m, core::Setting s) {
  return s == core::Setting::plane_strain ? 3.0 - 4.0 * m.nu : (3.0 - m.nu) / (1.0 + m.nu);
}

}  // namespace

double centre_crack_factor(double alpha) {
  const double a2 = alpha * alpha;
  return (1.0 - 0.025 * a2 + 0.06 * a2 * a2) * std::sqrt(1.0 / std::cos(0.5 * pi * alpha));
}

double centre_crack_k1(double stress, double half_length, double width) {
  return stress * std::sqrt(pi * half_length) * centre_crack_factor(2.0 * half_length / width);
}

double fracture_modulus(const core::Elastic& m, core::Setting s) {
  return s == core::Setting::plane_strain ? m.E / (1.0 - m.nu * m.nu) : m.E;
}

std::array<double, 2> WilliamsModeOne::displacement(double x, double y) const {
  const double r = std::hypot(x, y), th = std::atan2(y, x), k = kolosov(material, setting);
  const double s = std::sin(0.5 * th), c = std::cos(0.5 * th);
  const double amp = k1 / (2.0 * material.shear()) * std::sqrt(r / (2.0 * pi));
  return {amp * c * (k - 1.0 + 2.0 * s * s), amp * s * (k + 1.0 - 2.0 * c * c)};
}

// u_i = A √r g_i(θ): ∂u_i/∂r = u_i / 2r, ∂u_i/∂θ = A √r g_i'(θ), then
// ∂/∂x = cos θ ∂/∂r − sin θ / r ∂/∂θ and ∂/∂y = sin θ ∂/∂r + cos θ / r ∂/∂θ.
std::array<double, 4> WilliamsModeOne::displacement_gradient(double x, double y) const {
  const double r = std::hypot(x, y), th = std::atan2(y, x), k = kolosov(material, setting);
  const double s = std::sin(0.5 * th), c = std::cos(0.5 * th);
  const double amp = k1 / (2.0 * material.shear()) * std::sqrt(r / (2.0 * pi));
  const double gx = c * (k - 1.0 + 2.0 * s * s), gy = s * (k + 1.0 - 2.0 * c * c);
  const double dgx = -0.5 * s * (k - 1.0 + 2.0 * s * s) + 2.0 * s * c * c;
  const double dgy = 0.5 * c * (k + 1.0 - 2.0 * c * c) + 2.0 * s * s * c;
  const double ct = std::cos(th), st = std::sin(th);
  auto grad = [&](double g, double dg) {
    const double dr = amp * g / (2.0 * r), dth = amp * dg;
    return std::array<double, 2>{ct * dr - st / r * dth, st * dr + ct / r * dth};
  };
  const auto gux = grad(gx, dgx), guy = grad(gy, dgy);
  return {gux[0], gux[1], guy[0], guy[1]};
}

std::array<double, 3> WilliamsModeOne::stress(double x, double y) const {
  const double r = std::hypot(x, y), th = std::atan2(y, x);
  const double s = std::sin(0.5 * th), c = std::cos(0.5 * th), s3 = std::sin(1.5 * th), c3 = std::cos(1.5 * th);
  const double amp = k1 / std::sqrt(2.0 * pi * r);
  return {amp * c * (1.0 - s * s3), amp * c * (1.0 + s * s3), amp * c * s * c3};
}

}  // namespace pdmpm::analytic
