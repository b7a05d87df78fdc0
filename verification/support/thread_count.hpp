#pragma once
// OpenMP's thread count set for a scope and restored after it: a timing the report
// calls "one thread" runs on one thread whatever OMP_NUM_THREADS the tier sets (the
// full tier sets none, so OpenMP takes every core).
#include <omp.h>

namespace pdmpm::test {

class ThreadCount {
 public:
  explicit ThreadCount(int threads) { omp_set_num_threads(threads); }
  ~ThreadCount() { omp_set_num_threads(before_); }
  ThreadCount(const ThreadCount&) = delete;
  ThreadCount& operator=(const ThreadCount&) = delete;

 private:
  int before_ = omp_get_max_threads();
};

}  // namespace pdmpm::test
