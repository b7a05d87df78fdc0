// Force kernels of PMB and LPS, 2D and 3D, with and without the damage rule.
// Counter `bonds/s` = bond sides evaluated per second (each bond is seen from
// both its ends, as in LAMMPS' PERI pair styles).
#include <benchmark/benchmark.h>

#include "benchmarks/bench_bodies.hpp"
#include "solver/pd/kernels/bond_kernels.hpp"
#include "solver/pd/lps_plastic.hpp"

namespace pdmpm::bench {
namespace {

template <int D>
void force_kernel(benchmark::State& state, const char* model_name) {
  auto sys = lattice_body<D>(static_cast<int>(state.range(0)));
  deform(sys);
  auto model = pd::make_model<D>(model_name);
  model->initialise(sys);
  pd::ForceRequest req;
  req.break_bonds = state.range(1) != 0;
  req.critical_stretch = 1.0;  // the rule is evaluated but never fires
  for (auto _ : state) {
    model->compute_forces(sys, req);
    benchmark::ClobberMemory();
  }
  const double bonds = static_cast<double>(sys.families.n_bonds());
  state.counters["particles"] = sys.n_real();
  state.counters["bonds/s"] = benchmark::Counter(bonds, benchmark::Counter::kIsIterationInvariantRate);
  state.SetLabel(std::string(model_name) + (req.break_bonds ? " damage" : "") + " simd=" + pd::kernels::simd_level());
}

// Elastoplastic LPS with every particle flowing (σ_y far below the stress of
// deform()): the return mapping runs on every bond; the evaluation starts from the
// same committed state each time (no accept), as the first trial of a step does.
void lps_plastic3(benchmark::State& state) {
  auto sys = lattice_body<3>(static_cast<int>(state.range(0)));
  deform(sys);
  sys.hardening = core::J2Hardening{1.0, 1e9};
  pd::LpsPlastic<3> model;
  model.initialise(sys);
  for (auto _ : state) {
    model.compute_forces(sys, {});
    benchmark::ClobberMemory();
  }
  state.counters["particles"] = sys.n_real();
  state.counters["bonds/s"] = benchmark::Counter(static_cast<double>(sys.families.n_bonds()),
                                                 benchmark::Counter::kIsIterationInvariantRate);
  state.SetLabel("lps_plastic (all flowing)");
}

void pmb3(benchmark::State& s) { force_kernel<3>(s, "pmb"); }
void lps3(benchmark::State& s) { force_kernel<3>(s, "lps"); }
void pmb2(benchmark::State& s) { force_kernel<2>(s, "pmb"); }
void lps2(benchmark::State& s) { force_kernel<2>(s, "lps"); }

BENCHMARK(pmb3)->ArgsProduct({{20, 40, 64}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(lps3)->ArgsProduct({{20, 40, 64}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(lps_plastic3)->Arg(20)->Arg(40)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(pmb2)->ArgsProduct({{100, 300, 700}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(lps2)->ArgsProduct({{100, 300, 700}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace pdmpm::bench
