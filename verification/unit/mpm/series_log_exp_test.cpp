// The series that replace the library's ln and exp inside a material point's strain
// range are within an ulp or two of the exact value across the whole range and at its ends,
// and the scalar wrappers hand everything beyond it (and non-finite input) to the library.
#include "solver/mpm/series_log_exp.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace pdmpm::mpm {
namespace {

// |a − b| in units of the last place of b.
double ulps(double a, double b) { return std::abs(a - b) / (std::nextafter(std::abs(b), 1e300) - std::abs(b)); }

// The references: x87 extended precision (64-bit significand) rounded to double.
double half_log_reference(double d) { return static_cast<double>(0.5L * std::log(static_cast<long double>(d))); }
double exp_reference(double t) { return static_cast<double>(std::exp(static_cast<long double>(t))); }

TEST(SeriesLogExp, HalfLogIsWithinTwoUlpsForDeterminantsNearOne) {
  std::mt19937 rng(11);
  // z = (d − 1)/(d + 1) < 0.1 ⇔ d in (9/11, 11/9); a little beyond, the library answers.
  std::uniform_real_distribution<double> d_of(0.8, 1.25);
  double worst = 0.0;
  for (int i = 0; i < 200000; ++i) {
    const double d = d_of(rng);
    if (d == 1.0) continue;
    worst = std::max(worst, ulps(series_half_log(d), half_log_reference(d)));
  }
  // Two ulps: z = (d − 1)/(d + 1) rounds twice, z + z·(…) once more (series_log_exp.hpp).
  EXPECT_LE(worst, 2.0);
  EXPECT_EQ(series_half_log(1.0), 0.0);
  for (const double d : {1e-300, 1e-3, 0.5, 2.0, 1e3, 1e300})  // beyond the series: the library
    EXPECT_EQ(series_half_log(d), 0.5 * std::log(d)) << d;
  EXPECT_TRUE(std::isnan(series_half_log(std::numeric_limits<double>::quiet_NaN())));
  EXPECT_TRUE(std::isnan(series_half_log(-1.0)));
}

TEST(SeriesLogExp, ExpIsWithinOneUlpForSmallArguments) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> t_of(-0.11, 0.11);
  double worst = 0.0;
  for (int i = 0; i < 200000; ++i) {
    const double t = t_of(rng);
    worst = std::max(worst, ulps(series_exp(t), exp_reference(t)));
  }
  EXPECT_LE(worst, 1.0);  // Horner from the small end: each step adds a term below the sum's ulp
  EXPECT_EQ(series_exp(0.0), 1.0);
  for (const double t : {-700.0, -1.0, 0.1, 1.0, 700.0}) EXPECT_EQ(series_exp(t), std::exp(t)) << t;
  EXPECT_TRUE(std::isnan(series_exp(std::numeric_limits<double>::quiet_NaN())));
  EXPECT_EQ(series_exp(std::numeric_limits<double>::infinity()), std::numeric_limits<double>::infinity());
}

TEST(SeriesLogExp, HalfLogAndExpInvertEachOtherNearTheIdentity) {
  // J = exp(tr ln U) of a stretch with det U = d: exp(2 · ½ ln d) = d. Four ulps: the half-log's
  // two ulps of |ln d| are far below an ulp of d, exp adds one, and d itself rounds once.
  for (double d = 0.85; d < 1.15; d += 0.001) EXPECT_LE(ulps(series_exp(2.0 * series_half_log(d)), d), 4.0) << d;
}

}  // namespace
}  // namespace pdmpm::mpm
