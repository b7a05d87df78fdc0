#include "benchmarks/perf/triad.hpp"

#include <omp.h>

namespace pdmpm::perf {

Triad::Triad(std::size_t n) : a_(n), b_(n), c_(n) {
  // First touch in the same static schedule the passes use.
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) a_[i] = 0.0, b_[i] = 1.0, c_[i] = 2.0;
}

double Triad::bytes_per_second(int threads) {
  const std::size_t n = a_.size();
  double* a = a_.data();
  const double *b = b_.data(), *c = c_.data();
  const double s = 3.0;
  const double t0 = omp_get_wtime();
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::size_t i = 0; i < n; ++i) a[i] = b[i] + s * c[i];
  const double t = omp_get_wtime() - t0;
  // Keep the result observable so the pass is not optimised away.
  volatile double sink = a[n / 2];
  (void)sink;
  return 24.0 * static_cast<double>(n) / t;
}

}  // namespace pdmpm::perf
