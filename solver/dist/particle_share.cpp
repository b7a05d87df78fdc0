#include "solver/dist/particle_share.hpp"

#include <limits>
#include <stdexcept>

namespace pdmpm::dist {

std::vector<std::uint8_t> ParticleShare::all_reach(const std::vector<std::uint8_t>& reach) const {
  const int blocks = static_cast<int>(reach.size());
  std::vector<std::uint8_t> all(static_cast<std::size_t>(blocks) * comm_.size());
  MPI_Allgather(reach.data(), blocks, MPI_UINT8_T, all.data(), blocks, MPI_UINT8_T, comm_.handle());
  return all;
}

void ParticleShare::plan(std::vector<std::vector<Index>> send) {
  const int ranks = comm_.size();
  send_ = std::move(send);
  send_.resize(ranks);
  std::vector<int> count(ranks, 0);
  for (int q = 0; q < ranks; ++q) count[q] = static_cast<int>(send_[q].size());
  receive_count_.assign(ranks, 0);
  MPI_Alltoall(count.data(), 1, MPI_INT, receive_count_.data(), 1, MPI_INT, comm_.handle());
}

std::vector<double> ParticleShare::send(int width, const std::function<void(Index, double*)>& record) const {
  const int ranks = comm_.size();
  std::vector<int> send_count(ranks), send_offset(ranks), receive_count(ranks), receive_offset(ranks);
  std::int64_t sent = 0, received = 0;
  for (int q = 0; q < ranks; ++q) {
    send_count[q] = static_cast<int>(send_[q].size()) * width;
    receive_count[q] = receive_count_[q] * width;
    send_offset[q] = static_cast<int>(sent);
    receive_offset[q] = static_cast<int>(received);
    sent += send_count[q];
    received += receive_count[q];
  }
  if (sent > std::numeric_limits<int>::max() || received > std::numeric_limits<int>::max())
    throw std::length_error("MPM ghost exchange: more values than MPI counts in an int");
  std::vector<double> out(static_cast<std::size_t>(sent)), in(static_cast<std::size_t>(received));
  for (int q = 0; q < ranks; ++q)
    for (std::size_t s = 0; s < send_[q].size(); ++s) record(send_[q][s], &out[send_offset[q] + s * width]);
  MPI_Alltoallv(out.data(), send_count.data(), send_offset.data(), MPI_DOUBLE, in.data(), receive_count.data(),
                receive_offset.data(), MPI_DOUBLE, comm_.handle());
  return in;
}

}  // namespace pdmpm::dist
