// Partial-volume factor β (docs/discretisation.md, Deryugin et al. 2023 eq 7.2) at the ends and middle of
// the ramp for each option, and the family radius each option needs.
#include "solver/pd/partial_volume.hpp"

#include <gtest/gtest.h>

namespace pdmpm::pd {
namespace {

constexpr double kPvDx = 1e-3;
constexpr double kPvDelta = 3.015e-3;

struct Row {
  double r;                        // bond length
  double none, seed001, extended;  // expected β
};

TEST(PartialVolume, RampEndsAndMiddle) {
  const Row rows[] = {
      {0.5 * kPvDelta, 1.0, 1.0, 1.0},          // well inside
      {kPvDelta - 0.5 * kPvDx, 1.0, 1.0, 1.0},  // inner end of the ramp
      {kPvDelta - 0.25 * kPvDx, 1.0, 0.75, 0.75},
      {kPvDelta, 1.0, 0.5, 0.5},  // middle of the full ramp, end of seed001's
      {kPvDelta + 0.25 * kPvDx, 0.0, 0.0, 0.25},
      {kPvDelta + 0.5 * kPvDx, 0.0, 0.0, 0.0},  // outer end of the extended ramp
      {kPvDelta + 0.75 * kPvDx, 0.0, 0.0, 0.0},
  };
  for (const auto& row : rows) {
    SCOPED_TRACE("r = " + std::to_string(row.r));
    EXPECT_NEAR(partial_volume(PartialVolume::none, row.r, kPvDelta, kPvDx), row.none, 1e-12);
    EXPECT_NEAR(partial_volume(PartialVolume::seed001, row.r, kPvDelta, kPvDx), row.seed001, 1e-12);
    EXPECT_NEAR(partial_volume(PartialVolume::extended, row.r, kPvDelta, kPvDx), row.extended, 1e-12);
  }
}

TEST(PartialVolume, BondAtTheHorizonWithinRoundingIsKept) {
  // δ computed as m·Δx may sit one ulp below a lattice distance; the stencil
  // admits such a bond (slack 1e-10), so β must not drop it either.
  const double r = kPvDelta * (1.0 + 1e-12);
  EXPECT_NEAR(partial_volume(PartialVolume::none, r, kPvDelta, kPvDx), 1.0, 1e-12);
  EXPECT_NEAR(partial_volume(PartialVolume::seed001, r, kPvDelta, kPvDx), 0.5, 1e-8);
  EXPECT_NEAR(partial_volume(PartialVolume::extended, r, kPvDelta, kPvDx), 0.5, 1e-8);
}

TEST(PartialVolume, FamilyRatio) {
  EXPECT_DOUBLE_EQ(family_ratio(PartialVolume::none, kPvDelta, kPvDx), 3.015);
  EXPECT_DOUBLE_EQ(family_ratio(PartialVolume::seed001, kPvDelta, kPvDx), 3.015);
  EXPECT_DOUBLE_EQ(family_ratio(PartialVolume::extended, kPvDelta, kPvDx), 3.515);
}

TEST(PartialVolume, ZeroBeyondTheFamilyRadius) {
  for (PartialVolume pv : {PartialVolume::none, PartialVolume::seed001, PartialVolume::extended}) {
    const double reach = family_ratio(pv, kPvDelta, kPvDx) * kPvDx;
    EXPECT_EQ(partial_volume(pv, reach * (1.0 + 1e-6), kPvDelta, kPvDx), 0.0) << name(pv);
  }
}

TEST(PartialVolume, NamesRoundTrip) {
  for (PartialVolume pv : {PartialVolume::none, PartialVolume::seed001, PartialVolume::extended}) {
    const auto parsed = find_enum<PartialVolume>(name(pv));
    ASSERT_TRUE(parsed.has_value());
    EXPECT_EQ(*parsed, pv);
  }
  EXPECT_FALSE(find_enum<PartialVolume>("seed_001").has_value());
  EXPECT_FALSE(find_enum<PartialVolume>("").has_value());
}

}  // namespace
}  // namespace pdmpm::pd
