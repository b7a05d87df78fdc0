// The eight-lane polar decomposition is polar_log<2>, bit for bit, in every lane it
// does not flag; it flags exactly the inverted gradients and those beyond the
// series' range, which the caller hands to polar_log<2>.
#include "solver/mpm/polar_lanes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "solver/core/error.hpp"
#include "solver/mpm/kinematics.hpp"
#include "verification/support/same_bits.hpp"

namespace pdmpm::mpm {
namespace {

using test::same_bits;

struct PolarTally {
  int differing = 0, flagged = 0, inverted_unflagged = 0;
};

// Runs every instruction set's version over the gradients, eight at a time.
PolarTally compare(const std::vector<Mat<2>>& F) {
  PolarTally t;
  for (const auto& variant : polar_lanes_variants())
    for (std::size_t i0 = 0; i0 + kPolarLanes <= F.size(); i0 += kPolarLanes) {
      PolarLanes lanes;
      for (int l = 0; l < kPolarLanes; ++l) {
        const Mat<2>& f = F[i0 + l];
        lanes.f00[l] = f(0, 0), lanes.f10[l] = f(1, 0), lanes.f01[l] = f(0, 1), lanes.f11[l] = f(1, 1);
      }
      const unsigned flags = variant.function(lanes);
      for (int l = 0; l < kPolarLanes; ++l) {
        const Mat<2>& f = F[i0 + l];
        if (flags >> l & 1u) {
          ++t.flagged;
          continue;
        }
        if (!(f.determinant() > 0.0)) ++t.inverted_unflagged;
        PolarLog<2> ref;
        try {
          ref = polar_log<2>(f);
        } catch (const RunError&) {
          ++t.differing;
          continue;
        }
        const bool same = same_bits(ref.R(0, 0), lanes.c[l]) && same_bits(ref.R(1, 0), lanes.s[l]) &&
            same_bits(ref.R(0, 1), -lanes.s[l]) && same_bits(ref.log_U(0, 0), lanes.l00[l]) &&
            same_bits(ref.log_U(0, 1), lanes.l01[l]) && same_bits(ref.log_U(1, 0), lanes.l01[l]) &&
            same_bits(ref.log_U(1, 1), lanes.l11[l]);
        t.differing += !same;
      }
    }
  return t;
}

// F = R(θ) (I + ε G) with G's entries uniform in [−1, 1].
std::vector<Mat<2>> gradients(double strain, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), angle(-3.14, 3.14);
  std::vector<Mat<2>> F(n);
  for (auto& f : F) {
    Mat<2> G;
    G << u(rng), u(rng), u(rng), u(rng);
    const double th = angle(rng);
    Mat<2> R;
    R << std::cos(th), -std::sin(th), std::sin(th), std::cos(th);
    f = R * (Mat<2>::Identity() + strain * G);
  }
  return F;
}

TEST(PolarLanes, EqualPolarLogBitForBitForMetalStrains) {
  for (const double strain : {1e-6, 1e-4, 1e-2}) {
    const PolarTally t = compare(gradients(strain, 4000, 5));
    EXPECT_EQ(t.differing, 0) << "strain " << strain;
    EXPECT_EQ(t.flagged, 0) << "strain " << strain;  // r/m stays far below 0.1
  }
}

TEST(PolarLanes, FlagLargeStrainsAndInvertedGradientsOnly) {
  std::vector<Mat<2>> F = gradients(0.4, 4000, 6);  // some beyond r/m = 0.1, some inverted
  F[3] << -1.0, 0.0, 0.0, 1.0;                      // a reflection: det F < 0
  F[9] << std::nan(""), 0.0, 0.0, 1.0;
  const PolarTally t = compare(F);
  EXPECT_EQ(t.differing, 0);
  EXPECT_EQ(t.inverted_unflagged, 0);
  EXPECT_GT(t.flagged, 0);
}

}  // namespace
}  // namespace pdmpm::mpm
