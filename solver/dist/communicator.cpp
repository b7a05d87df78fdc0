#include "solver/dist/communicator.hpp"

#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "solver/core/error.hpp"

namespace pdmpm::dist {

MpiSession::MpiSession(int& argc, char**& argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
}

MpiSession::~MpiSession() { MPI_Finalize(); }

Communicator::Communicator() {
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised) return;
  comm_ = MPI_COMM_WORLD;
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

namespace {

// The reduction of one value over every process (the value itself in a one-process run).
template <class T>
T all_reduce(MPI_Comm comm, int size, T local, MPI_Datatype type, MPI_Op op) {
  if (size == 1) return local;
  T all{};
  MPI_Allreduce(&local, &all, 1, type, op, comm);
  return all;
}

}  // namespace

std::int64_t Communicator::sum(std::int64_t local) const {
  return all_reduce(comm_, size_, local, MPI_INT64_T, MPI_SUM);
}
double Communicator::max(double local) const { return all_reduce(comm_, size_, local, MPI_DOUBLE, MPI_MAX); }
double Communicator::min(double local) const { return all_reduce(comm_, size_, local, MPI_DOUBLE, MPI_MIN); }

namespace {

template <class T>
std::vector<T> gather_to_root(MPI_Comm comm, int rank, int size, const std::vector<T>& local, MPI_Datatype type) {
  if (size == 1) return local;
  if (local.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw std::length_error("gather: more values on one process than MPI counts in an int");
  const int n = static_cast<int>(local.size());
  std::vector<int> counts(rank == 0 ? size : 0), offsets(rank == 0 ? size : 0);
  MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  std::vector<T> all;
  if (rank == 0) {
    std::int64_t total = 0;
    for (int r = 0; r < size; ++r) {
      if (total > std::numeric_limits<int>::max()) throw std::length_error("gather: more values than an int counts");
      offsets[r] = static_cast<int>(total);
      total += counts[r];
    }
    all.resize(static_cast<std::size_t>(total));
  }
  MPI_Gatherv(local.data(), n, type, all.data(), counts.data(), offsets.data(), type, 0, comm);
  return all;
}

}  // namespace

std::vector<double> Communicator::gather(const std::vector<double>& local) const {
  return gather_to_root(comm_, rank_, size_, local, MPI_DOUBLE);
}

std::vector<std::int64_t> Communicator::gather(const std::vector<std::int64_t>& local) const {
  return gather_to_root(comm_, rank_, size_, local, MPI_INT64_T);
}

std::vector<double> Communicator::all_gather(const std::vector<double>& local) const {
  if (size_ == 1) return local;
  if (local.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw std::length_error("all_gather: more values on one process than MPI counts in an int");
  const int n = static_cast<int>(local.size());
  std::vector<int> counts(size_), offsets(size_);
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_);
  std::int64_t total = 0;
  for (int r = 0; r < size_; ++r) {
    if (total > std::numeric_limits<int>::max()) throw std::length_error("all_gather: more values than an int counts");
    offsets[r] = static_cast<int>(total);
    total += counts[r];
  }
  std::vector<double> all(static_cast<std::size_t>(total));
  MPI_Allgatherv(local.data(), n, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE, comm_);
  return all;
}

void Communicator::ordered_sum(double* partial, int n, const std::function<void(double*)>& add_own) const {
  constexpr int tag = 1;
  if (rank_ > 0) MPI_Recv(partial, n, MPI_DOUBLE, rank_ - 1, tag, comm_, MPI_STATUS_IGNORE);
  add_own(partial);
  if (rank_ + 1 < size_) MPI_Send(partial, n, MPI_DOUBLE, rank_ + 1, tag, comm_);
  if (size_ > 1) MPI_Bcast(partial, n, MPI_DOUBLE, size_ - 1, comm_);
}

void Communicator::broadcast(std::vector<double>& values, int root) const {
  if (size_ > 1) MPI_Bcast(values.data(), static_cast<int>(values.size()), MPI_DOUBLE, root, comm_);
}

void Communicator::barrier() const {
  if (size_ > 1) MPI_Barrier(comm_);
}

void Communicator::abort(int status) const {
  MPI_Abort(comm_, status);
  std::exit(status);  // MPI_Abort does not return; a one-process run without MPI gets here
}

void agree_on_failure(const Communicator& comm, const std::exception_ptr& failure) {
  const int status = failure ? exit_status_of(failure) : 0;
  const int worst = static_cast<int>(comm.max(status));
  if (failure) {
    try {
      std::rethrow_exception(failure);
    } catch (...) {
      std::throw_with_nested(SharedFailure());
    }
  }
  if (worst != 0) throw OtherProcessFailed(worst);
}

}  // namespace pdmpm::dist
