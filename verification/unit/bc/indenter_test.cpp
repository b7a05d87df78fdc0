#include "solver/bc/indenter.hpp"

#include <gtest/gtest.h>

#include "solver/core/particle_builder.hpp"

namespace pdmpm::bc {
namespace {

TEST(Indenter, PushesOutwardWithQuadraticForceAndReportsReaction) {
  core::Lattice<3> lat;
  core::Geometry<3> g;
  g.add(std::make_unique<core::Box<3>>(Vec<3>::Zero(), Vec<3>(1, 0, 0)));
  auto p = core::fill_lattice<3>(g, lat, 0.5);
  Indenter<3> ind;
  ind.center0 = Vec<3>(0, 0, 0.5);
  ind.velocity = Vec<3>(0, 0, -1);
  ind.radius = 1.0;
  ind.stiffness = 2.0;
  const Vec<3> F = ind.add_forces(p, 0.0);
  // Particle at the origin: r = 0.5 → |F| = 2 (0.5)² = 0.5, pointing −z; b = F/V.
  const Index at0 = p.x0[0].norm() == 0 ? 0 : 1;
  EXPECT_NEAR(p.b[at0][2], -0.5 / 0.5, 1e-15);
  // Particle at (1,0,0): r = √1.25 > 1 → untouched.
  EXPECT_EQ(p.b[1 - at0], Vec<3>::Zero());
  EXPECT_NEAR(F[2], 0.5, 1e-15);  // reaction on the indenter
  EXPECT_EQ(ind.center(2.0), Vec<3>(0, 0, -1.5));
}

TEST(Indenter, ForceDensityLawActsPerUnitVolume) {
  // LAMMPS' fix indent on PERI atoms: k (R − r)² is a force density; the reaction is Σ b V.
  core::Lattice<3> lat;
  core::Geometry<3> g;
  g.add(std::make_unique<core::Box<3>>(Vec<3>::Zero(), Vec<3>::Zero()));
  auto p = core::fill_lattice<3>(g, lat, 0.5);
  Indenter<3> ind;
  ind.center0 = Vec<3>(0, 0, 0.5);
  ind.radius = 1.0;
  ind.stiffness = 2.0;
  ind.force_density = true;
  const Vec<3> F = ind.add_forces(p, 0.0);
  EXPECT_NEAR(p.b[0][2], -0.5, 1e-15);     // 2 (1 − 0.5)², along −z
  EXPECT_NEAR(F[2], 0.5 * 0.5, 1e-15);     // times V = 0.5
}

}  // namespace
}  // namespace pdmpm::bc
