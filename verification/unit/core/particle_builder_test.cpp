#include "solver/core/particle_builder.hpp"

#include <gtest/gtest.h>

#include <set>

namespace pdmpm::core {
namespace {

TEST(ParticleBuilder, CellCentredRectangleHasNTimesMSites) {
  Lattice<2> lat;
  lat.spacing = 0.4e-3;
  lat.origin = Vec<2>(0.2e-3, 0.2e-3);
  Geometry<2> g;
  g.add(std::make_unique<Box<2>>(Vec<2>(0, 0), Vec<2>(0.08, 0.04)));
  const auto p = fill_lattice<2>(g, lat, 1.0);
  EXPECT_EQ(p.n_real, 200 * 100);
}

TEST(ParticleBuilder, BoundarySitesIncludedAndHolesRemoved) {
  // Octant of the spherical wave: sites 0 … 40 cm in 0.5 cm steps, minus the
  // 27 sites with max(|x|,|y|,|z|) ≤ 1 cm.
  Lattice<3> lat;
  lat.spacing = 0.005;
  Geometry<3> g;
  g.add(std::make_unique<Box<3>>(Vec<3>::Zero(), Vec<3>::Constant(0.4)));
  g.subtract(std::make_unique<Box<3>>(Vec<3>::Constant(-0.01), Vec<3>::Constant(0.01)));
  const auto p = fill_lattice<3>(g, lat, 1.0);
  EXPECT_EQ(p.n_real, 81 * 81 * 81 - 27);
}

TEST(ParticleBuilder, MortonOrderKeepsNeighboursClose) {
  Lattice<3> lat;
  Geometry<3> g;
  g.add(std::make_unique<Box<3>>(Vec<3>::Zero(), Vec<3>::Constant(15)));
  const auto p = fill_lattice<3>(g, lat, 1.0);
  // The first 8 particles form a 2×2×2 block.
  std::set<int> xs, ys, zs;
  for (int i = 0; i < 8; ++i) xs.insert(p.site[i][0]), ys.insert(p.site[i][1]), zs.insert(p.site[i][2]);
  EXPECT_EQ(xs.size(), 2u);
  EXPECT_EQ(ys.size(), 2u);
  EXPECT_EQ(zs.size(), 2u);
}

TEST(ParticleBuilder, EmptyGeometryGivesNoParticles) {
  Lattice<2> lat;
  Geometry<2> g;
  EXPECT_EQ(fill_lattice<2>(g, lat, 1.0).n_real, 0);
}

}  // namespace
}  // namespace pdmpm::core
