#include "solver/time/stable_step.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "solver/pd/pmb.hpp"
#include "verification/support/pd_fixtures.hpp"

namespace pdmpm::time {
namespace {

TEST(StableStep, OneDimensionalChainMatchesTheAnalyticLimit) {
  // Nearest-neighbour chain (δ = 1.5Δx, no partial volume): K has eigenvalues up
  // to 4 c V / (ρ Δx) (zone-boundary mode, interior), so Δt_crit = sqrt(ρ Δx / (c V)).
  test::BlockSpec spec;
  spec.sites = 400;
  spec.spacing = 1e-3;
  spec.setting = core::Setting::bar1d;
  spec.horizon_ratio = 1.5;
  spec.partial_volume = pd::PartialVolume::none;
  spec.measure = 1e-6;
  auto sys = test::make_block<1>(spec);
  pd::Pmb<1> m;
  m.initialise(sys);
  const double V = 1e-3 * 1e-6;
  const double exact = std::sqrt(sys.material.rho * 1e-3 / (m.micromodulus() * V));
  const auto res = lanczos_step<1>(sys, m, 2000, 1e-12);
  EXPECT_NEAR(res.dt / exact, 1.0, 1e-3);
  // Silling–Askari: sqrt(2ρ / (2 c V / Δx)) = exact: the bound is tight here.
  EXPECT_NEAR(silling_askari_step<1>(sys, m) / exact, 1.0, 1e-12);
  // The system is left as it was.
  for (const auto& u : sys.particles.u) EXPECT_EQ(u[0], 0.0);
}

TEST(StableStep, SillingAskariNeverExceedsThePowerIterationLimit) {
  for (int dim : {2, 3}) {
    test::BlockSpec spec;
    spec.sites = dim == 2 ? 20 : 9;
    if (dim == 2) {
      spec.setting = core::Setting::plane_strain;
      auto sys = test::make_block<2>(spec);
      pd::Pmb<2> m;
      m.initialise(sys);
      EXPECT_LE(silling_askari_step<2>(sys, m), lanczos_step<2>(sys, m).dt * (1 + 1e-9));
    } else {
      auto sys = test::make_block<3>(spec);
      pd::Pmb<3> m;
      m.initialise(sys);
      EXPECT_LE(silling_askari_step<3>(sys, m), lanczos_step<3>(sys, m).dt * (1 + 1e-9));
    }
  }
}

}  // namespace
}  // namespace pdmpm::time
