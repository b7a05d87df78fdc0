// The eight-lane ductile fracture strain is fracture_strain(d₀, c, triaxiality(τ / J))
// bit for bit in every lane, for every instruction set: random plane-stress states
// over the stress range of metals, and special states (stress-free, signed zeros,
// subnormal, non-finite, J = 0). Triaxiality's hydrostatic branch cannot be reached in
// plane stress (σ₃₃ = 0 keeps σ_eq ≥ |σ_m|), so no case aims at it.
#include "solver/mpm/ductile_lanes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "solver/mpm/stress_measures.hpp"
#include "verification/support/same_bits.hpp"

namespace pdmpm::mpm {
namespace {

struct PlaneStressPoint {
  double k00, k01, k10, k11, J;
};

// Lanes differing from the scalar functions, over every version; each group of eight
// asks for a different set of lanes (`needed`), and a lane not asked for must hold d₀.
int differing(const std::vector<PlaneStressPoint>& points, double d0, double c) {
  int n = 0;
  for (const auto& variant : fracture_strain_lanes_variants())
    for (std::size_t i0 = 0; i0 + kLawLanes <= points.size(); i0 += kLawLanes) {
      const unsigned needed = i0 % (3 * kLawLanes) == 0 ? 0xffu : static_cast<unsigned>(i0 / kLawLanes * 37u) & 0xffu;
      PlaneStressLanes lanes;
      double strain[kLawLanes];
      for (int l = 0; l < kLawLanes; ++l) {
        const PlaneStressPoint& q = points[i0 + l];
        lanes.k00[l] = q.k00, lanes.k01[l] = q.k01, lanes.k10[l] = q.k10, lanes.k11[l] = q.k11, lanes.J[l] = q.J;
      }
      variant.function(d0, c, lanes, needed, strain);
      for (int l = 0; l < kLawLanes; ++l) {
        const PlaneStressPoint& q = points[i0 + l];
        Mat<3> tau = Mat<3>::Zero();
        tau(0, 0) = q.k00, tau(0, 1) = q.k01, tau(1, 0) = q.k10, tau(1, 1) = q.k11;
        const Mat<3> sigma = tau / q.J;
        const double expected = needed >> l & 1u ? fracture_strain(d0, c, triaxiality(sigma)) : d0;
        n += !test::same_bits(expected, strain[l]);
      }
    }
  return n;
}

TEST(DuctileLanes, EqualTheScalarCriterionBitForBit) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> stress(-1.5e9, 1.5e9), volume(0.9, 1.1);
  std::vector<PlaneStressPoint> points(16000);
  for (auto& q : points) {
    const double shear = stress(rng);
    q = {stress(rng), shear, shear, stress(rng), volume(rng)};
  }
  for (std::size_t i = 0; i < points.size(); i += 4) points[i].k10 = stress(rng);  // τ not symmetric
  EXPECT_EQ(differing(points, 0.8, -1.5), 0);
  EXPECT_EQ(differing(points, 2.6, 1.5), 0);
}

TEST(DuctileLanes, EqualTheScalarCriterionOnSpecialStates) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<PlaneStressPoint> points{
      {0.0, 0.0, 0.0, 0.0, 1.0},                // stress-free: η = 0
      {-0.0, -0.0, -0.0, -0.0, 1.0},            // signed zeros
      {3e8, 0.0, 0.0, 3e8, 1.0},                // equibiaxial
      {3e8, 0.0, 0.0, 0.0, 1.02},               // uniaxial
      {0.0, 2e8, 2e8, 0.0, 0.98},               // pure shear
      {-3e8, 0.0, 0.0, 0.0, 1.0},               // uniaxial compression
      {1e-300, 0.0, 0.0, 1e-300, 1.0},          // tiny, equibiaxial
      {5e8, 1e-320, 1e-320, 5e8, 1.0},          // subnormal shear
      {inf, 0.0, 0.0, 1e8, 1.0},                // not finite
      {nan, 0.0, 0.0, 1e8, 1.0},                // not a number
      {1e8, 1e8, 1e8, 1e8, 0.0},                // J = 0
      {-0.0, 0.0, 0.0, -0.0, 1.0},              // σ_m = −0
      {2e8, -1e8, -1e8, 2e8, 1.0},              // biaxial with shear
      {1e9, 1e9, -1e9, 1e9, 1.1},               // τ not symmetric
      {-7e8, 3e8, 3e8, -7e8, 0.95},             // biaxial compression with shear
      {1e8, 0.0, 0.0, 1e8 * (1 + 1e-15), 1.0},  // nearly equibiaxial
  };
  EXPECT_EQ(differing(points, 0.8, -1.5), 0);
}

// Which lanes need ε_f: those that flowed (both rules), and for the rule "strain" also
// those with plastic strain (α = ε̄_p + offset > 0); all of them where e^{cη} may round to
// zero; never a lane past n.
TEST(DuctileLanes, OnlyPointsWhoseCriterionCanChangeNeedTheFractureStrain) {
  PlaneStressLanes law;
  for (int l = 0; l < kLawLanes; ++l) law.alpha[l] = l % 3 == 0 ? 0.0 : (l % 3 == 1 ? 0.02 : -0.01);
  law.yielded = 0b10010001u;  // lanes 0, 4, 7
  core::DuctileFailure rule;
  rule.enabled = true, rule.d0 = 1.0, rule.c = -1.5;
  rule.rule = core::FailureRule::accumulated;
  EXPECT_EQ(lanes_needing_fracture_strain(rule, law, kLawLanes), 0b10010001u);
  EXPECT_EQ(lanes_needing_fracture_strain(rule, law, 5), 0b00010001u);
  rule.rule = core::FailureRule::strain;  // α > 0 in lanes 1, 4, 7
  EXPECT_EQ(lanes_needing_fracture_strain(rule, law, kLawLanes), 0b10010011u);
  rule.c = -2000.0;
  EXPECT_EQ(lanes_needing_fracture_strain(rule, law, kLawLanes), 0xffu);
  EXPECT_EQ(lanes_needing_fracture_strain(rule, law, 3), 0b111u);
}

}  // namespace
}  // namespace pdmpm::mpm
