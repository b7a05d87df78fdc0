#pragma once
// Per-stencil-offset bond data: reference vector ξ, length |ξ|, influence ω and
// partial-volume factor β. On a lattice every bond is one of the stencil
// offsets, so these are looked up instead of stored per bond.
#include <vector>

#include "solver/core/stencil.hpp"
#include "solver/pd/influence.hpp"
#include "solver/pd/partial_volume.hpp"

namespace pdmpm::pd {

template <int D>
struct BondTable {
  std::vector<Vec<D>> xi;
  std::vector<double> length;
  std::vector<double> omega;
  std::vector<double> beta;
  std::vector<double> weight;  // ω β

  static BondTable build(const core::Stencil<D>& st, double dx, double delta, Influence w, PartialVolume pv) {
    BondTable t;
    for (int k = 0; k < st.size(); ++k) {
      const Vec<D> x = dx * st.offset[k].template cast<double>();
      const double L = x.norm();
      t.xi.push_back(x);
      t.length.push_back(L);
      t.omega.push_back(influence(w, L, delta));
      t.beta.push_back(partial_volume(pv, L, delta, dx));
      t.weight.push_back(t.omega.back() * t.beta.back());
    }
    return t;
  }
};

}  // namespace pdmpm::pd
