#include "solver/dist/halo_exchange.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>

namespace pdmpm::dist {

HaloExchange::HaloExchange(const Communicator& comm, Index n, OwnedRange own, Index n_real,
                           const std::vector<Index>& halo)
    : comm_(comm), first_global_(own.begin), n_body_(n), n_real_(n_real), halo_(halo) {
  const int ranks = comm_.size();
  // What this process receives: its halo grouped by owner (contiguous, as ranges are).
  std::vector<std::vector<std::int64_t>> asked(ranks);
  std::map<int, Peer> peers;
  for (std::size_t h = 0; h < halo.size(); ++h) {
    const int q = owner_rank(halo[h], n, ranks);
    auto& peer = peers[q];
    if (peer.recv_count == 0) peer.recv_first = n_real + static_cast<Index>(h);
    ++peer.recv_count;
    asked[q].push_back(halo[h]);
  }
  // What it sends: the requests of the others, turned into its own local indices.
  std::vector<int> ask_count(ranks), ask_offset(ranks), get_count(ranks), get_offset(ranks);
  std::vector<std::int64_t> ask_flat;
  for (int q = 0; q < ranks; ++q) {
    ask_count[q] = static_cast<int>(asked[q].size());
    ask_offset[q] = static_cast<int>(ask_flat.size());
    ask_flat.insert(ask_flat.end(), asked[q].begin(), asked[q].end());
  }
  MPI_Alltoall(ask_count.data(), 1, MPI_INT, get_count.data(), 1, MPI_INT, comm_.handle());
  int total = 0;
  for (int q = 0; q < ranks; ++q) get_offset[q] = total, total += get_count[q];
  std::vector<std::int64_t> get_flat(static_cast<std::size_t>(total));
  MPI_Alltoallv(ask_flat.data(), ask_count.data(), ask_offset.data(), MPI_INT64_T, get_flat.data(), get_count.data(),
                get_offset.data(), MPI_INT64_T, comm_.handle());
  for (int q = 0; q < ranks; ++q) {
    if (get_count[q] == 0) continue;
    auto& peer = peers[q];
    for (int k = 0; k < get_count[q]; ++k) {
      const auto g = static_cast<Index>(get_flat[static_cast<std::size_t>(get_offset[q] + k)]);
      if (!own.contains(g)) throw std::logic_error("halo exchange: asked for a particle this process does not own");
      peer.send.push_back(g - own.begin);
    }
  }
  for (auto& [q, peer] : peers) {
    peer.rank = q;
    peers_.push_back(std::move(peer));
  }
  buffers_.resize(peers_.size());
}

void HaloExchange::fill(double* data, int width) const {
  std::vector<MPI_Request> requests;
  requests.reserve(2 * peers_.size());
  for (std::size_t k = 0; k < peers_.size(); ++k) {
    const auto& peer = peers_[k];
    if (peer.recv_count > 0) {
      requests.emplace_back();
      MPI_Irecv(data + static_cast<std::size_t>(peer.recv_first) * width, static_cast<int>(peer.recv_count) * width,
                MPI_DOUBLE, peer.rank, 0, comm_.handle(), &requests.back());
    }
  }
  for (std::size_t k = 0; k < peers_.size(); ++k) {
    const auto& peer = peers_[k];
    if (peer.send.empty()) continue;
    auto& buf = buffers_[k];
    buf.resize(peer.send.size() * static_cast<std::size_t>(width));
    for (std::size_t s = 0; s < peer.send.size(); ++s)
      for (int c = 0; c < width; ++c) buf[s * width + c] = data[static_cast<std::size_t>(peer.send[s]) * width + c];
    requests.emplace_back();
    MPI_Isend(buf.data(), static_cast<int>(buf.size()), MPI_DOUBLE, peer.rank, 0, comm_.handle(), &requests.back());
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
}

void HaloExchange::ordered_sum(double* partial, int n, const std::function<void(double*)>& add_own) const {
  comm_.ordered_sum(partial, n, add_own);
}

void HaloExchange::index_bond_sides(const std::vector<BondIndex>& offsets, const std::vector<Index>& neighbor) {
  struct Side {
    Index low, high;  // the pair's global indices
    BondIndex side;
  };
  std::map<int, std::vector<Side>> by_rank;
  for (Index i = 0; i + 1 < static_cast<Index>(offsets.size()); ++i)
    for (BondIndex b = offsets[i]; b < offsets[i + 1]; ++b) {
      const Index j = neighbor[b];
      if (j < n_real_ || j >= n_real_ + static_cast<Index>(halo_.size())) continue;  // own, or a mirror
      const Index gi = first_global_ + i, gj = halo_[j - n_real_];
      by_rank[owner_rank(gj, n_body_, comm_.size())].push_back({std::min(gi, gj), std::max(gi, gj), b});
    }
  std::vector<int> count(comm_.size(), 0), theirs(comm_.size(), 0);
  shared_sides_.clear();
  for (auto& [q, sides] : by_rank) {
    std::sort(sides.begin(), sides.end(),
              [](const Side& a, const Side& b) { return a.low != b.low ? a.low < b.low : a.high < b.high; });
    SharedSides shared{q, {}};
    for (const auto& side : sides) shared.sides.push_back(side.side);
    count[q] = static_cast<int>(shared.sides.size());
    shared_sides_.push_back(std::move(shared));
  }
  MPI_Alltoall(count.data(), 1, MPI_INT, theirs.data(), 1, MPI_INT, comm_.handle());
  if (count != theirs)
    throw std::logic_error("halo exchange: processes disagree on the bond sides they share (asymmetric families)");
  side_buffers_.assign(2 * shared_sides_.size(), {});
}

void HaloExchange::fill_reverse_sides(const double* sides, double* reverse) const {
  std::vector<MPI_Request> requests;
  requests.reserve(2 * shared_sides_.size());
  constexpr int tag = 2;
  for (std::size_t k = 0; k < shared_sides_.size(); ++k) {
    auto& in = side_buffers_[2 * k + 1];
    in.resize(shared_sides_[k].sides.size());
    requests.emplace_back();
    MPI_Irecv(in.data(), static_cast<int>(in.size()), MPI_DOUBLE, shared_sides_[k].rank, tag, comm_.handle(),
              &requests.back());
  }
  for (std::size_t k = 0; k < shared_sides_.size(); ++k) {
    auto& out = side_buffers_[2 * k];
    out.clear();
    for (BondIndex b : shared_sides_[k].sides) out.push_back(sides[b]);
    requests.emplace_back();
    MPI_Isend(out.data(), static_cast<int>(out.size()), MPI_DOUBLE, shared_sides_[k].rank, tag, comm_.handle(),
              &requests.back());
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  for (std::size_t k = 0; k < shared_sides_.size(); ++k) {
    const auto& in = side_buffers_[2 * k + 1];
    for (std::size_t s = 0; s < in.size(); ++s) reverse[shared_sides_[k].sides[s]] = in[s];
  }
}

std::vector<std::vector<double>> HaloExchange::send_to(const std::vector<std::vector<double>>& to) const {
  const int ranks = comm_.size();
  std::vector<int> send_count(ranks), send_offset(ranks), receive_count(ranks), receive_offset(ranks);
  std::vector<double> out;
  for (int q = 0; q < ranks; ++q) {
    send_offset[q] = static_cast<int>(out.size());
    send_count[q] = static_cast<int>(to[q].size());
    out.insert(out.end(), to[q].begin(), to[q].end());
  }
  MPI_Alltoall(send_count.data(), 1, MPI_INT, receive_count.data(), 1, MPI_INT, comm_.handle());
  int total = 0;
  for (int q = 0; q < ranks; ++q) receive_offset[q] = total, total += receive_count[q];
  std::vector<double> in(static_cast<std::size_t>(total));
  MPI_Alltoallv(out.data(), send_count.data(), send_offset.data(), MPI_DOUBLE, in.data(), receive_count.data(),
                receive_offset.data(), MPI_DOUBLE, comm_.handle());
  std::vector<std::vector<double>> from(ranks);
  for (int q = 0; q < ranks; ++q)
    from[q].assign(in.begin() + receive_offset[q], in.begin() + receive_offset[q] + receive_count[q]);
  return from;
}

double HaloExchange::max(double local) const { return comm_.max(local); }

std::int64_t HaloExchange::values_sent() const {
  std::int64_t n = 0;
  for (const auto& peer : peers_) n += static_cast<std::int64_t>(peer.send.size());
  return n;
}

}  // namespace pdmpm::dist
