#pragma once
// The lane arithmetic of ductile_lanes.hpp, compiled once per instruction set (lane_set.hpp;
// lanes.hpp stops any other includer).
#include <cmath>

#include "solver/mpm/ductile_lanes.hpp"
#include "solver/mpm/lanes.hpp"

namespace pdmpm::mpm {
namespace {

template <int W>
inline void fracture_strain_lanes_by(double d0, double c, const PlaneStressLanes& in, unsigned needed, double* out) {
  using V = Lanes<W>;
  using d = typename V::d;
  for (int c0 = 0; c0 < kLawLanes; c0 += W) {
    const d J = V::load(in.J + c0);
    const d s00 = V::load(in.k00 + c0) / J, s10 = V::load(in.k10 + c0) / J, s01 = V::load(in.k01 + c0) / J,
            s11 = V::load(in.k11 + c0) / J;
    const d s_zero = d{} / J;  // σ's elements where τ is zero: +0 / J, as the scalar division gives
    // mean_stress and von_mises (stress_measures.hpp), term by term.
    const d mean = (s00 + (s11 + s_zero)) / 3.0;
    const d off = s_zero - mean * 0.0;  // dev σ off the diagonal where σ is zero
    const d dev00 = s00 - mean * 1.0, dev11 = s11 - mean * 1.0, dev22 = s_zero - mean * 1.0;
    const d dev10 = s10 - mean * 0.0, dev01 = s01 - mean * 0.0;
    const d even = (dev00 * dev00 + off * off) + (dev11 * dev11 + off * off);
    const d odd = (dev10 * dev10 + dev01 * dev01) + (off * off + off * off);
    const d q = V::sqrt(1.5 * ((even + odd) + dev22 * dev22));
    // triaxiality: 0 for a stress-free point, ±1e12 for a hydrostatic one (which plane
    // stress cannot reach; kept so each lane is the scalar function).
    d eta = mean / q;
    eta =
        V::select(q <= 1e-12 * V::select(mean < 0.0, -mean, mean), V::select(mean > 0.0, d{} + 1e12, d{} - 1e12), eta);
    eta = V::select((q == 0.0) & (mean == 0.0), d{} + 0.0, eta);
    double e[W];
    for (int i = 0; i < W; ++i) e[i] = needed >> (c0 + i) & 1u ? d0 * std::exp(c * eta[i]) : d0;
    V::store(out + c0, V::load(e));
  }
}

}  // namespace
}  // namespace pdmpm::mpm
