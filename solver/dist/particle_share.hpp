#pragma once
// MPM's ghost points over MPI (mpm::OtherProcesses): a plan per step says which own
// points each other process needs (those reaching a node block it flags), then
// records go across in one all-to-all. Ownership is by contiguous global ranges, so
// the records arrive, rank after rank, in the global order of their points.
#include <vector>

#include "solver/dist/communicator.hpp"
#include "solver/dist/decomposition.hpp"
#include "solver/mpm/other_processes.hpp"

namespace pdmpm::dist {

class ParticleShare final : public mpm::OtherProcesses {
 public:
  ParticleShare(const Communicator& comm, OwnedRange own) : comm_(comm), own_(own) {}

  Index first_global() const override { return own_.begin; }
  int rank() const override { return comm_.rank(); }
  std::vector<std::uint8_t> all_reach(const std::vector<std::uint8_t>& reach) const override;
  void plan(std::vector<std::vector<Index>> send) override;
  std::vector<double> send(int width, const std::function<void(Index, double*)>& record) const override;
  void ordered_sum(double* partial, int n, const std::function<void(double*)>& add_own) const override {
    comm_.ordered_sum(partial, n, add_own);
  }
  double max(double local) const override { return comm_.max(local); }
  std::vector<double> all_gather(const std::vector<double>& local) const override { return comm_.all_gather(local); }

 private:
  Communicator comm_;
  OwnedRange own_;
  std::vector<std::vector<Index>> send_;  // per process: own points it needs, ascending
  std::vector<int> receive_count_;        // per process: points it sends here
};

}  // namespace pdmpm::dist
