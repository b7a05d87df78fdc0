#include "solver/hybrid/blend_zone.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "solver/core/particle_builder.hpp"

namespace pdmpm::hybrid {
namespace {

using core::ParticleKind;

// A 2D body of 41 × 41 sites, Δx = 1 (lattice units), δ = 3.015Δx.
struct Plate {
  core::Particles<2> p;
  RegionMap<2> map;
  std::vector<ParticleKind> kind;
  std::vector<std::uint8_t> removed;
  Plate() : p(fill()), map(p, 3.015, 3.015, RegionRadii{}), kind(p.size(), ParticleKind::mpm), removed(p.n_real, 0) {}
  static core::Particles<2> fill() {
    core::Lattice<2> lat;
    lat.spacing = 1.0;
    lat.origin = Vec<2>::Zero();
    core::Geometry<2> g;
    g.add(std::make_unique<core::Box<2>>(Vec<2>(0.0, 0.0), Vec<2>(40.0, 40.0)));
    return core::fill_lattice<2>(g, lat, 1.0);
  }
};

TEST(BlendBand, WeightIsOneThenFallsLinearlyThenZero) {
  const BlendBand band{.reach = 3.0, .ramp = 6.0};
  EXPECT_EQ(band.zone(), 12.0);
  EXPECT_EQ(band.weight(0.0), 1.0);
  EXPECT_EQ(band.weight(3.0), 1.0);
  EXPECT_DOUBLE_EQ(band.weight(6.0), 0.5);
  EXPECT_EQ(band.weight(9.0), 0.0);
  EXPECT_EQ(band.weight(20.0), 0.0);
}

// Brute force against classify_blended: a disc of PD particles, every other particle's
// distance to the nearest PD one decides its kind and weight.
TEST(ClassifyBlended, KindsAndWeightsFollowTheDistanceToTheNearestPdParticle) {
  Plate b;
  const BlendBand band{.reach = 3.015, .ramp = 6.03};
  const Vec<2> centre(20.0, 20.0);
  for (Index i = 0; i < b.p.n_real; ++i)
    if ((b.p.x0[i] - centre).norm() <= 4.0) b.kind[i] = ParticleKind::pd;
  const Index gone = b.map.find(IVec<2>(20, 29));  // a removed particle keeps its kind byte out of the band
  ASSERT_GE(gone, 0);
  b.removed[static_cast<std::size_t>(gone)] = 1;
  b.kind[static_cast<std::size_t>(gone)] = ParticleKind::removed;
  std::vector<double> beta;
  classify_blended<2>(b.map, band, b.kind, b.removed, beta);
  Index transition = 0, checked = 0;
  for (Index i = 0; i < b.p.n_real; ++i) {
    if (b.removed[i]) {
      EXPECT_EQ(b.kind[i], ParticleKind::removed);
      continue;
    }
    double nearest = std::numeric_limits<double>::infinity();
    for (Index j = 0; j < b.p.n_real; ++j)
      if (b.kind[j] == ParticleKind::pd) nearest = std::min(nearest, (b.p.x0[i] - b.p.x0[j]).norm());
    if (b.kind[i] == ParticleKind::pd) {
      EXPECT_EQ(beta[i], 1.0);
      continue;
    }
    ++checked;
    const bool in_zone = nearest <= band.zone() * (1.0 + 1e-10);
    EXPECT_EQ(b.kind[i], in_zone ? ParticleKind::transition : ParticleKind::mpm) << "particle " << i;
    EXPECT_DOUBLE_EQ(beta[i], in_zone ? band.weight(nearest) : 0.0) << "particle " << i;
    transition += b.kind[i] == ParticleKind::transition;
  }
  EXPECT_GT(transition, 300) << "the band must hold a ring of particles";
  EXPECT_GT(checked - transition, 100) << "and the body must reach beyond it";
}

}  // namespace
}  // namespace pdmpm::hybrid
