// The eight-lane GIMP weights are the scalar weights_1d's, bit for bit: at random
// positions and half-widths, on the region boundaries |r| = lp, h − lp, h + lp where
// a lattice with a cell of 2Δx puts its particles, and at signed zeros.
#include "solver/mpm/gimp_lanes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "solver/mpm/shape_function.hpp"

namespace pdmpm::mpm {
namespace {

int differing_lanes(GimpLanesFunction gimp, const std::vector<double>& x, const std::vector<double>& lp, double h);

// Compares every lane of every instruction set's version with weights_1d; returns
// the number of lanes that differ.
int differing_lanes(const std::vector<double>& x, const std::vector<double>& lp, double h) {
  int bad = 0;
  for (const auto& variant : gimp_lanes_variants()) bad += differing_lanes(variant.function, x, lp, h);
  return bad;
}

int differing_lanes(GimpLanesFunction gimp, const std::vector<double>& x, const std::vector<double>& lp, double h) {
  int bad = 0;
  for (std::size_t i0 = 0; i0 + kGimpLanes <= x.size(); i0 += kGimpLanes) {
    GimpLanes lanes;
    gimp(&x[i0], &lp[i0], h, lanes);
    for (int l = 0; l < kGimpLanes; ++l) {
      const Weights1D s = weights_1d(ShapeFunction::gimp, x[i0 + l], h, lp[i0 + l]);
      bool same = s.first == lanes.first[l];
      for (int n = 0; n < 3; ++n)
        same = same && std::memcmp(&s.w[n], &lanes.w[n][l], sizeof(double)) == 0 &&
            std::memcmp(&s.dw[n], &lanes.dw[n][l], sizeof(double)) == 0;
      bad += !same;
    }
  }
  return bad;
}

TEST(GimpLanes, EqualTheScalarWeightsAtRandomPositions) {
  const double h = 1e-3;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> pos(0.0, 50 * h), width(0.05 * h, 0.5 * h);
  std::vector<double> x(80000), lp(80000);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = pos(rng), lp[i] = width(rng);
  EXPECT_EQ(differing_lanes(x, lp, h), 0);
}

TEST(GimpLanes, EqualTheScalarWeightsOnRegionBoundaries) {
  // A lattice of spacing Δx = h/2 with lp = Δx/2 puts particles at 0.25 h and 0.75 h
  // from a node: exactly on |r| = lp and |r| = h − lp. Perturb by a few ulps either way.
  const double h = 2 * 0.5e-3, lp0 = 0.25 * h;
  std::vector<double> x, lp;
  for (int cell = 3; cell < 40; ++cell)
    for (const double offset : {0.25, 0.75, 0.5, 0.0})
      for (int ulps = -3; ulps <= 3; ++ulps) {
        double v = (cell + offset) * h;
        for (int u = 0; u < std::abs(ulps); ++u) v = std::nextafter(v, ulps < 0 ? 0.0 : 1.0);
        x.push_back(v);
        lp.push_back(lp0);
      }
  while (x.size() % kGimpLanes) x.push_back(x.back()), lp.push_back(lp0);
  EXPECT_EQ(differing_lanes(x, lp, h), 0);
}

TEST(GimpLanes, GiveAPartitionOfUnity) {
  const double h = 1.0;
  const double x[kGimpLanes] = {3.0, 3.1, 3.25, 3.5, 3.75, 3.9, 3.99, 4.0};
  const double lp[kGimpLanes] = {0.25, 0.25, 0.25, 0.25, 0.25, 0.1, 0.5, 0.4};
  GimpLanes lanes;
  gimp_lanes(x, lp, h, lanes);
  for (int l = 0; l < kGimpLanes; ++l) {
    // Sums of three weights of order 1: a few ulps of 1.
    EXPECT_NEAR(lanes.w[0][l] + lanes.w[1][l] + lanes.w[2][l], 1.0, 1e-14) << "lane " << l;
    EXPECT_NEAR(lanes.dw[0][l] + lanes.dw[1][l] + lanes.dw[2][l], 0.0, 1e-13) << "lane " << l;
  }
}

}  // namespace
}  // namespace pdmpm::mpm
