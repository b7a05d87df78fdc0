#include "benchmarks/perf/stats.hpp"

#include <algorithm>
#include <random>

namespace pdmpm::perf {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

Ratio ratio_of_medians(const std::vector<double>& num, const std::vector<double>& den, int resamples) {
  Ratio r;
  r.value = median(num) / median(den);
  if (num.empty() || den.empty()) return r;
  std::mt19937_64 rng(20240601);
  auto resample = [&rng](const std::vector<double>& v) {
    std::uniform_int_distribution<std::size_t> pick(0, v.size() - 1);
    std::vector<double> out(v.size());
    for (double& x : out) x = v[pick(rng)];
    return median(std::move(out));
  };
  std::vector<double> ratios(static_cast<std::size_t>(resamples));
  for (double& x : ratios) x = resample(num) / resample(den);
  std::sort(ratios.begin(), ratios.end());
  const auto at = [&](double q) { return ratios[static_cast<std::size_t>(q * static_cast<double>(ratios.size() - 1) + 0.5)]; };
  r.lo = at(0.025);
  r.hi = at(0.975);
  return r;
}

}  // namespace pdmpm::perf
