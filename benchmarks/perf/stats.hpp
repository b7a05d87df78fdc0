#pragma once
// Medians and a bootstrap interval for a ratio of medians: the one form in which
// the performance driver reports timings (docs/design.md: both variants in one process,
// interleaved repetitions, ratio of medians with a confidence band).
#include <vector>

namespace pdmpm::perf {

double median(std::vector<double> v);

struct Ratio {
  double value = 0.0;         // median(num) / median(den)
  double lo = 0.0, hi = 0.0;  // 95 % percentile bootstrap interval
};

// Each sample is resampled with replacement `resamples` times (fixed seed, so the
// same timings give the same interval). With few repetitions the interval is
// coarse: it can only take values that ratios of the measured samples take.
Ratio ratio_of_medians(const std::vector<double>& num, const std::vector<double>& den, int resamples = 4000);

}  // namespace pdmpm::perf
