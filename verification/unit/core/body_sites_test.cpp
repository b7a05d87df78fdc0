#include "solver/core/body_sites.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

#include "solver/core/particle_builder.hpp"

namespace pdmpm::core {
namespace {

Geometry<3> holed_block() {
  Geometry<3> g;
  g.add(std::make_unique<Box<3>>(Vec<3>(0.0, 0.0, 0.0), Vec<3>(0.013, 0.007, 0.005)));
  g.subtract(std::make_unique<Ball<3>>(Vec<3>(0.006, 0.003, 0.002), 0.002));
  return g;
}

// Keys sorted and unique; every site decodes to a site the geometry holds, and finds its
// own index; sites off the body find nothing. A distributed process relies on all of it.
TEST(BodySites, KeysDecodeToTheirSitesAndFindTheirIndex) {
  Lattice<3> lat;
  lat.spacing = 1e-3;
  lat.origin = Vec<3>(5e-4, 5e-4, 5e-4);
  const auto body = body_sites<3>(holed_block(), lat, 1e-9);
  ASSERT_GT(body.size(), 300);
  EXPECT_TRUE(std::adjacent_find(body.keys.begin(), body.keys.end(), std::greater_equal<>()) == body.keys.end());
  for (Index g = 0; g < body.size(); ++g) ASSERT_EQ(body.find(body.site(g)), g);
  EXPECT_EQ(body.find(IVec<3>(6, 3, 2)), -1);   // in the hole
  EXPECT_EQ(body.find(IVec<3>(-1, 0, 0)), -1);  // below the key origin
  EXPECT_EQ(body.find(IVec<3>(40, 0, 0)), -1);  // beyond the box
}

// The particles a range makes are the whole body's (fill_lattice) at those indices, the
// remote ghosts after them.
TEST(BodySites, RangesAreTheWholeBodysParticles) {
  Lattice<3> lat;
  lat.spacing = 1e-3;
  const auto body = body_sites<3>(holed_block(), lat, 1e-9);
  const auto whole = fill_lattice<3>(holed_block(), lat, 1e-9);
  ASSERT_EQ(whole.n_real, body.size());
  const auto part = body.particles(100, 200, {3, 250});
  ASSERT_EQ(part.n_real, 100);
  ASSERT_EQ(part.n_ghost(), 2);
  for (Index i = 0; i < 100; ++i) EXPECT_EQ(part.x0[i], whole.x0[100 + i]);
  EXPECT_EQ(part.x0[100], whole.x0[3]);
  EXPECT_EQ(part.x0[101], whole.x0[250]);
  EXPECT_EQ(part.ghost_owner[0], Particles<3>::kRemoteOwner);
}

}  // namespace
}  // namespace pdmpm::core
