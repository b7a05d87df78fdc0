// The hybrid's step in its limits (no PD particle: the MPM run; mode pd: the PD
// run, both bitwise), momentum across the PD | transition | MPM interface, and the
// state a yielded particle keeps across a conversion MPM → PD → MPM.
#include "solver/hybrid/simulation.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "solver/hybrid/conversion.hpp"
#include "solver/sim/mpm_setup.hpp"
#include "solver/time/velocity_verlet.hpp"
#include "verification/support/hybrid_body.hpp"

namespace pdmpm::hybrid {
namespace {

using core::ParticleKind;

// A smooth velocity field, large enough to yield within a few hundred steps.
void kick_field(core::Particles<2>& p) {
  for (Index i = 0; i < p.n_real; ++i) {
    const Vec<2> x = p.x0[i];
    p.v[i] = Vec<2>(20.0 * std::sin(300 * x[1]) + 5.0, 15.0 * std::cos(250 * x[0]));
  }
}

using Body = test::HybridBody;
io::Scene plate(const std::string& method, const std::string& pd_tables = "") {
  return test::HybridPlate{.pd_tables = pd_tables}.scene(method);
}

constexpr double kDt = 2e-8;  // below both stable steps (PD ≈ 6e-8 s, grid ≈ 1.6e-7 s at Δx = 1 mm)

TEST(HybridSimulation, WithNoPdParticleItIsThePureMpmRunBitwise) {
  auto mpm_setup = sim::build_mpm<2>(plate("mpm"));
  kick_field(mpm_setup.particles);
  mpm::Simulation<2> alone(mpm_setup.settings, mpm_setup.particles);

  Body body{Settings{}};
  kick_field(body.particles());
  body.hybrid->start();
  ASSERT_EQ(body.hybrid->counts().mpm, body.particles().n_real);
  for (int s = 0; s < 100; ++s) {
    alone.step(kDt);
    body.hybrid->step(kDt);
  }
  EXPECT_EQ(body.hybrid->events().to_pd, 0);
  double eq = 0.0;
  for (Index i = 0; i < body.particles().n_real; ++i) {
    ASSERT_EQ(body.particles().u[i], mpm_setup.particles.u[i]) << i;
    ASSERT_EQ(body.particles().v[i], mpm_setup.particles.v[i]) << i;
    eq = std::max(eq, body.mpm->eq_plastic_strain(i));
  }
  EXPECT_GT(eq, 0.0) << "the run must yield, or J2 is not exercised";
}

TEST(HybridSimulation, ModePdIsThePurePdRunBitwise) {
  // A pre-crack and a critical stretch, so bond breaking is part of the comparison.
  const std::string tables = "[[precrack]]\nfrom = [0.0, 0.0075]\nto = [0.01, 0.0075]\n";
  auto pd_alone = sim::build_pd<2>(plate("pd", tables));
  kick_field(pd_alone.system.particles);
  auto alone = sim::make_simulation(pd_alone);
  time::VelocityVerlet<2> verlet(alone, kDt);
  verlet.start();

  Settings settings;
  settings.mode = Mode::pd;
  Body body{settings, {.pd_tables = tables}};
  kick_field(body.particles());
  body.hybrid->start();
  ASSERT_EQ(body.hybrid->counts().pd, body.particles().n_real);
  for (int s = 0; s < 100; ++s) {
    verlet.step(s % 10 == 0);
    body.hybrid->step(kDt, s % 10 == 0);
  }
  const auto& p = pd_alone.system.particles;
  for (Index i = 0; i < p.n_real; ++i) {
    ASSERT_EQ(body.particles().u[i], p.u[i]) << i;
    ASSERT_EQ(body.particles().v[i], p.v[i]) << i;
  }
  EXPECT_EQ(body.hybrid->internal_energy(), alone.internal_energy());
  EXPECT_EQ(body.hybrid->mpm().active().size(), 0u);
}

TEST(HybridSimulation, CouplingAcrossTheInterfaceConservesMomentum) {
  // The pre-crack's faces start PD with a region of R_pd = 1.5δ around them; the
  // rest is transition and MPM. Free body, no load: every force is a pair force or a
  // grid force, so P + ½Δt Σ V f_transition is constant.
  Settings settings;
  settings.mode = Mode::expand;
  settings.radii.pd_radius = 1.5;
  settings.radii.expand_trigger = 0.5;
  settings.radii.expand_radius = 1.0;
  Body body{settings, {.pd_tables = "[[precrack]]\nfrom = [0.012, 0.0075]\nto = [0.018, 0.0075]\n"}};
  kick_field(body.particles());
  body.hybrid->start();
  const KindCounts c = body.hybrid->counts();
  ASSERT_GT(c.pd, 0);
  ASSERT_GT(c.transition, 0);
  ASSERT_GT(c.mpm, 0);
  const Vec<2> p0 = body.hybrid->momentum();
  // Scale: Σ m|v| (a momentum any round-off is relative to).
  double scale = 0.0;
  for (Index i = 0; i < body.particles().n_real; ++i)
    scale += 7850.0 * body.particles().volume[i] * body.particles().v[i].norm();
  double worst = 0.0;
  for (int s = 0; s < 200; ++s) {
    body.hybrid->step(kDt);
    worst = std::max(worst, (body.hybrid->momentum() - p0).norm() / scale);
  }
  // Round-off of ~10⁴ particle sums per step over 200 steps: 1e-12 leaves two decades.
  EXPECT_LT(worst, 1e-12) << "momentum drift relative to Σ m|v|";
  // The coupling must have acted: PD particles next to the interface moved differently
  // from a free PD body (no pair force with the transition particles would leave the
  // region's momentum constant by itself).
  Vec<2> pd_part = Vec<2>::Zero();
  for (const Index i : body.pd->movers()) pd_part += 7850.0 * body.particles().volume[i] * body.particles().v[i];
  EXPECT_GT(body.hybrid->events().to_pd + c.pd, 0);
  std::cout << "momentum drift " << worst << ", PD part momentum " << pd_part.transpose() << "\n";
}

TEST(HybridConversion, AYieldedBlockKeepsItsStressAndPlasticStrainMpmToPdToMpm) {
  // A homogeneous stretch beyond yield in MPM, every particle converted to PD and back:
  // the interior particles' stress and plastic strain return (within 1 % of the stress,
  // the gate; the PD return map is exact only to first order in the strain, and
  // F is rebuilt from bond vectors).
  Body body{Settings{}};
  auto& p = body.particles();
  body.hybrid->start();
  Mat<2> F;
  F << 1.003, 0.001, 0.0005, 0.999;
  for (Index i = 0; i < p.n_real; ++i) {
    p.u[i] = (F - Mat<2>::Identity()) * p.x0[i];
    body.mpm->set_deformation_gradient(i, F);
  }
  const Index probe = [&] {  // an interior particle, far from every face
    for (Index i = 0; i < p.n_real; ++i)
      if ((p.x0[i] - Vec<2>(0.015, 0.0075)).norm() < 0.6e-3) return i;
    return Index{-1};
  }();
  ASSERT_GE(probe, 0);
  const Mat<3> stress0 = body.mpm->state().stress[probe];
  const mpm::PointHistory h0 = body.mpm->state().history[probe];
  ASSERT_GT(h0.eq_plastic_strain, 1e-3) << "the block must have yielded";

  for (Index i = 0; i < p.n_real; ++i) p.kind[i] = ParticleKind::pd;
  for (Index i = 0; i < p.n_real; ++i) to_pd<2>(*body.mpm, body.pd_setup.system, body.pd->model(), i);
  body.pd->refresh_kinds();
  body.pd->internal_forces(false);
  body.pd->accept();
  for (Index i = 0; i < p.n_real; ++i) to_mpm<2>(body.pd_setup.system, body.pd->model(), *body.mpm, i);

  const Mat<3> stress1 = body.mpm->state().stress[probe];
  const mpm::PointHistory h1 = body.mpm->state().history[probe];
  const double stress_change = (stress1 - stress0).norm() / stress0.norm();
  EXPECT_LT(stress_change, 0.01);
  // The plastic strain may move by what the 1 % stress budget moves it on the hardening
  // line, 0.01 σ_eq/(3G + H): the PD evaluation in between flows a little further, since
  // its small-strain bond extensions and MPM's log strain differ at O(|F − I|).
  const double G = 200e9 / 2.6, H = 200e9 * 2e9 / (200e9 - 2e9);
  const double budget = 0.01 * body.mpm->von_mises(probe) / (3.0 * G + H);
  const double eq_change = std::abs(h1.eq_plastic_strain - h0.eq_plastic_strain);
  EXPECT_LT(eq_change, budget);
  EXPECT_LT((h1.plastic_strain - h0.plastic_strain).norm(), std::sqrt(1.5) * budget);
  std::cout << "conversion round trip: stress " << stress_change << " relative, ε̄_p " << eq_change << " (budget "
            << budget << ", ε̄_p = " << h0.eq_plastic_strain << ")\n";
  const auto Fpd = bond_deformation_gradient<2>(body.pd_setup.system, probe);
  ASSERT_TRUE(Fpd.has_value());
  EXPECT_LT((*Fpd - F).norm(), 1e-12);
}

}  // namespace
}  // namespace pdmpm::hybrid
