// One full velocity-Verlet step (kicks, drift, boundary conditions, forces) of
// a free cube, as the run loop does it between outputs.
#include <benchmark/benchmark.h>

#include "solver/io/scene.hpp"
#include "solver/time/velocity_verlet.hpp"
#include "solver/sim/pd_setup.hpp"
#include "solver/time/stable_step.hpp"

namespace pdmpm::bench {
namespace {

void verlet_step(benchmark::State& state, const char* model) {
  const double n = static_cast<double>(state.range(0));
  const std::string text =
      "[scene]\nid = \"b\"\n[discretization]\ndimension = 3\nspacing = 1e-3\nhorizon_ratio = 3.015\n"
      "[[shape]]\ntype = \"box\"\nmin = [0, 0, 0]\nmax = [" +
      std::to_string((n - 1) * 1e-3) + ", " + std::to_string((n - 1) * 1e-3) + ", " + std::to_string((n - 1) * 1e-3) +
      "]\n[material]\ndensity = 7850\nyoungs_modulus = 200e9\npoissons_ratio = 0.25\n"
      "[model]\ntype = \"" +
      model + "\"\n[time]\nsteps = 1\n";
  const auto scene = io::parse_scene_text(text, "bench");
  auto setup = sim::build_pd<3>(scene);
  for (Index i = 0; i < setup.system.n_real(); ++i) setup.system.particles.v[i][0] = std::sin(i * 0.1);
  auto st = sim::make_simulation(setup);
  time::VelocityVerlet<3> stepper(st, 0.5 * time::silling_askari_step<3>(setup.system, *setup.model));
  stepper.start();
  for (auto _ : state) stepper.step(false);
  state.counters["particle_steps/s"] =
      benchmark::Counter(static_cast<double>(setup.system.n_real()), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["bonds/s"] = benchmark::Counter(static_cast<double>(setup.system.families.n_bonds()),
                                                 benchmark::Counter::kIsIterationInvariantRate);
}

void step_pmb3(benchmark::State& s) { verlet_step(s, "pmb"); }
void step_lps3(benchmark::State& s) { verlet_step(s, "lps"); }

BENCHMARK(step_pmb3)->Arg(40)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(step_lps3)->Arg(40)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace pdmpm::bench
