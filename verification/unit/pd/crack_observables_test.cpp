#include "solver/pd/crack_observables.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "solver/pd/damage.hpp"
#include "solver/pd/precrack.hpp"
#include "verification/support/pd_fixtures.hpp"

namespace pdmpm::pd {
namespace {

System<2> square(int sites = 20) {
  test::BlockSpec spec;
  spec.sites = sites;
  spec.spacing = 1.0;
  spec.setting = core::Setting::plane_strain;
  return test::make_block<2>(spec);
}

Index at(const System<2>& sys, double x, double y) {
  for (Index i = 0; i < sys.n_real(); ++i)
    if (std::abs(sys.particles.x0[i][0] - x) < 1e-9 && std::abs(sys.particles.x0[i][1] - y) < 1e-9) return i;
  ADD_FAILURE() << "no particle at " << x << ", " << y;
  return 0;
}

// Breaks every bond of particle i (both sides), so φ_i = 1.
void detach(System<2>& sys, Index i) {
  const auto& fam = sys.families;
  for (BondIndex b = fam.begin(i); b < fam.end(i); ++b) {
    sys.bonds.cut(b);
    const Index j = fam.neighbor[b];
    for (BondIndex c = fam.begin(j); c < fam.end(j); ++c)
      if (fam.neighbor[c] == i) sys.bonds.cut(c);
  }
}

TEST(RayleighSpeed, PoissonSolidClosedForm) {
  // ν = 1/4 (λ = G): ξ² = 2 − 2/√3 (Rayleigh 1885), c_R = ξ c_s.
  const core::Elastic m{200e9, 0.25, 7850.0};
  const double cs = std::sqrt(m.shear() / m.rho);
  EXPECT_NEAR(rayleigh_speed(m, core::Setting::solid3d) / cs, std::sqrt(2.0 - 2.0 / std::sqrt(3.0)), 1e-12);
  // Plane strain has the 3D wave speeds; plane stress a slower c_p, hence a slower c_R.
  EXPECT_DOUBLE_EQ(rayleigh_speed(m, core::Setting::plane_strain), rayleigh_speed(m, core::Setting::solid3d));
  EXPECT_LT(rayleigh_speed(m, core::Setting::plane_stress), rayleigh_speed(m, core::Setting::plane_strain));
}

TEST(CrackObservables, CutThroughTheBodySeparatesItIntoTwoPieces) {
  auto sys = square();
  CrackObservables<2> obs(sys, {}, {}, {});
  obs.sample(sys, local_damage(sys), 0.0);
  EXPECT_EQ(obs.components(), 1);
  EXPECT_EQ(obs.pieces(), 1);
  cut_bonds<2>(sys, CrackSurface<2>{{Vec<2>(9.5, -1), Vec<2>(9.5, 30)}});
  obs.sample(sys, local_damage(sys), 1.0);
  EXPECT_EQ(obs.components(), 2);
  EXPECT_EQ(obs.pieces(), 2);
  ASSERT_TRUE(obs.separation_time());
  EXPECT_EQ(*obs.separation_time(), 1.0);
  // A clean straight cut leaves every particle below φ = ½: no cracked particle.
  EXPECT_EQ(obs.cracked(), 0);
}

TEST(CrackObservables, PreCutBondsAreTheNotchNotACrack) {
  auto sys = square();
  cut_bonds<2>(sys, CrackSurface<2>{{Vec<2>(-1, 9.5), Vec<2>(8, 9.5)}});
  CrackObservables<2> obs(sys, {}, {}, {});
  obs.sample(sys, local_damage(sys), 0.0);
  const Index near_notch = at(sys, 5, 10);
  EXPECT_TRUE(obs.excluded()[near_notch]);
  detach(sys, near_notch);
  obs.sample(sys, local_damage(sys), 1.0);
  EXPECT_FALSE(obs.initiation_time()) << "damage inside the notch is not a crack";
  EXPECT_EQ(obs.initial_pieces(), 1);
}

TEST(CrackObservables, CrackTipPathAngleAndSpeed) {
  auto sys = square(30);
  CrackSettings s;
  s.speed_window = 3.0;  // three sample intervals
  std::vector<NamedLocation<2>> locations(1);
  locations[0].name = "far";
  locations[0].point = Vec<2>(25, 15);
  locations[0].radius = 1.5;
  for (Index i = 0; i < sys.n_real(); ++i)
    if ((sys.particles.x0[i] - locations[0].point).norm() <= 1.5) locations[0].particles.push_back(i);
  CrackObservables<2> obs(sys, s, locations, {});
  obs.sample(sys, local_damage(sys), 0.0);
  // A crack running along +x from (5, 15), one site per unit of time.
  for (int k = 0; k <= 10; ++k) {
    detach(sys, at(sys, 5.0 + k, 15.0));
    obs.sample(sys, local_damage(sys), 1.0 + k);
  }
  ASSERT_TRUE(obs.initiation_time());
  EXPECT_EQ(*obs.initiation_time(), 1.0);
  const auto* lead = obs.leading();
  ASSERT_NE(lead, nullptr);
  EXPECT_EQ(obs.paths().size(), 1u) << "one crack: its particles are family members";
  // Detaching a particle also cracks no neighbour (φ of a neighbour stays below ½), so
  // the crack's members are exactly the detached particles.
  EXPECT_EQ(lead->members, 11u);
  EXPECT_NEAR(lead->origin[0], 5.0, 1e-12);
  EXPECT_NEAR(lead->tip.back()[0], 15.0, 1e-12);
  EXPECT_NEAR(lead->extent.back(), 10.0, 1e-12);
  EXPECT_NEAR(lead->angle_deg(), 0.0, 1e-12);
  // Exactly linear growth: the least-squares slope is the rate, 1 site per unit time.
  EXPECT_NEAR(lead->speed.back(), 1.0, 1e-12);
  EXPECT_TRUE(std::isnan(lead->speed.front())) << "no speed before the crack is one window old";
  EXPECT_NEAR(obs.overall_angle_deg(), 0.0, 1e-9);
  // The named location at (25, 15) is out of the crack's reach: no failure there.
  EXPECT_FALSE(obs.first_failure(0));
  detach(sys, at(sys, 25, 15));
  obs.sample(sys, local_damage(sys), 20.0);
  ASSERT_TRUE(obs.first_failure(0));
  EXPECT_EQ(*obs.first_failure(0), 20.0);
  EXPECT_EQ(obs.paths().size(), 2u) << "a second, separate crack";
}

TEST(CrackObservables, ExcludedRegionsHoldNoCrack) {
  auto sys = square();
  std::vector<std::uint8_t> exclude(static_cast<std::size_t>(sys.n_real()), 0);
  const Index i = at(sys, 10, 10);
  exclude[i] = 1;
  CrackObservables<2> obs(sys, {}, {}, exclude);
  obs.sample(sys, local_damage(sys), 0.0);
  detach(sys, i);
  obs.sample(sys, local_damage(sys), 1.0);
  EXPECT_FALSE(obs.initiation_time());
  EXPECT_EQ(obs.components(), 2) << "the detached particle is a fragment all the same";
}

}  // namespace
}  // namespace pdmpm::pd
