#include "solver/pd/pmb.hpp"

#include <gtest/gtest.h>

#include "solver/pd/constants.hpp"
#include "verification/support/pd_fixtures.hpp"

namespace pdmpm::pd {
namespace {

TEST(Pmb, TwoParticleBondForceAndEnergy) {
  // Two particles 1 mm apart in 1D, stretched by 1e-6 m: f = c ω β s V_j, W = ¼ c ω β s² L V_j.
  test::BlockSpec spec;
  spec.sites = 2;
  spec.spacing = 1e-3;
  spec.setting = core::Setting::bar1d;
  spec.horizon_ratio = 1.5;
  spec.partial_volume = PartialVolume::none;
  spec.measure = 1e-6;
  auto sys = test::make_block<1>(spec);
  Pmb<1> m;
  m.initialise(sys);
  const Index right = sys.particles.x0[0][0] > sys.particles.x0[1][0] ? 0 : 1;
  sys.particles.u[right][0] = 1e-6;
  std::vector<double> W(2);
  ForceRequest req;
  req.energy = &W;
  m.compute_forces(sys, req);
  const double c = m.micromodulus(), s = 1e-3, V = 1e-3 * 1e-6;
  EXPECT_NEAR(sys.particles.f[1 - right][0], c * s * V, 1e-12 * c * s * V);
  EXPECT_NEAR(sys.particles.f[right][0], -c * s * V, 1e-12 * c * s * V);
  EXPECT_NEAR(W[0], 0.25 * c * s * s * 1e-3 * V, 1e-12 * W[0]);
}

TEST(Pmb, BondsBreakOnBothSidesAtTheSameStep) {
  test::BlockSpec spec;
  spec.sites = 6;
  spec.setting = core::Setting::plane_strain;
  spec.measure = 1e-3;
  auto sys = test::make_block<2>(spec);
  Pmb<2> m;
  m.initialise(sys);
  for (Index i = 0; i < sys.n_real(); ++i) sys.particles.u[i] = Vec<2>(0.0, 0.02 * sys.particles.x0[i][1] * sys.particles.x0[i][0] / 1e-3);
  ForceRequest req;
  req.break_bonds = true;
  req.critical_stretch = 0.01;
  const auto broke = m.compute_forces(sys, req);
  EXPECT_GT(broke, 0);
  EXPECT_EQ(broke % 2, 0);
  for (Index i = 0; i < sys.n_real(); ++i)
    for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b) {
      const Index j = sys.families.neighbor[b];
      for (BondIndex c = sys.families.begin(j); c < sys.families.end(j); ++c)
        if (sys.families.neighbor[c] == i) {
          EXPECT_EQ(sys.bonds.broken(b), sys.bonds.broken(c));
        }
    }
}

TEST(Pmb, PoissonRatioIsFixedByTheSetting) {
  Pmb<3> m;
  const auto& info = model_info(m.name());
  EXPECT_EQ(info.poisson_range(core::Setting::solid3d), std::make_pair(0.25, 0.25));
  EXPECT_EQ(info.poisson_range(core::Setting::plane_strain), std::make_pair(0.25, 0.25));
  EXPECT_EQ(info.poisson_range(core::Setting::plane_stress), std::make_pair(1.0 / 3.0, 1.0 / 3.0));
}

}  // namespace
}  // namespace pdmpm::pd
