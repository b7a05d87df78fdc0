// Simulation-level properties: bit-identical results for any thread count,
// symmetry planes equal to the mirrored full model, momentum conservation of a
// free body, and the errors a user gets for bodies the grid does not cover.
#include "solver/mpm/simulation.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "solver/core/error.hpp"
#include "verification/gates/mpm_gate_util.hpp"

namespace pdmpm::mpm {
namespace {

namespace mu = test::mpm_util;

// A 2D J2 plate, swirled and stretched so every kernel does real work.
std::vector<Vec<2>> run_plate(int threads, ShapeFunction shape, UpdateScheme scheme, bool nonlocal) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(threads);
  // 5000 particles: above kParallelMin, so the threaded paths really run.
  auto particles = mu::box_particles<2>(Vec<2>(0, 0), Vec<2>(0.1, 0.05), 1e-3, 2e-3);
  for (Index p = 0; p < particles.n_real; ++p) {
    const Vec<2> x = particles.x0[p];
    particles.v[p] = Vec<2>(30.0 * std::sin(60.0 * x[1]) + 200.0 * x[0], -20.0 * std::cos(80.0 * x[0]));
  }
  Settings<2> s;
  s.setting = core::Setting::plane_stress;
  s.shape = shape;
  s.scheme = scheme;
  s.material = {MaterialModel::j2, {200e9, 0.3, 7800}, {300e6, 2e9}};
  if (nonlocal) s.nonlocal = {true, 2e-3, 1.5};
  s.failure = {true, 0.05, -1.5, core::FailureRule::strain};
  GridBc<2> wall;
  wall.kind = BcKind::fixed;
  wall.max = Vec<2>(0.0, 1e9);
  s.boundaries.push_back(wall);
  Simulation<2> sim(s, particles);
  for (int n = 0; n < 30; ++n) sim.step();
  omp_set_num_threads(saved);
  std::vector<Vec<2>> out;
  for (Index p = 0; p < particles.n_real; ++p) {
    out.push_back(particles.u[p]);
    out.push_back(particles.v[p]);
    out.push_back(Vec<2>(sim.state().cauchy(p)(0, 0), sim.state().history(p).eq_plastic_strain));
  }
  return out;
}

TEST(MpmSimulation, BitIdenticalForAnyThreadCount) {
  struct Case {
    ShapeFunction shape;
    UpdateScheme scheme;
    bool nonlocal;
  };
  for (const Case c :
       {Case{ShapeFunction::linear, UpdateScheme::usf, false}, Case{ShapeFunction::gimp, UpdateScheme::musl, true},
        Case{ShapeFunction::bspline2, UpdateScheme::usl, false}}) {
    const auto a = run_plate(1, c.shape, c.scheme, c.nonlocal);
    const auto b = run_plate(2, c.shape, c.scheme, c.nonlocal);
    ASSERT_EQ(a.size(), b.size());
    bool plastic = false;
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i], b[i]) << name(c.shape) << " " << name(c.scheme) << " entry " << i;
      if (i % 3 == 2 && a[i][1] > 0.0) plastic = true;
    }
    EXPECT_TRUE(plastic) << "the test should exercise the plastic return";
  }
}

// A step that inverts particles (det F ≤ 0) stops the run with the same message —
// the lowest such particle — for any thread count (the 2D polar decompositions run
// eight particles at a time and hand inverted ones to the scalar code).
// The 2D scatter reads the stress in schedule order, a copy the stress update keeps:
// a stress set from outside between steps (set_deformation_gradient, as a conversion
// from PD does) must reach the grid at the next step, though the schedule stands.
// A 20 × 20 mm plane-stress J2 plate at rest (GIMP, MUSL) and its centre particle.
struct RestingPlate {
  core::Particles<2> particles = mu::box_particles<2>(Vec<2>(0, 0), Vec<2>(0.02, 0.02), 1e-3, 2e-3);
  Simulation<2> sim{settings(), particles};
  static Settings<2> settings() {
    Settings<2> s;
    s.setting = core::Setting::plane_stress;
    s.shape = ShapeFunction::gimp;
    s.scheme = UpdateScheme::musl;
    s.material = {MaterialModel::j2, {200e9, 0.3, 7800}, {300e6, 2e9}};
    return s;
  }
  Index centre() const {
    Index c = 0;
    for (Index p = 0; p < particles.n_real; ++p)
      if ((particles.x0[p] - Vec<2>(0.01, 0.01)).norm() < (particles.x0[c] - Vec<2>(0.01, 0.01)).norm()) c = p;
    return c;
  }
  double fastest() const {
    double v = 0.0;
    for (Index p = 0; p < particles.n_real; ++p) v = std::max(v, particles.v[p].norm());
    return v;
  }
};

TEST(MpmSimulation, AStressSetBetweenStepsReachesTheGrid) {
  RestingPlate plate;
  auto& sim = plate.sim;
  const double dt = 1e-8;
  sim.step(dt);  // at rest: no stress anywhere
  const Index centre = plate.centre();
  sim.set_deformation_gradient(centre, 1.001 * Mat<2>::Identity());  // a stretched point: 0.2 GPa
  ASSERT_GT(sim.state().kirchhoff.get(centre)(0, 0), 1e8);
  sim.step(dt);
  // Its force on the grid moves its neighbours: ~ V τ ∇S Δt / m ≈ 1e-2 m/s here.
  EXPECT_GT(plate.fastest(), 1e-4);
}

// A hybrid's blended coupling weights each particle's stress (set_stress_weight): a
// stretched point of weight ½ pushes its neighbours half as hard, stores half the energy,
// and weight 0 takes it out of the internal force.
TEST(MpmSimulation, StressWeightScalesAParticlesForceAndEnergy) {
  auto run = [](double weight, double& strain) {
    RestingPlate plate;
    const Index centre = plate.centre();
    std::vector<double> w(plate.particles.size(), 1.0);
    w[centre] = weight;
    plate.sim.set_stress_weight(w);
    plate.sim.set_deformation_gradient(centre, 1.0005 * Mat<2>::Identity());  // elastic: 0.14 GPa
    strain = plate.sim.energies().strain;
    plate.sim.step(1e-8);
    return plate.fastest();
  };
  double e1 = 0.0, e_half = 0.0, e0 = 0.0;
  const double full = run(1.0, e1), half = run(0.5, e_half), none = run(0.0, e0);
  EXPECT_GT(full, 1e-4);
  EXPECT_NEAR(half / full, 0.5, 1e-12);  // the velocities are linear in the one force
  EXPECT_EQ(none, 0.0);
  EXPECT_DOUBLE_EQ(e_half, 0.5 * e1);
  EXPECT_EQ(e0, 0.0);
}

TEST(MpmSimulation, InvertedParticleStopsTheRunNamingIt) {
  std::vector<std::string> messages;
  for (const int threads : {1, 2}) {
    const int saved = omp_get_max_threads();
    omp_set_num_threads(threads);
    auto particles = mu::box_particles<2>(Vec<2>(0, 0), Vec<2>(0.1, 0.05), 1e-3, 2e-3);
    // Squeezed along x at a rate k right of x = 0.07: the Cayley increment
    // (1 − k Δt/2)/(1 + k Δt/2) < 0 where k Δt > 2, so not at particle 0.
    for (Index p = 0; p < particles.n_real; ++p)
      particles.v[p] = Vec<2>(particles.x0[p][0] > 0.07 ? -1e5 * (particles.x0[p][0] - 0.07) : 0.0, 0.0);
    Settings<2> s;
    s.setting = core::Setting::plane_stress;
    s.material = {MaterialModel::j2, {200e9, 0.3, 7800}, {300e6, 2e9}};
    Simulation<2> sim(s, particles);
    try {
      sim.step(1e-4);
      ADD_FAILURE() << "no error on " << threads << " threads";
    } catch (const RunError& e) {
      messages.push_back(e.what());
      EXPECT_NE(messages.back().find("inverted"), std::string::npos) << e.what();
      EXPECT_EQ(messages.back().find("particle 0 "), std::string::npos) << e.what();
    }
    omp_set_num_threads(saved);
  }
  ASSERT_EQ(messages.size(), 2u);
  EXPECT_EQ(messages[0], messages[1]);
}

// Half bar [0, L] with a symmetry plane at 0 vs the full bar [−L, L] with an odd
// initial velocity: the half model's particles follow the full model's exactly.
TEST(MpmSimulation, SymmetryPlaneEqualsMirroredFullModel) {
  for (auto shape : {ShapeFunction::linear, ShapeFunction::gimp, ShapeFunction::bspline2}) {
    const double L = 1.0, dx = 1.0 / 32;
    auto half = mu::box_particles<2>(Vec<2>(0, 0), Vec<2>(L, 0.25), dx);
    auto full = mu::box_particles<2>(Vec<2>(-L, 0), Vec<2>(L, 0.25), dx);
    auto v0 = [](const Vec<2>& x) {  // normal component odd, tangential even: the mirror extension
      return Vec<2>(0.3 * std::sin(3.0 * x[0]) * (1 + x[1]), 0.2 * std::cos(2.0 * x[0]) * x[1]);
    };
    for (Index p = 0; p < half.n_real; ++p) half.v[p] = v0(half.x0[p]);
    for (Index p = 0; p < full.n_real; ++p) full.v[p] = v0(full.x0[p]);
    Settings<2> s;
    s.setting = core::Setting::plane_strain;
    s.shape = shape;
    s.material = {MaterialModel::neo_hookean, {1e4, 0.3, 1.0}};
    Settings<2> sh = s;
    GridBc<2> sym;
    sym.kind = BcKind::symmetry;
    sym.axis = 0;
    sym.position = 0.0;
    sym.side = +1;
    sh.boundaries.push_back(sym);
    Simulation<2> a(sh, half), b(s, full);
    for (int n = 0; n < 100; ++n) {
      const double dt = 0.3 * b.stable_dt();
      a.step(dt);
      b.step(dt);
    }
    double worst = 0.0, scale = 0.0;
    for (Index p = 0; p < half.n_real; ++p) {
      // The full-model particle at the same reference position.
      Index q = -1;
      for (Index k = 0; k < full.n_real; ++k)
        if ((full.x0[k] - half.x0[p]).norm() < 1e-12) q = k;
      ASSERT_GE(q, 0);
      worst = std::max(worst, (half.u[p] - full.u[q]).norm());
      scale = std::max(scale, full.u[q].norm());
    }
    // Round-off: the two models sum the same terms in different orders.
    EXPECT_LT(worst, 1e-12 * scale) << name(shape);
  }
}

TEST(MpmSimulation, FreeBodyConservesMomentum) {
  auto particles = mu::box_particles<3>(Vec<3>::Zero(), Vec<3>(0.4, 0.3, 0.2), 0.05);
  for (Index p = 0; p < particles.n_real; ++p)
    particles.v[p] = Vec<3>(1.0, -0.5, 0.25) + 3.0 * Vec<3>(std::sin(9 * particles.x0[p][1]), particles.x0[p][2], 0.0);
  Settings<3> s;
  s.setting = core::Setting::solid3d;
  s.material = {MaterialModel::j2, {1e7, 0.3, 1000}, {1e5, 1e6}};
  Simulation<3> sim(s, particles);
  const Vec<3> p0 = sim.momentum();
  for (int n = 0; n < 100; ++n) sim.step();
  EXPECT_LT((sim.momentum() - p0).norm(), 1e-12 * p0.norm());
  EXPECT_GT(sim.energies().dissipated, 0.0);
}

TEST(MpmSimulation, GridThatMissesTheBodyIsAnInputError) {
  auto particles = mu::box_particles<2>(Vec<2>(0, 0), Vec<2>(1, 1), 0.1);
  Settings<2> s;
  s.material = {MaterialModel::linear_elastic, {1e6, 0.3, 1000}};
  s.domain_min = Vec<2>(0.0, 0.0);
  s.domain_max = Vec<2>(0.5, 1.0);
  try {
    Simulation<2> sim(s, particles, "scene.toml", "mpm");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "mpm.grid.min");
  }
  s.domain_min.reset();
  s.domain_max.reset();
  s.dt = 1.0;  // far above h/c
  EXPECT_THROW(Simulation<2>(s, particles), InputError);
}

TEST(MpmSimulation, OnlyMpmAndTransitionParticlesMove) {
  auto particles = mu::box_particles<2>(Vec<2>(0, 0), Vec<2>(1, 1), 0.1);
  for (Index p = 0; p < particles.n_real; ++p) {
    particles.v[p] = Vec<2>(1.0, 0.0);
    if (p % 3 == 0) particles.kind[p] = core::ParticleKind::pd;
    if (p % 3 == 1) particles.kind[p] = core::ParticleKind::transition;
  }
  Settings<2> s;
  s.material = {MaterialModel::linear_elastic, {1e6, 0.3, 1000}};
  Simulation<2> sim(s, particles);
  for (int n = 0; n < 5; ++n) sim.step();
  for (Index p = 0; p < particles.n_real; ++p) {
    if (p % 3 == 0)
      EXPECT_EQ(particles.u[p].norm(), 0.0);
    else
      EXPECT_GT(particles.u[p].norm(), 0.0);
  }
}

}  // namespace
}  // namespace pdmpm::mpm

namespace pdmpm::mpm {
namespace {

// A 3D block stretched homogeneously (grid velocity v = L x on every node, nearly
// isochoric so the mean stress and η grow slowly): every particle carries the same
// stress. It must fail when the criterion of docs/models/mpm.md is met — ε̄_p ≥ d₀ exp(c η) ("strain"),
// or Σ Δε̄_p / ε_f(η) ≥ 1 ("accumulated") — evaluated here from the code's own ε̄_p
// and η outputs, and carry no stress afterwards.
TEST(MpmSimulation, DuctileFailureAtTheCriterionStrain) {
  const double d0 = 0.15, c = -1.5;
  for (core::FailureRule rule : {core::FailureRule::strain, core::FailureRule::accumulated}) {
    auto particles = mu::box_particles<3>(Vec<3>::Zero(), Vec<3>::Constant(4e-3), 1e-3);
    Settings<3> s;
    s.setting = core::Setting::solid3d;
    s.material = {MaterialModel::j2, {200e9, 0.3, 7800}, {300e6, 2e9}};
    s.failure = {true, d0, c, rule};
    const double rate = 100.0;  // 1/s along x; lateral −0.499 rate: small volumetric rate
    GridBc<3> drive;
    drive.kind = BcKind::velocity;
    drive.components.fill(true);
    drive.velocity_field = [&](const Vec<3>& x, double) {
      return Vec<3>(rate * x[0], -0.499 * rate * x[1], -0.499 * rate * x[2]);
    };
    s.boundaries.push_back(drive);
    s.padding_cells = 4;
    Simulation<3> sim(s, particles);
    const Index p = 0;
    double alpha = 0.0, eta = 0.0, damage = 0.0;
    int failed_at = -1;
    for (int n = 0; n < 2000; ++n) {
      sim.step(1e-5);  // Δε ≈ 1e-3 per step
      if (sim.failed(p)) {
        failed_at = n;
        break;
      }
      const double a = sim.eq_plastic_strain(p);
      eta = sim.triaxiality(p);
      damage += (a - alpha) / (d0 * std::exp(c * eta));
      alpha = a;
      // Not failed yet: the criterion must not be met.
      if (rule == core::FailureRule::strain)
        EXPECT_LT(alpha, d0 * std::exp(c * eta));
      else
        EXPECT_LT(damage, 1.0 + 1e-12);
    }
    ASSERT_GE(failed_at, 0) << name(rule);
    EXPECT_GT(eta, 0.05);  // the test exercises the exponent
    // It failed within one strain increment (≈ 1e-3, η changes by < 1e-3 per step).
    if (rule == core::FailureRule::strain)
      EXPECT_GT(alpha + 1.5e-3, d0 * std::exp(c * eta));
    else
      EXPECT_GT(damage + 1.5e-3 / (d0 * std::exp(c * eta)), 1.0);
    EXPECT_EQ(sim.state().cauchy(p).norm(), 0.0);
    // Every particle sees the same homogeneous state, so all fail in that step.
    for (Index q = 0; q < particles.n_real; ++q) EXPECT_TRUE(sim.failed(q));
    EXPECT_EQ(static_cast<Index>(sim.newly_failed().size()), particles.n_real);
  }
}

// The kinetic energy the grid sees after a step (MUSL's remap, null_space_watch.hpp): all
// of a uniform motion's, almost none of rows moving in antiphase with one particle per cell
// (each interior node sits midway between two rows and their momenta cancel there).
double grid_share_after_one_step(bool alternating) {
  auto particles = mu::box_particles<2>(Vec<2>(0, 0), Vec<2>(0.02, 0.02), 1e-3);
  for (Index p = 0; p < particles.n_real; ++p) {
    const auto row = static_cast<int>(std::floor(particles.x0[p][1] / 1e-3));
    particles.v[p] = alternating ? Vec<2>(0.0, row % 2 == 0 ? 1.0 : -1.0) : Vec<2>(3.0, -2.0);
  }
  Settings<2> s;
  s.setting = core::Setting::plane_stress;
  s.shape = ShapeFunction::gimp;
  s.scheme = UpdateScheme::musl;
  s.cell_factor = 1.0;  // particles at the cells' centres
  s.material = {MaterialModel::linear_elastic, {200e9, 0.3, 7800}, {}};
  Simulation<2> sim(s, particles);
  EXPECT_FALSE(sim.grid_kinetic_energy().has_value()) << "nothing remapped before the first step";
  sim.step(1e-12);
  return *sim.grid_kinetic_energy() / sim.energies().kinetic;
}

TEST(MpmSimulation, GridKineticEnergySeesUniformMotionNotAntiphaseRows) {
  EXPECT_NEAR(grid_share_after_one_step(false), 1.0, 1e-12);
  // The two edge rows' outer nodes have no partner row: 2 of 21 node rows keep a quarter of
  // a row's energy each, so a few per cent stays visible.
  EXPECT_LT(grid_share_after_one_step(true), 0.05);
}

TEST(MpmSimulation, GridKineticEnergyOnlyForMusl) {
  auto particles = mu::box_particles<2>(Vec<2>(0, 0), Vec<2>(0.01, 0.01), 1e-3);
  Settings<2> s;
  s.setting = core::Setting::plane_stress;
  s.scheme = UpdateScheme::usl;
  s.material = {MaterialModel::linear_elastic, {200e9, 0.3, 7800}, {}};
  Simulation<2> sim(s, particles);
  sim.step(1e-9);
  EXPECT_FALSE(sim.grid_kinetic_energy().has_value());
}

}  // namespace
}  // namespace pdmpm::mpm
