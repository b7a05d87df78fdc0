#pragma once
// The bond-midpoint deformation of the stabilized hybrid PD model (solver/pd/hpd.hpp):
// the sub-horizon of bond i→j is the overlap of the two horizons, the points bonded (live)
// to both i and j, with i and j themselves. Over it the displacement is fitted by an affine
// field in the least-squares sense, with weights w_l = V_l (times HpdOptions::end_weight for i
// and j), whose gradient is the bond's
//   H_ij = Σ_l u_l ⊗ c_l,   c_l = w_l K⁻¹ (x_l − x̄),   K = Σ_l w_l (x_l − x̄) ⊗ (x_l − x̄),
// x̄ = Σ w_l x_l / Σ w_l (the weighted centroid; Σ_l c_l = 0, so translations give H = 0, and
// any affine field u = a + G x gives H = G exactly, near boundaries too). This is the
// bond-associated deformation gradient of Breitzman & Dayal (2018) and Chen (2018), here
// on the horizons' overlap that the stabilized hybrid PD (HPD) paper (Soil Dyn. Earthq. Eng.
// 2023) prescribes for the bond midpoint.
//
// A bond whose sub-horizon has fewer than HpdOptions::min_points(D) points, or whose points
// lie on one line or plane (K singular: smallest eigenvalue ≤ 1e-10 × largest), cannot
// determine an nD gradient: it is marked axial and keeps only its ends, c_j = −c_i = ξ/|ξ|²
// (the minimum-norm fit), of which the model uses the stretch along the bond alone.
//
// The coefficients depend on the reference positions and on which bonds are live; they are
// rebuilt when the live set changes (bonds broke, or a step was rejected).
#include <cstdint>
#include <string>
#include <vector>

#include "solver/pd/system.hpp"

namespace pdmpm::pd {

template <int D>
struct SubHorizon {
  // Per bond side b: its points and coefficients in [begin[b], begin[b + 1]) (none if b is not live).
  std::vector<BondIndex> begin;
  std::vector<Index> point;
  std::vector<Vec<D>> coef;
  std::vector<std::uint8_t> axial;  // 1: too few points or degenerate, the axial fallback
  // The same entries by point: particle k appears in the entries at_point[at_begin[k] … at_begin[k + 1]).
  std::vector<BondIndex> at_begin;
  std::vector<BondIndex> at_point;
  std::vector<BondIndex> entry_bond;     // the bond side of each entry
  std::vector<std::uint8_t> built_live;  // live bit of every bond side when built
  std::int64_t n_axial = 0;              // live bond sides on the fallback

  static SubHorizon build(const System<D>& sys, int min_points, double end_weight);
  // Whether the live bonds differ from those the coefficients were built for.
  bool stale(const System<D>& sys) const;
};

// Empty when every bond of a full (interior) family has a sub-horizon of ≥ min_points points
// spanning D dimensions on this stencil; otherwise says which bond offset does not.
template <int D>
std::string sub_horizon_shortfall(const core::Stencil<D>& stencil, int min_points);

}  // namespace pdmpm::pd
