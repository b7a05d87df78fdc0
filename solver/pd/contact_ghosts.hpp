#pragma once
// Short-range contact in a distributed run (docs/models/distributed.md, "Contact"): the
// particles other processes own that may press on this process's particles. Contact pairs
// are found by current position, so this halo is not the families' (a body may strike
// another that was far away in the reference configuration): at each rebuild of the
// contact list, every process sends its particles' bounding box to every other, and each
// sends back those of its particles that lie within the list's radius of the box — in its
// own (global) order, so the ghosts arrive in the global particle order, lower processes
// first. Until the next rebuild the same particles' current positions travel every step.
#include <vector>

#include "solver/core/particles.hpp"
#include "solver/core/state_archive.hpp"

namespace pdmpm::pd {

template <int D>
class ContactGhosts {
 public:
  // At a rebuild: finds and receives the ghosts for own positions `own` (finite, checked)
  // and a list radius; sets the box that holds every process's particles.
  void find(const core::Particles<D>& p, const std::vector<Vec<D>>& own, double radius);
  // Between rebuilds: the same ghosts' current positions.
  void refresh(const core::Particles<D>& p, const std::vector<Vec<D>>& own);

  Index size() const { return static_cast<Index>(global_.size()); }
  Index from_lower_processes() const { return lower_; }  // the first ghosts, owned by lower ranks
  const std::vector<Vec<D>>& position() const { return y_; }
  const std::vector<Vec<D>>& reference_position() const { return x0_; }
  const std::vector<double>& volume() const { return volume_; }
  const std::vector<Index>& global() const { return global_; }
  // The box of every process's current positions (at the last find).
  const Vec<D>& body_lo() const { return lo_; }
  const Vec<D>& body_hi() const { return hi_; }

  void checkpoint(core::StateArchive& a);

 private:
  std::vector<std::int64_t> send_start_;  // per process q, own particles q holds as ghosts (CSR)
  std::vector<Index> send_;
  std::vector<std::int64_t> receive_start_;  // per process q, where its ghosts start
  std::vector<Vec<D>> y_, x0_;
  std::vector<double> volume_;
  std::vector<Index> global_;
  Index lower_ = 0;
  Vec<D> lo_ = Vec<D>::Zero(), hi_ = Vec<D>::Zero();
};

}  // namespace pdmpm::pd
