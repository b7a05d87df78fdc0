#include "solver/bc/symmetry.hpp"

#include <gtest/gtest.h>

#include "solver/core/error.hpp"
#include "solver/core/particle_builder.hpp"

namespace pdmpm::bc {
namespace {

core::Particles<3> octant(int n) {
  core::Lattice<3> lat;
  core::Geometry<3> g;
  g.add(std::make_unique<core::Box<3>>(Vec<3>::Zero(), Vec<3>::Constant(n - 1)));
  return core::fill_lattice<3>(g, lat, 1.0);
}

TEST(Symmetry, OctantGhostsCompleteTheFamiliesNearThePlanes) {
  auto p = octant(8);
  const Index n = p.n_real;
  add_symmetry_ghosts<3>(p, {{"s0", 0, 0.0}, {"s1", 1, 0.0}, {"s2", 2, 0.0}}, 3.0, "t");
  EXPECT_GT(p.n_ghost(), 0);
  // Ghost sites are the mirrors of owners within reach; sites −3 … −1 on each mirrored axis.
  for (Index g = 0; g < p.n_ghost(); ++g) {
    const Index i = n + g, o = p.ghost_owner[g];
    ASSERT_LT(o, n);
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(p.site[i][a], p.ghost_sign[g][a] > 0 ? p.site[o][a] : -p.site[o][a]);
      EXPECT_GE(p.site[i][a], -3);
    }
  }
  // Corner ghosts (all three coordinates negative) exist: intersections are mirrored too.
  bool corner = false;
  for (Index i = n; i < p.size(); ++i) corner = corner || (p.site[i].array() < 0).all();
  EXPECT_TRUE(corner);
  // Ghost state follows the owner, reflected.
  p.u[5] = Vec<3>(1, 2, 3);
  p.update_ghosts();
  for (Index g = 0; g < p.n_ghost(); ++g)
    if (p.ghost_owner[g] == 5) {
      EXPECT_EQ(p.u[n + g], p.u[5].cwiseProduct(p.ghost_sign[g]));
    }
}

TEST(Symmetry, HalfSpacingPlaneIsAllowedAndOffLatticePlaneIsNot) {
  auto p = octant(4);
  EXPECT_NO_THROW(add_symmetry_ghosts<3>(p, {{"s", 0, -0.5}}, 2.0, "t"));
  auto q = octant(4);
  EXPECT_THROW(add_symmetry_ghosts<3>(q, {{"s", 0, -0.3}}, 2.0, "t"), InputError);
}

TEST(Symmetry, BodyOnBothSidesIsRejected) {
  auto p = octant(4);
  EXPECT_THROW(add_symmetry_ghosts<3>(p, {{"s", 0, 1.0}}, 2.0, "t"), InputError);
}

}  // namespace
}  // namespace pdmpm::bc
