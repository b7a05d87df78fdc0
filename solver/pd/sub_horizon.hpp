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
// The coefficients depend on the reference positions and on which bonds are live. The layout
// is fixed when built: every bond side of the reference family has one slot per point of its
// largest sub-horizon (all its reference bonds live); a point outside the current sub-horizon
// has coefficient zero (it adds nothing to H or to the forces). When the live set changes (bonds
// broke, or a step was rejected) update() fits again, in place, only the sides whose sub-horizon
// can have changed (the rule is in sub_horizon.cpp): no copy of the others, no new layout.
#include <cstdint>
#include <string>
#include <vector>

#include "solver/pd/system.hpp"

namespace pdmpm::pd {

// The bond flags of a distributed run's halo particles: a bond i→j whose j is in the halo has
// a sub-horizon that reads j's bonds, some to other halo particles, which live on other
// processes. flags[g · stencil + r] is the trial flag byte of ghost g's (store index
// n_real + g) side with stencil index r, kNoBond where it has none. Empty in one process.
struct HaloBonds {
  static constexpr std::uint8_t kNoBond = 0xFF;
  int stencil = 0;
  std::vector<std::uint8_t> flags;
  bool empty() const { return flags.empty(); }
};

template <int D>
struct SubHorizon {
  // Per bond side b: its slots [begin[b], begin[b + 1]) (none outside the reference family).
  std::vector<BondIndex> begin;
  std::vector<Index> point;
  std::vector<Vec<D>> coef;
  std::vector<std::uint8_t> axial;  // 1: too few points or degenerate, the axial fallback
  // The plain fit (weights V_l, ends not weighted) whose residual r_l = u_l − ū − H̃ (x_l − x̄)
  // HpdOptions::stabilization penalises: per slot the point's volume V_l (0: not in the sub-horizon
  // now, or no residual), per bond side x̄ = Σ V_l x_l / Σ V_l relative to x_i, K̃⁻¹ with
  // K̃ = Σ_l V_l (x_l − x̄) ⊗ (x_l − x̄), 1 / Σ_l V_l and 1 / tr K̃; zeros for dead and axial sides.
  std::vector<double> volume;
  std::vector<Vec<D>> centroid;
  std::vector<Mat<D>> volume_inverse;
  std::vector<double> inv_volume, inv_second_moment;
  // The same slots by point, each with its bond side and a copy of its coefficient: particle k
  // (real or halo) appears in [at_begin[k], at_begin[k + 1]) (the force loop gathers them in order; copies, not
  // indices, so that it reads memory in sequence); entry_at[e] is slot e's place there.
  std::vector<BondIndex> at_begin;
  std::vector<BondIndex> at_bond;
  std::vector<Vec<D>> at_coef;
  std::vector<BondIndex> entry_at;
  std::vector<std::uint8_t> built_live;  // live bit of every bond side when last fitted
  // A distributed run's halo bonds (set before build and update), and as last fitted.
  HaloBonds halo;
  std::vector<std::uint8_t> built_halo;
  std::int64_t n_axial = 0;        // live bond sides on the fallback
  std::vector<int> diff, reverse;  // stencil tables of the fits (sub_horizon.cpp)

  // The layout for the reference family, fitted for the live bonds (`halo`: a distributed
  // run's halo bonds).
  static SubHorizon build(const System<D>& sys, int min_points, double end_weight, const HaloBonds& halo = {});
  // Fits again the sides the live-bit changes since the last fit can reach; the result equals
  // build() on the same system bit for bit (the reference family must not have changed).
  void update(const System<D>& sys, int min_points, double end_weight);
  // Whether the live bonds differ from those the coefficients were built for.
  bool stale(const System<D>& sys) const;
};

// Empty when every bond of a full (interior) family has a sub-horizon of ≥ min_points points
// spanning D dimensions on this stencil; otherwise says which bond offset does not.
template <int D>
std::string sub_horizon_shortfall(const core::Stencil<D>& stencil, int min_points);

}  // namespace pdmpm::pd
