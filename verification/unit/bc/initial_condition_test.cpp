#include "solver/bc/initial_condition.hpp"

#include <gtest/gtest.h>

#include "solver/core/particle_builder.hpp"

namespace pdmpm::bc {
namespace {

// Four particles at x = 0, 1, 2, 3 (y = 0), spacing 1.
core::Particles<2> row_of_four() {
  core::Lattice<2> lat;
  core::Geometry<2> g;
  g.add(std::make_unique<core::Box<2>>(Vec<2>::Zero(), Vec<2>(3, 0)));
  return core::fill_lattice<2>(g, lat, 1.0);
}

TEST(InitialConditions, ValuesLandOnTheirParticlesAndFreeComponentsStay) {
  auto p = row_of_four();
  ASSERT_EQ(p.n_real, 4);
  for (Index i = 0; i < p.n_real; ++i) p.u[i] = Vec<2>(7, 7), p.v[i] = Vec<2>(9, 9);
  InitialCondition<2> c;
  c.particles = {1, 2};
  c.velocity[0] = Expression::parse("10 * x");  // v_y "free"
  c.displacement[1] = Expression::parse("x^2 + y");
  apply_initial_conditions<2>({c}, p);
  // Selected: the given components at the reference position; the free ones untouched.
  EXPECT_EQ(p.v[1], Vec<2>(10, 9));
  EXPECT_EQ(p.v[2], Vec<2>(20, 9));
  EXPECT_EQ(p.u[1], Vec<2>(7, 1));
  EXPECT_EQ(p.u[2], Vec<2>(7, 4));
  // Not selected: untouched.
  EXPECT_EQ(p.v[0], Vec<2>(9, 9));
  EXPECT_EQ(p.u[3], Vec<2>(7, 7));
  EXPECT_EQ(p.x0[2], Vec<2>(2, 0));  // the reference position stays
}

TEST(InitialConditions, LaterConditionsOverwriteEarlierOnes) {
  auto p = row_of_four();
  InitialCondition<2> first, second;
  first.particles = {0, 1, 2, 3};
  first.velocity = {Expression(1.0), Expression(2.0)};
  second.particles = {2, 3};
  second.velocity[1] = Expression(-5.0);  // v_x free: keeps the first table's value
  apply_initial_conditions<2>({first, second}, p);
  EXPECT_EQ(p.v[1], Vec<2>(1, 2));
  EXPECT_EQ(p.v[2], Vec<2>(1, -5));
  EXPECT_EQ(p.v[3], Vec<2>(1, -5));
  // In the other order the first table wins everywhere.
  apply_initial_conditions<2>({second, first}, p);
  EXPECT_EQ(p.v[3], Vec<2>(1, 2));
}

TEST(InitialConditions, GradientsFromTheLastDisplacementOfEachComponent) {
  auto p = row_of_four();
  InitialCondition<2> shear, stretch;
  shear.particles = {0, 1, 2, 3};
  shear.displacement = {Expression::parse("0.3 * y"), Expression::parse("0.5 * x")};
  stretch.particles = {2};
  stretch.displacement[0] = Expression::parse("1e-3 * x^2");  // u_y stays the shear's
  const auto grads = initial_displacement_gradients<2>({shear, stretch}, p);
  ASSERT_EQ(grads.size(), 4u);
  // Central differences are exact for a linear field up to rounding of (u(X+h) − u(X−h)) / 2h,
  // h = 1e-4: |u| ≤ 1.5 gives ≤ 2·1.1e-16·1.5 / 2e-4 ≈ 2e-12.
  const double tol = 1e-11;
  const Mat<2> g0 = grads[0].second;
  EXPECT_EQ(grads[0].first, 0);
  EXPECT_NEAR(g0(0, 0), 0.0, tol);
  EXPECT_NEAR(g0(0, 1), 0.3, tol);
  EXPECT_NEAR(g0(1, 0), 0.5, tol);
  EXPECT_NEAR(g0(1, 1), 0.0, tol);
  // Particle 2 (x = 2): row x from the stretch, ∂(1e-3 x²)/∂x = 4e-3 (exact for a quadratic
  // up to the same rounding), row y from the shear.
  const Mat<2> g2 = grads[2].second;
  EXPECT_NEAR(g2(0, 0), 4e-3, tol);
  EXPECT_NEAR(g2(0, 1), 0.0, tol);
  EXPECT_NEAR(g2(1, 0), 0.5, tol);
}

TEST(InitialConditions, VelocityAloneHasNoGradient) {
  auto p = row_of_four();
  InitialCondition<2> c;
  c.particles = {0, 1};
  c.velocity = {Expression(1.0), Expression(0.0)};
  c.displacement[1] = std::nullopt;
  EXPECT_TRUE(initial_displacement_gradients<2>({c}, p).empty());
  c.displacement[1] = Expression::parse("2 * x");
  const auto grads = initial_displacement_gradients<2>({c}, p);
  ASSERT_EQ(grads.size(), 2u);  // only the particles the displacement reaches
  EXPECT_EQ(grads[1].first, 1);
  EXPECT_EQ(grads[1].second.row(0), Vec<2>::Zero().transpose());  // u_x set by nobody: zero row
  EXPECT_NEAR(grads[1].second(1, 0), 2.0, 1e-11);                 // as above: rounding of a linear field
}

}  // namespace
}  // namespace pdmpm::bc
