// Memory bandwidth of this machine, measured in the same run as the kernels
// (STREAM-style triad a = b + s·c over arrays far larger than the caches), for
// the roofline: bytes per bond × bonds/s against what the memory can deliver.
#include <benchmark/benchmark.h>

#include <vector>

namespace pdmpm::bench {
namespace {

void triad(benchmark::State& state) {
  const std::size_t n = std::size_t{1} << 24;  // 3 arrays × 128 MiB
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  const double s = 3.0;
  for (auto _ : state) {
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) a[i] = b[i] + s * c[i];
    benchmark::ClobberMemory();
  }
  // STREAM counts 3 × 8 bytes per element (write-allocate traffic not counted).
  state.counters["bytes/s"] =
      benchmark::Counter(24.0 * static_cast<double>(n), benchmark::Counter::kIsIterationInvariantRate);
}

BENCHMARK(triad)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(1.0);

}  // namespace
}  // namespace pdmpm::bench
