#include "solver/bc/boundary.hpp"

#include <gtest/gtest.h>

#include "solver/core/particle_builder.hpp"

namespace pdmpm::bc {
namespace {

core::Particles<2> line_of(int n) {
  core::Lattice<2> lat;
  core::Geometry<2> g;
  g.add(std::make_unique<core::Box<2>>(Vec<2>::Zero(), Vec<2>(n - 1, 0)));
  return core::fill_lattice<2>(g, lat, 2.0);
}

TEST(Boundaries, DisplacementSetsUAndConsistentVelocity) {
  auto p = line_of(3);
  Boundaries<2> b;
  Constraint<2> c;
  c.kind = ConstraintKind::displacement;
  c.particles = {0};
  c.active = {true, false};
  c.value[0] = Expression::parse("2 * t");
  b.constraints.push_back(c);
  b.finalise(p.n_real);
  EXPECT_TRUE(b.constrained(0, 0));
  EXPECT_FALSE(b.constrained(0, 1));
  EXPECT_FALSE(b.constrained(1, 0));
  p.u[0][1] = 7.0;
  b.apply_displacement(p, 0.5, 0.1);
  EXPECT_DOUBLE_EQ(p.u[0][0], 1.0);
  EXPECT_DOUBLE_EQ(p.v[0][0], 2.0);
  EXPECT_DOUBLE_EQ(p.u[0][1], 7.0);  // free component untouched
}

TEST(Boundaries, FixedZeroesAndVelocityPrescribes) {
  auto p = line_of(3);
  Boundaries<2> b;
  Constraint<2> fixed;
  fixed.kind = ConstraintKind::fixed;
  fixed.particles = {1};
  fixed.active = {true, true};
  Constraint<2> vel;
  vel.kind = ConstraintKind::velocity;
  vel.particles = {2};
  vel.active = {false, true};
  vel.value[1] = Expression::parse("-3");
  b.constraints = {fixed, vel};
  b.finalise(p.n_real);
  p.u[1] = Vec<2>(1, 1);
  p.v[1] = Vec<2>(1, 1);
  b.apply_displacement(p, 1.0, 0.1);
  b.apply_velocity(p, 1.0);
  EXPECT_EQ(p.u[1], Vec<2>::Zero());
  EXPECT_EQ(p.v[1], Vec<2>::Zero());
  EXPECT_DOUBLE_EQ(p.v[2][1], -3.0);
}

TEST(Boundaries, TractionIsStressOverLayer) {
  auto p = line_of(2);
  Boundaries<2> b;
  Traction<2> t;
  t.particles = {0};
  t.value[0] = Expression::parse("20e6");
  t.value[1] = Expression::parse("0");
  t.layer = 0.5;
  b.tractions.push_back(t);
  b.finalise(p.n_real);
  b.add_tractions(p, 0.0);
  EXPECT_DOUBLE_EQ(p.b[0][0], 40e6);
  EXPECT_DOUBLE_EQ(p.b[1][0], 0.0);
}

}  // namespace
}  // namespace pdmpm::bc
