#pragma once
// The lane arithmetic of gimp_lanes.hpp, compiled once per instruction set (lane_set.hpp;
// lanes.hpp stops any other includer).
#include <cmath>

#include "solver/mpm/gimp_lanes.hpp"
#include "solver/mpm/lanes.hpp"

namespace pdmpm::mpm {
namespace {

template <int W>
inline void gimp_lanes_by(const double* x_rel, const double* lp_in, double h, GimpLanes& out) {
  using V = Lanes<W>;
  using d = typename V::d;
  using m = typename V::m;
  const double inv_h = 1.0 / h;  // as GimpScale
  for (int c0 = 0; c0 < kGimpLanes; c0 += W) {
    const d x = V::load(x_rel + c0), lp = V::load(lp_in + c0);
    const d g = x * inv_h, inv_h_lp = inv_h * (1.0 / lp);
    // First node strictly inside the support (x_I > x − h − lp), as weights_1d.
    const d before = V::floor(g - 1.0 - lp * inv_h);
    for (int i = 0; i < W; ++i) out.first[c0 + i] = static_cast<int>(before[i]) + 1;
    const d zero{}, one = zero + 1.0, hv = zero + h, inv_hv = zero + inv_h;
    const d half = 0.5 * inv_h_lp, quarter = 0.25 * inv_h_lp;
    for (int k = 0; k < 3; ++k) {
      const d r = (g - (before + 1.0 + k)) * h;  // x_p − x_I, as weights_1d's (g − (first + k)) h
      const m negative = r < 0.0;
      const d a = V::select(negative, -r, r), sign = V::select(negative, -one, one);
      const m inner = a < lp, middle = a < hv - lp, outer = a < hv + lp;  // inner ⊂ middle ⊂ outer
      const d dist = hv + lp - a;
      // S = c − num·fac (gimp_weight): inner 1 − (r² + lp²)/(2h lp), middle 1 − |r|/h,
      // outer 0 − (−d²)/(4h lp) = d²/(4h lp), outside 0 − 0·1.
      const d c = V::select(middle, one, zero);
      const d num = V::select(inner, r * r + lp * lp, V::select(middle, a, V::select(outer, -(dist * dist), zero)));
      const d fac = V::select(inner, half, V::select(middle, inv_hv, V::select(outer, quarter, one)));
      const d w = c - num * fac;
      // ∂S/∂x (gimp_gradient): inner −r/(h lp), middle −sign/h, outer −sign d/(2h lp), outside 0·1.
      const d gnum = V::select(inner, -r, V::select(middle, -sign, V::select(outer, -sign * dist, zero)));
      const d gfac = V::select(inner, inv_h_lp, V::select(middle, inv_hv, V::select(outer, half, one)));
      const d dw = gnum * gfac;
      V::store(out.w[k] + c0, w);
      V::store(out.dw[k] + c0, dw);
    }
  }
}

}  // namespace
}  // namespace pdmpm::mpm
