// The eight-lane deformation update is cayley_increment<2>(L, Δt) F bit for bit, in
// every instruction set's version: random velocity gradients from rest to strain
// increments of 10 % per step, random F around a rotation, signed zeros.
#include "solver/mpm/deformation_lanes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "solver/mpm/kinematics.hpp"
#include "verification/support/same_bits.hpp"

namespace pdmpm::mpm {
namespace {

using test::same_bits;

TEST(DeformationLanes, EqualTheScalarCayleyUpdateBitForBit) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double dt = 12e-9;
  int differing = 0, compared = 0;
  for (const double rate : {0.0, 1e3, 1e6, 1e7})  // |L| Δt up to 0.1
    for (int group = 0; group < 500; ++group) {
      DeformationLanes in;
      Mat<2> L[kDeformationLanes], F[kDeformationLanes];
      for (int l = 0; l < kDeformationLanes; ++l) {
        L[l] << rate * u(rng), rate * u(rng), rate * u(rng), rate * u(rng);
        const double th = 3.0 * u(rng);
        F[l] << std::cos(th) + 0.1 * u(rng), -std::sin(th), std::sin(th), std::cos(th) + 0.1 * u(rng);
        if (group == 0 && l == 0) L[l] << -0.0, -0.0, -0.0, -0.0;
        in.l00[l] = L[l](0, 0), in.l01[l] = L[l](0, 1), in.l10[l] = L[l](1, 0), in.l11[l] = L[l](1, 1);
        in.f00[l] = F[l](0, 0), in.f01[l] = F[l](0, 1), in.f10[l] = F[l](1, 0), in.f11[l] = F[l](1, 1);
      }
      for (const auto& variant : deformation_lanes_variants()) {
        DeformationLanes out = in;
        variant.function(out, dt);
        for (int l = 0; l < kDeformationLanes; ++l) {
          const Mat<2> expected = cayley_increment<2>(L[l], dt) * F[l];
          differing += !(same_bits(expected(0, 0), out.f00[l]) && same_bits(expected(0, 1), out.f01[l]) &&
                         same_bits(expected(1, 0), out.f10[l]) && same_bits(expected(1, 1), out.f11[l]));
          ++compared;
        }
      }
    }
  EXPECT_EQ(differing, 0) << "of " << compared;
}

}  // namespace
}  // namespace pdmpm::mpm
