#include "solver/dist/communicator.hpp"

#include <limits>
#include <numeric>
#include <stdexcept>

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

std::int64_t Communicator::sum(std::int64_t local) const {
  if (size_ == 1) return local;
  std::int64_t all = 0;
  MPI_Allreduce(&local, &all, 1, MPI_INT64_T, MPI_SUM, comm_);
  return all;
}

double Communicator::max(double local) const {
  if (size_ == 1) return local;
  double all = 0.0;
  MPI_Allreduce(&local, &all, 1, MPI_DOUBLE, MPI_MAX, comm_);
  return all;
}

double Communicator::min(double local) const {
  if (size_ == 1) return local;
  double all = 0.0;
  MPI_Allreduce(&local, &all, 1, MPI_DOUBLE, MPI_MIN, comm_);
  return all;
}

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

void Communicator::barrier() const {
  if (size_ > 1) MPI_Barrier(comm_);
}

}  // namespace pdmpm::dist
