#include "solver/analytic/spherical_wave.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace pdmpm::analytic {
namespace {

// Deryugin et al. 2023 §9 with the PMB material: c_p = √(240 GPa / 7850).
SphericalWave seed_wave() {
  SphericalWave w;
  w.r0 = 0.01;
  w.period = 1e-5;
  w.amplitude = 1e-4;
  w.cp = std::sqrt(240e9 / 7850.0);
  return w;
}

TEST(SphericalWave, WallFollowsTheSource) {
  const auto w = seed_wave();
  for (double t : {0.0, 0.1e-5, 0.37e-5, 1.25e-5, 6.9e-5}) {
    EXPECT_NEAR(w.radial_displacement(w.r0, t), w.source(t), 1e-15 * w.amplitude) << t;
    EXPECT_NEAR(w.radial_velocity(w.r0, t), w.source_rate(t), 1e-9 * w.amplitude * 2 * std::numbers::pi / w.period) << t;
  }
}

TEST(SphericalWave, NothingAheadOfTheFront) {
  const auto w = seed_wave();
  const double t = 3e-5;
  EXPECT_EQ(w.radial_displacement(w.front(t) * 1.001, t), 0.0);
  EXPECT_EQ(w.radial_velocity(w.front(t) * 1.001, t), 0.0);
  // Displacement is continuous at the front (the source starts from rest position).
  EXPECT_NEAR(w.radial_displacement(w.front(t) * 0.99999, t), 0.0, 1e-4 * w.amplitude);
}

TEST(SphericalWave, DerivativesAreConsistent) {
  // F' and F'' against central differences of the closed form (h² error ~ 1e-8 relative).
  const auto w = seed_wave();
  const double h = 1e-10;
  for (double tau : {0.2e-5, 0.9e-5, 2.3e-5}) {
    const double scale = std::abs(w.F(tau)) / tau + std::abs(w.dF(tau));
    EXPECT_NEAR((w.F(tau + h) - w.F(tau - h)) / (2 * h), w.dF(tau), 1e-6 * scale) << tau;
    EXPECT_NEAR((w.dF(tau + h) - w.dF(tau - h)) / (2 * h), w.d2F(tau), 1e-6 * std::abs(w.d2F(tau)) + 1e-6 * scale / tau) << tau;
    // The ODE F' + (c/r0) F = −c r0 g.
    EXPECT_NEAR(w.dF(tau) + w.cp / w.r0 * w.F(tau), -w.cp * w.r0 * w.source(tau), 1e-12 * scale);
  }
  for (double r : {0.02, 0.1}) {
    const double t = 2.5e-5, hv = 1e-10;
    const double du = (w.radial_displacement(r, t + hv) - w.radial_displacement(r, t - hv)) / (2 * hv);
    EXPECT_NEAR(du, w.radial_velocity(r, t), 1e-6 * std::abs(w.radial_velocity(r, t)) + 1e-3) << r;
  }
}

TEST(SphericalWave, SatisfiesTheRadialWaveEquation) {
  // u_tt = c² (u_rr + 2 u_r / r − 2 u / r²) for the radial displacement of an
  // irrotational field, checked by fourth-order central differences.
  const auto w = seed_wave();
  auto u = [&](double r, double t) { return w.radial_displacement(r, t); };
  for (double r : {0.015, 0.05, 0.12}) {
    const double t = (r - w.r0) / w.cp + 1.3e-5;  // behind the front
    const double hr = 2e-5, ht = hr / w.cp;
    auto d1 = [](double fm2, double fm1, double fp1, double fp2, double h) { return (fm2 - 8 * fm1 + 8 * fp1 - fp2) / (12 * h); };
    auto d2 = [](double fm2, double fm1, double f0, double fp1, double fp2, double h) {
      return (-fm2 + 16 * fm1 - 30 * f0 + 16 * fp1 - fp2) / (12 * h * h);
    };
    const double u0 = u(r, t);
    const double utt = d2(u(r, t - 2 * ht), u(r, t - ht), u0, u(r, t + ht), u(r, t + 2 * ht), ht);
    const double ur = d1(u(r - 2 * hr, t), u(r - hr, t), u(r + hr, t), u(r + 2 * hr, t), hr);
    const double urr = d2(u(r - 2 * hr, t), u(r - hr, t), u0, u(r + hr, t), u(r + 2 * hr, t), hr);
    const double rhs = w.cp * w.cp * (urr + 2 * ur / r - 2 * u0 / (r * r));
    EXPECT_NEAR(utt, rhs, 1e-6 * std::abs(utt) + 1e-6 * w.cp * w.cp * 2 * std::abs(u0) / (r * r)) << r;
  }
}

TEST(SphericalWave, CavityContinuationMeetsTheWall) {
  const auto w = seed_wave();
  const double t = 0.4e-5;
  EXPECT_NEAR(w.radial_displacement(w.r0 * (1 - 1e-12), t), w.radial_displacement(w.r0, t), 1e-12 * w.amplitude);
  EXPECT_DOUBLE_EQ(w.radial_displacement(0.5 * w.r0, t), 0.5 * w.source(t));
  EXPECT_EQ(w.radial_displacement(0.5 * w.r0, 0.0), 0.0);
}

}  // namespace
}  // namespace pdmpm::analytic
