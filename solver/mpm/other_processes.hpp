#pragma once
// The other processes of a distributed MPM run as the step sees them
// (solver/dist/particle_share.hpp implements it with MPI; docs/models/distributed.md).
// Each process owns a fixed, contiguous range of the body's material points by global
// index (they are Lagrangian: they never change owner) and the whole background grid.
// A node's sums must hold every point whose stencil reaches it, so before each step a
// process receives, as ghosts, the other processes' points that reach the nodes its
// own points reach — found afresh every step, since points move.
#include <cstdint>
#include <functional>
#include <vector>

#include "solver/core/types.hpp"

namespace pdmpm::mpm {

class OtherProcesses {
 public:
  virtual ~OtherProcesses() = default;
  // The global index of this process's first own point (own points are contiguous).
  virtual Index first_global() const = 0;
  // This process's place in rank order (the global order of the points).
  virtual int rank() const = 0;
  // Every process's `reach` (one flag per node block, the same blocks on every process:
  // the blocks its points reach), concatenated in rank order.
  virtual std::vector<std::uint8_t> all_reach(const std::vector<std::uint8_t>& reach) const = 0;
  // The own points (store indices, ascending) each process needs this step, one list per
  // process in rank order (this process's empty); remembered for send().
  virtual void plan(std::vector<std::vector<Index>> send) = 0;
  // The planned points' records (`width` doubles each, written by record(k, out)) to the
  // processes that need them; returns the records this process receives, in the global
  // order of their points.
  virtual std::vector<double> send(int width, const std::function<void(Index, double*)>& record) const = 0;
  // `n` sums over the points of every process in their global order: add_own adds this
  // process's terms to `partial`, which arrives holding the processes' before it.
  virtual void ordered_sum(double* partial, int n, const std::function<void(double*)>& add_own) const = 0;
  // The largest of every process's `local` (exact in any order).
  virtual double max(double local) const = 0;
  // Every process's values, concatenated in rank order, on every process.
  virtual std::vector<double> all_gather(const std::vector<double>& local) const = 0;
};

}  // namespace pdmpm::mpm
