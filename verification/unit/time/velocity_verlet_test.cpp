#include "solver/time/velocity_verlet.hpp"
#include "solver/sim/pd_setup.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "solver/io/scene.hpp"
#include "solver/time/stable_step.hpp"
#include "verification/support/scene_text.hpp"

namespace pdmpm::time {
namespace {

// A free 30 mm × 15 mm steel plate (LPS, plane stress) with `tables` added.
io::Scene free_plate(const std::string& tables = "") {
  return test::SceneText{.id = "free", .tables = tables}.parse("free.toml");
}

// A free plate with a smooth initial velocity field: momentum stays at round-off
// and the total energy oscillates within a small bound (no drift).
TEST(Verlet, FreeVibrationConservesMomentumAndEnergy) {
  const auto scene = free_plate();
  auto setup = sim::build_pd<2>(scene);
  auto& p = setup.system.particles;
  for (Index i = 0; i < p.n_real; ++i) {
    const Vec<2> x = p.x0[i];
    p.v[i] = Vec<2>(std::sin(200 * x[1]), std::cos(150 * x[0])) * 0.1;
  }
  auto st = sim::make_simulation(setup);
  // Remove the initial momentum so "conserved" means "stays zero".
  const Vec<2> m0 = st.momentum() / (st.density() * p.n_real * p.volume[0]);
  for (Index i = 0; i < p.n_real; ++i) p.v[i] -= m0;
  const double dt = 0.8 * time::lanczos_step<2>(setup.system, *setup.model).dt;
  time::VelocityVerlet<2> stepper(st, dt);
  stepper.start();
  const double e0 = stepper.initial_energy();
  double emin = e0, emax = e0, pmax = 0.0;
  const double pscale = st.density() * p.n_real * p.volume[0] * 0.1;
  for (int k = 0; k < 2000; ++k) {
    stepper.step(true);
    const double e = st.kinetic_energy() + st.internal_energy();
    emin = std::min(emin, e);
    emax = std::max(emax, e);
    pmax = std::max(pmax, st.momentum().norm() / pscale);
  }
  EXPECT_LT(pmax, 1e-13);  // round-off of sums over 450 particles
  // Velocity Verlet conserves a shadow energy; the true energy oscillates with
  // amplitude O((ω Δt)²) — bounded, here below 2 % at 0.8 of the critical step.
  EXPECT_LT((emax - emin) / e0, 0.02);
}

TEST(Verlet, PrescribedVelocityWorkIsBooked) {
  const auto scene = free_plate(R"(
[[boundary]]
kind = "velocity"
value = ["0.5", "free"]
region = { type = "box", min = [0.0295, 0], max = [0.03, 0.015] }
[[boundary]]
kind = "fixed"
region = { type = "box", min = [0, 0], max = [0.0005, 0.015] }
)");
  auto setup = sim::build_pd<2>(scene);
  auto st = sim::make_simulation(setup);
  const double dt = 0.8 * time::silling_askari_step<2>(setup.system, *setup.model);
  time::VelocityVerlet<2> stepper(st, dt);
  stepper.start();
  for (int k = 0; k < 400; ++k) stepper.step(k == 399);
  const double e = st.kinetic_energy() + st.internal_energy();
  // Energy in the body = work done by the supports, to the accuracy of the
  // booking (first order in Δt at the held particles): within 1 %.
  EXPECT_GT(stepper.external_work(), 0.0);
  EXPECT_NEAR(e / stepper.external_work(), 1.0, 0.01);
}

}  // namespace
}  // namespace pdmpm::time
