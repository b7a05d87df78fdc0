#pragma once
// Per-stencil-offset bond data: reference vector ξ, length |ξ|, influence ω and
// partial-volume factor β. On a lattice every bond is one of the stencil
// offsets, so these are looked up instead of stored per bond.
#include <vector>

#include "solver/pd/kernels/bond_kernels.hpp"

#include "solver/core/stencil.hpp"
#include "solver/pd/influence.hpp"
#include "solver/pd/partial_volume.hpp"

namespace pdmpm::pd {

template <int D>
struct BondTable {
  std::vector<Vec<D>> xi;
  std::vector<double> length;   // (length, weight, xi_component: + kernels::lanes zeros of padding)
  std::vector<double> omega;
  std::vector<double> beta;
  std::vector<double> weight;  // ω β
  std::vector<double> xi_component[3];  // ξ by component (structure of arrays for the kernels)
  std::vector<double> rows;             // 4 per offset: ξ, |ξ|, zeros (kernels::BondShapeTable::rows)

  kernels::BondShapeTable view() const {
    kernels::BondShapeTable v{};
    for (int a = 0; a < D; ++a) v.xi[a] = xi_component[a].data();
    v.length = length.data();
    v.weight = weight.data();
    v.rows = rows.data();
    return v;
  }

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
      for (int a = 0; a < D; ++a) t.xi_component[a].push_back(x[a]);
      for (int a = 0; a < 4; ++a) t.rows.push_back(a < D ? x[a] : a == D ? L : 0.0);
    }
    // Padding for the kernels' whole-block loads (kernels::BondShapeTable).
    for (int pad = 0; pad < kernels::lanes; ++pad) {
      t.length.push_back(0.0);
      t.weight.push_back(0.0);
      for (int a = 0; a < D; ++a) t.xi_component[a].push_back(0.0);
      for (int a = 0; a < 4; ++a) t.rows.push_back(0.0);
    }
    return t;
  }
};

}  // namespace pdmpm::pd
