#pragma once
// Fixed uniform background grid: nodes at node0 + k·h, k ∈ [0, n)^D, with the
// per-node quantities of one explicit step. Node order is x fastest.
#include <vector>

#include "solver/core/types.hpp"

namespace pdmpm::mpm {

template <int D>
struct Grid {
  Vec<D> node0 = Vec<D>::Zero();  // position of node (0, …, 0)
  double h = 1.0;                 // cell size
  IVec<D> n = IVec<D>::Ones();    // nodes per axis
  IVec<D> stride = IVec<D>::Ones();

  std::vector<double> mass;
  std::vector<Vec<D>> momentum;
  std::vector<Vec<D>> force_internal;  // −Σ V₀ τ ∇S
  std::vector<Vec<D>> force_external;  // body forces, tractions, particle external forces
  std::vector<Vec<D>> velocity;        // vⁿ (after boundary conditions)
  std::vector<Vec<D>> velocity_new;    // vⁿ⁺¹ (after boundary conditions)

  Grid() = default;
  Grid(const Vec<D>& node0_, double h_, const IVec<D>& n_) : node0(node0_), h(h_), n(n_) {
    Index s = 1;
    for (int a = 0; a < D; ++a) {
      stride[a] = s;
      s *= n[a];
    }
    const std::size_t N = static_cast<std::size_t>(s);
    mass.assign(N, 0.0);
    momentum.assign(N, Vec<D>::Zero());
    force_internal.assign(N, Vec<D>::Zero());
    force_external.assign(N, Vec<D>::Zero());
    velocity.assign(N, Vec<D>::Zero());
    velocity_new.assign(N, Vec<D>::Zero());
  }

  Index size() const { return static_cast<Index>(mass.size()); }
  Index index(const IVec<D>& k) const { return k.dot(stride); }
  IVec<D> coords(Index i) const {
    IVec<D> k;
    for (int a = 0; a < D; ++a) {
      k[a] = i % n[a];
      i /= n[a];
    }
    return k;
  }
  Vec<D> position(const IVec<D>& k) const { return node0 + h * k.template cast<double>(); }
  Vec<D> position(Index i) const { return position(coords(i)); }
  IVec<D> cells() const { return n - IVec<D>::Ones(); }
};

}  // namespace pdmpm::mpm
