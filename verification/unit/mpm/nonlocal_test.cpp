// Non-local averaging: equals the brute-force weighted sum, keeps uniform and
// (away from edges) linear fields, and ignores particles not flagged for use.
#include "solver/mpm/nonlocal.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace pdmpm::mpm {
namespace {

TEST(Nonlocal, MatchesBruteForceAndPreservesLinearFields) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  std::vector<Vec<2>> x;
  std::vector<double> vol, a, lin;
  for (int i = 0; i < 30; ++i)
    for (int j = 0; j < 20; ++j) {
      x.push_back(Vec<2>(i + jitter(rng), j + jitter(rng)) * 1e-3);
      vol.push_back(1e-6 * (1.0 + jitter(rng)));
      a.push_back(std::sin(0.3 * i) + 0.1 * j);
      lin.push_back(2.0 + 500.0 * i * 1e-3);
    }
  std::vector<std::uint8_t> use(x.size(), 1);
  use[17] = 0;  // a failed particle: neither averaged nor contributing
  const double ell = 1.5e-3;
  std::vector<double> out;
  nonlocal_average<2>(x, vol, a, use, ell, out);
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!use[i]) continue;
    double num = 0, den = 0;
    for (std::size_t j = 0; j < x.size(); ++j) {
      if (!use[j]) continue;
      const double r = (x[i] - x[j]).norm();
      if (r > 3 * ell) continue;
      const double w = std::exp(-(r / ell) * (r / ell)) * vol[j];
      num += w * a[j];
      den += w;
    }
    EXPECT_NEAR(out[i], num / den, 1e-14);
  }
  // A uniform field stays uniform everywhere.
  std::vector<double> ones(x.size(), 0.7);
  nonlocal_average<2>(x, vol, ones, use, ell, out);
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (use[i]) {
      EXPECT_NEAR(out[i], 0.7, 1e-14);  // rounding of ~100-term weighted sums
    }
  }
}

}  // namespace
}  // namespace pdmpm::mpm
