// The plane-stress J2 return: its Newton start lies at or left of the consistency
// parameter (what a one-sided Newton on the convex, decreasing f needs) and is exact
// where one modulus scales both spectral modes; the returned stress is plane and on
// the hardened yield surface.
#include "solver/mpm/j2_plasticity.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace pdmpm::mpm {
namespace {

const core::Elastic kSteel{215e9, 0.33, 7800.0};
const core::J2Hardening kHardening{340e6, 1.45e9};

// f(Δγ) = ½φ² − ⅓κ² of Simo & Hughes (1998) §3.4 in the spectral coordinates s₁, s₂.
double consistency(double dg, double s1, double s2, double c1, double c2, double kappa0, double H) {
  const double d1 = 1.0 / (1.0 + c1 * dg), d2 = 1.0 / (1.0 + c2 * dg);
  const double phi = std::sqrt(s1 * d1 * d1 + s2 * d2 * d2);
  const double kappa = kappa0 + H * std::sqrt(2.0 / 3.0) * dg * phi;
  return 0.5 * phi * phi - kappa * kappa / 3.0;
}

TEST(J2PlaneStress, NewtonStartsAtOrLeftOfTheRoot) {
  const J2Constants k(kSteel, kHardening);
  const double c1 = k.c1, c2 = 2.0 * k.G, H = k.H;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto sqrt_of = [](double x) { return std::sqrt(x); };
  for (int i = 0; i < 100000; ++i) {
    const double kappa0 = k.yield_stress * (1.0 + 3.0 * u(rng));
    // Trial states from just beyond the yield surface to fifty times beyond it, any mix
    // of the two modes (s₁: in-plane mean stress, s₂: in-plane deviator).
    const double over = std::pow(50.0, u(rng)), share = u(rng);
    const double S = 2.0 / 3.0 * kappa0 * kappa0 * over * over;
    const double s1 = share * S, s2 = S - s1;
    const double start = plane_stress_newton_start(s1, s2, c1, c2, kappa0, H, sqrt_of);
    ASSERT_GT(start, 0.0);
    // At or left of the root: f ≥ 0 there, to f's round-off (its terms are ~κ²·over²).
    EXPECT_GE(consistency(start, s1, s2, c1, c2, kappa0, H), -1e-14 * S) << "s1 " << s1 << " s2 " << s2;
  }
  // One mode alone (s₁ = 0: a pure in-plane deviator): the start is the root.
  const double kappa0 = k.yield_stress, S = 2.0 / 3.0 * kappa0 * kappa0 * 1.21;
  const double start = plane_stress_newton_start(0.0, S, c1, c2, kappa0, H, sqrt_of);
  EXPECT_LE(std::abs(consistency(start, 0.0, S, c1, c2, kappa0, H)), 1e-14 * S);
}

TEST(J2PlaneStress, ReturnedStressIsPlaneAndOnTheHardenedYieldSurface) {
  const J2Constants k(kSteel, kHardening);
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int yielded = 0;
  for (int i = 0; i < 20000; ++i) {
    Mat<3> eps = Mat<3>::Zero();
    const double scale = 0.02 * std::abs(u(rng));  // up to twelve yield strains
    eps(0, 0) = scale * u(rng), eps(1, 1) = scale * u(rng), eps(0, 1) = eps(1, 0) = scale * u(rng);
    PointHistory h;
    h.eq_plastic_strain = 0.01 * (1.0 + u(rng));
    const double kappa_before = k.yield_stress + k.H * h.eq_plastic_strain;
    const J2Result r = j2_return_plane_stress(k, eps, h, 0.0);
    const Mat<3>& T = r.T;
    EXPECT_EQ(T(2, 2), 0.0);
    const double vm = std::sqrt(T(0, 0) * T(0, 0) - T(0, 0) * T(1, 1) + T(1, 1) * T(1, 1) + 3.0 * T(0, 1) * T(0, 1));
    if (r.d_eq_plastic > 0.0) {
      ++yielded;
      // The tolerance of the return, |f| ≤ 1e-15 κ², is ~1e-15 relative in σ_vm; 1e-12
      // leaves room for the von Mises sum's own rounding.
      EXPECT_NEAR(vm, k.yield_stress + k.H * h.eq_plastic_strain, 1e-12 * kappa_before);
    } else {
      EXPECT_LE(vm, kappa_before * (1.0 + 1e-12));
    }
  }
  EXPECT_GT(yielded, 5000);  // both branches exercised
}

}  // namespace
}  // namespace pdmpm::mpm
