// hybrid::Simulation's region life cycle: the start (pre-crack faces PD), onset at an
// MPM ductile failure (the particle removed, a PD region around it), and what a
// removed particle is for both methods. Limits, momentum, conversions and thread
// invariance are gates (verification/gates/hybrid_gate.cpp).
#include "solver/hybrid/simulation.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "verification/support/hybrid_body.hpp"

namespace pdmpm::hybrid {
namespace {

using core::ParticleKind;

TEST(HybridSimulation, APreCrackStartsAsAPdRegionOfRadiusRpd) {
  Settings s;
  s.mode = Mode::expand;
  s.radii.pd_radius = 1.0;
  test::HybridPlate plate;
  plate.pd_tables = "[[precrack]]\nfrom = [0.010, 0.0075]\nto = [0.020, 0.0075]\n";
  test::HybridBody body(s, plate);
  body.hybrid->start();
  const auto& p = body.particles();
  const double reach = 3.015e-3 * (1.0 + 1e-9);
  for (Index i = 0; i < p.n_real; ++i) {
    // Reference distance to the cut segment y = 7.5 mm, 10 ≤ x ≤ 20 mm, measured from particle centres:
    // a particle with a cut bond lies within δ of the segment, so PD ones within 2δ.
    const Vec<2> x = p.x0[i];
    const double dx = std::max({0.010 - x[0], 0.0, x[0] - 0.020});
    const double d = std::hypot(dx, x[1] - 0.0075);
    if (p.kind[i] == ParticleKind::pd) {
      EXPECT_LT(d, 2.0 * reach) << i;
    }
    if (d < 0.5e-3) {
      EXPECT_EQ(p.kind[i], ParticleKind::pd) << "a particle next to the cut must be PD: " << i;
    }
  }
  const KindCounts c = body.hybrid->counts();
  EXPECT_GT(c.pd, 0);
  EXPECT_GT(c.transition, 0);
  EXPECT_EQ(c.pd + c.transition + c.mpm, p.n_real);
  EXPECT_EQ(static_cast<Index>(body.mpm->active().size()), c.transition + c.mpm);
}

TEST(HybridSimulation, DuctileFailureInMpmRemovesTheParticleAndFormsAPdRegion) {
  // ε_f = 0.0005 (c = 0): the plate pulled at 10 m/s yields and fails first at the grips.
  Settings s;
  s.mode = Mode::expand;
  s.radii.pd_radius = 1.0;
  const std::string pull =
      "[[boundary]]\nname = \"left\"\nkind = \"velocity\"\nregion = { type = \"box\", min = [-1, -1], max = [1.5e-3, "
      "1] }\n"
      "value = [\"-10\", \"free\"]\n"
      "[[boundary]]\nname = \"right\"\nkind = \"velocity\"\nregion = { type = \"box\", min = [28.5e-3, -1], max = [1, "
      "1] }\n"
      "value = [\"10\", \"free\"]\n";
  test::HybridPlate plate;
  plate.tables = pull;
  plate.material_keys = "failure = { d0 = 0.0005, c = 0.0 }";
  test::HybridBody body(s, plate);
  body.hybrid->start();
  const auto& p = body.particles();
  int steps = 0;
  while (body.hybrid->events().onsets == 0 && steps < 3000) {
    body.hybrid->step(2e-8);
    ++steps;
  }
  ASSERT_GT(body.hybrid->events().onsets, 0) << "no particle failed in " << steps << " steps";
  const KindCounts c = body.hybrid->counts();
  EXPECT_EQ(c.removed, body.hybrid->events().onsets);
  EXPECT_GT(c.pd, 0);
  EXPECT_EQ(body.hybrid->events().to_pd, c.pd);
  for (Index i = 0; i < p.n_real; ++i) {
    if (p.kind[i] != ParticleKind::removed) continue;
    EXPECT_TRUE(body.hybrid->removed()[i]);
    const auto& active = body.mpm->active();
    EXPECT_EQ(std::count(active.begin(), active.end(), i), 0) << "a removed particle is not mapped to the grid";
    const auto& sys = body.pd_setup.system;
    for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b)
      EXPECT_FALSE(sys.bonds.live(b)) << "no bond reaches a removed particle";
  }
  // The run goes on with the region in place.
  for (int n = 0; n < 50; ++n) body.hybrid->step(2e-8);
  for (Index i = 0; i < p.n_real; ++i) ASSERT_TRUE(p.u[i].allFinite() && p.v[i].allFinite()) << i;
}

}  // namespace
}  // namespace pdmpm::hybrid
