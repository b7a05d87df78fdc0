#pragma once
// STREAM-style triad a = b + s·c over arrays far larger than the caches: the
// memory bandwidth the roofline compares the bond kernels against, measured in
// the same process as the kernels.
#include <cstddef>
#include <vector>

namespace pdmpm::perf {

class Triad {
 public:
  explicit Triad(std::size_t elements = std::size_t{1} << 24);  // 3 × 128 MiB by default
  // Bytes per second of one pass with `threads` OpenMP threads, counted as STREAM
  // does: 24 bytes per element (the write-allocate read of `a` is not counted).
  double bytes_per_second(int threads);

 private:
  std::vector<double> a_, b_, c_;
};

}  // namespace pdmpm::perf
