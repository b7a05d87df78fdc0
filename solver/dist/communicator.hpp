#pragma once
// The processes of a distributed run (MPI), with the few collective operations the
// solver needs. A run started without mpirun is one process: size() = 1.
#include <mpi.h>

#include <cstdint>
#include <exception>
#include <functional>
#include <vector>

namespace pdmpm::dist {

// Initialises MPI for the lifetime of main() (and finalises it); the first thing a
// program that may run under mpirun creates. OpenMP threads never call MPI, so
// MPI_THREAD_FUNNELED is enough.
class MpiSession {
 public:
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
};

class Communicator {
 public:
  // Every process of the run (MPI_COMM_WORLD); one process if MPI is not initialised.
  Communicator();

  int rank() const { return rank_; }
  int size() const { return size_; }
  MPI_Comm handle() const { return comm_; }

  std::int64_t sum(std::int64_t local) const;
  double max(double local) const;
  double min(double local) const;
  // Every process's `local` values, concatenated in rank order, on rank 0 (empty elsewhere).
  std::vector<double> gather(const std::vector<double>& local) const;
  std::vector<std::int64_t> gather(const std::vector<std::int64_t>& local) const;
  // Every process's `local` values, concatenated in rank order, on every process.
  std::vector<double> all_gather(const std::vector<double>& local) const;
  // `n` sums passed along the processes in rank order: add_own adds this process's terms
  // to `partial`, which arrives holding the processes' before it and returns the totals,
  // the same on every process. A chain: one message per process per sum, in sequence —
  // the price of summing in one global order (docs/models/distributed.md).
  void ordered_sum(double* partial, int n, const std::function<void(double*)>& add_own) const;
  // Process `root`'s `values` (the same length everywhere) on every process.
  void broadcast(std::vector<double>& values, int root) const;
  void barrier() const;
  // Stops every process of the run with this exit status (MPI_Abort): for an error only
  // one process met, which would leave the others waiting for it.
  [[noreturn]] void abort(int status) const;

 private:
  MPI_Comm comm_ = MPI_COMM_NULL;
  int rank_ = 0, size_ = 1;
};

// After a step that only some processes may fail (process 0 opening the outputs):
// every process learns whether one failed. The one that did throws `failure` nested in
// a SharedFailure, the others throw OtherProcessFailed with its exit status (core/error.hpp).
void agree_on_failure(const Communicator& comm, const std::exception_ptr& failure);

}  // namespace pdmpm::dist
