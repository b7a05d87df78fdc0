#pragma once
// Boundary conditions on grid nodes: velocity constraints on node regions
// (fixed, roller, prescribed velocity) and mirror symmetry planes on grid lines.
//
// A symmetry plane acts as if every particle had a mirror image across it: after
// each particle-to-grid transfer the nodes beyond the plane are folded onto their
// mirror nodes (normal components change sign), the plane's own node gets its
// mirror contribution (normal momentum and force cancel), and the nodes beyond
// then copy their mirror's reflected values. GIMP and B-spline supports reach
// past a body's edge, so this keeps them consistent where a plain velocity
// constraint on the edge nodes would not.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "solver/mpm/grid.hpp"
#include "solver/mpm/settings.hpp"

namespace pdmpm::mpm {

template <int D>
class GridBoundary {
 public:
  GridBoundary() = default;
  GridBoundary(const std::vector<GridBc<D>>& bcs, const Grid<D>& grid);

  // Fold the contributions of nodes beyond symmetry planes into the domain and clear
  // them there (call after each particle-to-grid transfer; null arrays are skipped).
  void fold(std::vector<double>* mass, std::vector<Vec<D>>* vec1, std::vector<Vec<D>>* vec2 = nullptr,
            std::vector<Vec<D>>* vec3 = nullptr) const;
  // Nodes beyond symmetry planes take their mirror's reflected value.
  void mirror(std::vector<Vec<D>>& v) const;
  // Impose the velocity constraints at time t. With `mass` and `dt` given, the force
  // each boundary exerted (Σ m Δv / dt over its nodes) is written to `reactions`.
  // With `terms` too, each node's share goes there instead, in the order the sums take
  // them (a distributed run sums the shares of every process's nodes in that order).
  struct NodeTerm {
    std::size_t boundary;
    Index node;
    Vec<D> value;
  };
  void constrain(std::vector<Vec<D>>& v, double t, const std::vector<double>* mass = nullptr, double dt = 0.0,
                 std::vector<Vec<D>>* reactions = nullptr, std::vector<NodeTerm>* terms = nullptr) const;

  // Moves the boxes of the moving velocity constraints from t to t + dt by their
  // prescribed velocity at the box centre (trapezoid rule: exact for a constant speed
  // and a linear ramp) and re-collects their nodes. Call at the end of each step.
  // A moving box holds a node with weight w, v ← w v_prescribed + (1 − w) v, w falling
  // from 1 to 0 over the cell centred on each face it moves across: a node is let go
  // over the box's travel of one cell, not at once (which jolted the grip's load).
  void advance(double t, double dt);
  // Displacement of each constraint's box since t = 0 (zero unless it moves); for
  // checkpoints, with refresh() after it is restored.
  std::vector<Vec<D>>& box_offsets() { return offset_; }
  void refresh();

  // Power of the velocity constraints at time t against nodal forces f (the reaction
  // −f on each constrained component, times the prescribed velocity; real share only).
  // With `terms`, each node's contributions per component (0 where free) go there
  // instead, and the power returned is 0: the power is −Σ of them in their order.
  double constraint_power(const std::vector<Vec<D>>& f, double t, std::vector<NodeTerm>* terms = nullptr) const;

  // Share of a node's (folded) mass and force that belongs to the real body: ½ on a
  // symmetry plane (the mirror image holds the other half), ¼ where two planes meet.
  // Reactions and work sums use it so mirror images are not counted.
  double real_share(Index node) const { return share_.empty() ? 1.0 : share_[node]; }

  std::size_t count() const { return bcs_.size(); }
  const std::vector<Index>& nodes(std::size_t bc) const { return nodes_[bc]; }

 private:
  struct MirrorPair {
    Index outside, inside;
    int axis;
  };
  // Velocity of velocity bc b at its n-th node and time t, before the ramp; `uniform`
  // is uniform_velocity(b, t), taken instead when it holds a value.
  Vec<D> prescribed(std::size_t b, std::size_t n, double t, const std::optional<Vec<D>>& uniform) const;
  // Bc b's velocity at time t when it is the same at every node (a constant, or a field
  // that does not depend on position), evaluated once; else nothing.
  std::optional<Vec<D>> uniform_velocity(std::size_t b, double t) const;
  // The nodes (and their positions) of bc b's box displaced by offset_[b].
  void collect_nodes(std::size_t b);

  std::vector<GridBc<D>> bcs_;
  std::vector<std::vector<Index>> nodes_;                        // per velocity-type bc: constrained nodes
  std::vector<std::vector<Vec<D>>> positions_;                   // per bc: positions of its nodes
  std::vector<std::vector<double>> weight_;                      // per moving bc: each node's hold w ∈ (0, 1]
  std::vector<std::vector<MirrorPair>> pairs_;                   // per symmetry plane, applied in order
  std::vector<std::pair<std::vector<Index>, int>> plane_nodes_;  // per symmetry plane: nodes on it, axis
  std::vector<double> share_;                                    // real_share per node (empty: all 1)
  std::vector<Vec<D>> offset_;                                   // per bc: its box's displacement
  Vec<D> node0_ = Vec<D>::Zero();                                // the grid's nodes: node0 + k h, k < n
  double h_ = 1.0;
  IVec<D> n_ = IVec<D>::Ones();
};

}  // namespace pdmpm::mpm
