// Neighbour search: CSR families from the lattice site map, O(N · stencil).
#include <benchmark/benchmark.h>

#include "benchmarks/bench_bodies.hpp"

namespace pdmpm::bench {
namespace {

void families3(benchmark::State& state) {
  auto sys = lattice_body<3>(static_cast<int>(state.range(0)));
  const double ratio = sys.delta / sys.spacing();
  for (auto _ : state) {
    auto fam = core::Families<3>::build(sys.particles, ratio);
    benchmark::DoNotOptimize(fam.neighbor.data());
  }
  state.counters["bonds/s"] =
      benchmark::Counter(static_cast<double>(sys.families.n_bonds()), benchmark::Counter::kIsIterationInvariantRate);
}

BENCHMARK(families3)->Arg(20)->Arg(40)->Arg(64)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace pdmpm::bench
