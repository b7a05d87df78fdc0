#include "solver/pd/precrack.hpp"

#include <gtest/gtest.h>

#include "verification/support/pd_fixtures.hpp"

namespace pdmpm::pd {
namespace {

TEST(Precrack, SegmentCutsExactlyTheCrossingBonds2D) {
  test::BlockSpec spec;
  spec.sites = 10;
  spec.spacing = 1.0;
  spec.setting = core::Setting::plane_strain;
  spec.measure = 1.0;
  auto sys = test::make_block<2>(spec);
  // Vertical crack at x = 4.5 from y = −1 to y = 20 (through the whole block).
  CrackSurface<2> crack{{Vec<2>(4.5, -1), Vec<2>(4.5, 20)}};
  const auto cut = cut_bonds<2>(sys, crack);
  EXPECT_GT(cut, 0);
  for (Index i = 0; i < sys.n_real(); ++i)
    for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b) {
      const double xi = sys.particles.x0[i][0], xj = sys.particles.x0[sys.families.neighbor[b]][0];
      EXPECT_EQ(sys.bonds.broken(b), (xi < 4.5) != (xj < 4.5));
    }
}

TEST(Precrack, ParticleOnTheCrackLineKeepsOneSide) {
  test::BlockSpec spec;
  spec.sites = 10;
  spec.spacing = 1.0;
  spec.setting = core::Setting::plane_strain;
  auto sys = test::make_block<2>(spec);
  CrackSurface<2> crack{{Vec<2>(4.0, -1), Vec<2>(4.0, 20)}};  // through a column of sites
  cut_bonds<2>(sys, crack);
  for (Index i = 0; i < sys.n_real(); ++i) {
    BondIndex intact = 0;
    for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b) intact += !sys.bonds.broken(b);
    EXPECT_GT(intact, 0) << "particle " << i << " lost every bond";
  }
}

TEST(Precrack, FiniteSegmentOnlyCutsNearIt) {
  test::BlockSpec spec;
  spec.sites = 20;
  spec.spacing = 1.0;
  spec.setting = core::Setting::plane_strain;
  auto sys = test::make_block<2>(spec);
  CrackSurface<2> crack{{Vec<2>(9.5, 8.2), Vec<2>(9.5, 10.8)}};
  cut_bonds<2>(sys, crack);
  for (Index i = 0; i < sys.n_real(); ++i)
    for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b)
      if (sys.bonds.broken(b)) {
        const Vec<2> mid = 0.5 * (sys.particles.x0[i] + sys.particles.x0[sys.families.neighbor[b]]);
        EXPECT_LT(std::abs(mid[1] - 9.5), 3.0);
      }
}

TEST(Precrack, PlaneCutsBonds3D) {
  test::BlockSpec spec;
  spec.sites = 8;
  spec.spacing = 1.0;
  auto sys = test::make_block<3>(spec);
  CrackSurface<3> crack{{Vec<3>(3.5, -1, -1), Vec<3>(3.5, 10, -1), Vec<3>(3.5, -1, 10)}};
  cut_bonds<3>(sys, crack);
  for (Index i = 0; i < sys.n_real(); ++i)
    for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b) {
      const double xi = sys.particles.x0[i][0], xj = sys.particles.x0[sys.families.neighbor[b]][0];
      EXPECT_EQ(sys.bonds.broken(b), (xi < 3.5) != (xj < 3.5));
    }
}

}  // namespace
}  // namespace pdmpm::pd
