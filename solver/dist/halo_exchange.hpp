#pragma once
// The messages between a process and the others (core::OtherProcesses). Halo:
// each process sends the values of its own particles that other processes hold in
// their halos, and receives its halo's values from their owners; the lists are
// agreed once (each process asks the owners for its halo's global indices), a
// fill is then one message per neighbouring process each way. Sums: passed along
// the processes in rank order, each adding its own particles' terms — the
// one-process order, since ownership ranges are contiguous in the global index.
#include <vector>

#include "solver/core/particles.hpp"
#include "solver/dist/communicator.hpp"
#include "solver/dist/decomposition.hpp"

namespace pdmpm::dist {

class HaloExchange final : public core::OtherProcesses {
 public:
  // `halo`: global indices of the remote ghosts, increasing, in the store's ghost
  // order after `n_real` own particles; `n`: the body's real particles.
  HaloExchange(const Communicator& comm, Index n, OwnedRange own, Index n_real, const std::vector<Index>& halo);

  void fill(double* data, int width) const override;
  void ordered_sum(double* partial, int n, const std::function<void(double*)>& add_own) const override;
  double max(double local) const override;
  Index first_global() const override { return first_global_; }
  void fill_reverse_sides(const double* sides, double* reverse) const override;
  int processes() const override { return comm_.size(); }
  int rank() const override { return comm_.rank(); }
  Index ghost_global(Index g) const override { return halo_[g]; }
  int ghost_owner_rank(Index g) const override { return owner_rank(halo_[g], n_body_, comm_.size()); }
  std::vector<std::vector<double>> send_to(const std::vector<std::vector<double>>& to) const override;

  // The bond sides that cross to another process, from the store's families (`offsets`
  // per own particle, `neighbor` per bond side): with each neighbouring process, the
  // sides i→j whose j it owns, in the order of the pair {global i, global j} — which
  // orders its reverse sides j→i alike, so the two lists match with no message. Throws
  // std::logic_error if a process counts a different number of sides shared with this one.
  void index_bond_sides(const std::vector<BondIndex>& offsets, const std::vector<Index>& neighbor);

  // Values one fill of width 1 sends from this process (the communication volume).
  std::int64_t values_sent() const;
  int neighbours() const { return static_cast<int>(peers_.size()); }

 private:
  struct Peer {
    int rank = 0;
    std::vector<Index> send;  // own particles (local index) it needs, in its order
    Index recv_first = 0;     // first local index of the ghosts it owns
    Index recv_count = 0;
  };
  struct SharedSides {
    int rank = 0;
    std::vector<BondIndex> sides;  // this process's sides to particles `rank` owns, in pair order
  };
  Communicator comm_;
  Index first_global_ = 0, n_body_ = 0, n_real_ = 0;
  std::vector<Index> halo_;  // global index of each remote ghost
  std::vector<SharedSides> shared_sides_;
  mutable std::vector<std::vector<double>> side_buffers_;  // send, then receive, per entry of shared_sides_
  std::vector<Peer> peers_;
  mutable std::vector<std::vector<double>> buffers_;
};

}  // namespace pdmpm::dist
