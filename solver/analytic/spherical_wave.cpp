#include "solver/analytic/spherical_wave.hpp"

#include <cmath>
#include <numbers>

namespace pdmpm::analytic {

double SphericalWave::source(double t) const {
  if (t <= 0.0) return 0.0;
  return amplitude * std::sin(2.0 * std::numbers::pi * t / period);
}

double SphericalWave::source_rate(double t) const {
  if (t <= 0.0) return 0.0;
  const double w = 2.0 * std::numbers::pi / period;
  return amplitude * w * std::cos(w * t);
}

double SphericalWave::F(double tau) const {
  if (tau <= 0.0) return 0.0;
  const double a = cp / r0, w = 2.0 * std::numbers::pi / period;
  return -cp * r0 * amplitude * (a * std::sin(w * tau) - w * std::cos(w * tau) + w * std::exp(-a * tau)) / (a * a + w * w);
}

double SphericalWave::dF(double tau) const {
  if (tau <= 0.0) return 0.0;
  return -cp * r0 * source(tau) - (cp / r0) * F(tau);
}

double SphericalWave::d2F(double tau) const {
  if (tau <= 0.0) return 0.0;
  return -cp * r0 * source_rate(tau) - (cp / r0) * dF(tau);
}

double SphericalWave::radial_displacement(double r, double t) const {
  if (r < r0) return source(t) * r / r0;
  const double tau = t - (r - r0) / cp;
  return -dF(tau) / (cp * r) - F(tau) / (r * r);
}

double SphericalWave::radial_velocity(double r, double t) const {
  if (r < r0) return source_rate(t) * r / r0;
  const double tau = t - (r - r0) / cp;
  return -d2F(tau) / (cp * r) - dF(tau) / (r * r);
}

}  // namespace pdmpm::analytic
