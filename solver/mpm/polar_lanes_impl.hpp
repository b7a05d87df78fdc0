#pragma once
// The lane arithmetic of polar_lanes.hpp, compiled once per instruction set (lane_set.hpp;
// lanes.hpp stops any other includer).
#include <cmath>

#include "solver/mpm/lanes.hpp"
#include "solver/mpm/polar_lanes.hpp"
#include "solver/mpm/series_log_exp.hpp"

namespace pdmpm::mpm {
namespace {

template <int W>
inline unsigned polar_log_lanes_by(PolarLanes& in) {
  using V = Lanes<W>;
  using d = typename V::d;
  using m = typename V::m;
  unsigned scalar = 0;
  for (int c0 = 0; c0 < kPolarLanes; c0 += W) {
    const d f00 = V::load(in.f00 + c0), f10 = V::load(in.f10 + c0), f01 = V::load(in.f01 + c0),
            f11 = V::load(in.f11 + c0);
    const d det = f00 * f11 - f10 * f01;
    // R = [c −s; s c] with (c, s) ∥ (F₀₀ + F₁₁, F₁₀ − F₀₁); U = RᵀF symmetrised.
    const d a = f00 + f11, b = f10 - f01;
    const d inv = 1.0 / V::sqrt(a * a + b * b);
    const d c = a * inv, s = b * inv;
    const d u00 = c * f00 + s * f10, u11 = -s * f01 + c * f11;
    const d u01 = c * f01 + s * f11, u10 = -s * f00 + c * f10;
    const d U00 = 0.5 * (u00 + u00), U01 = 0.5 * (u01 + u10), U10 = 0.5 * (u10 + u01), U11 = 0.5 * (u11 + u11);
    // ln U = ½ ln(det U) I + q (U − m I), q = atanh(r/m)/r, by the series of log_spd2.
    const d mean = 0.5 * (U00 + U11), hd = 0.5 * (U00 - U11), off = 0.5 * (U01 + U10);
    const d r = V::sqrt(hd * hd + off * off);
    const d inv_mean = 1.0 / mean, x = r * inv_mean, y = x * x;
    const d q = atanh_over_x_series(y) * inv_mean;
    const m fine = (det > 0.0) & (x < kSeriesLimit);
    // ½ ln det U by series_half_log: the series where it holds, else the library.
    const d z = half_log_argument(det), by_series = half_log_series(z);
    const m near_one = V::select(z < 0.0, -z, z) < kSeriesLimit;
    const unsigned flagged = V::bits(~fine), by_library = V::bits(~near_one) & ~flagged;
    scalar |= flagged << c0;
    const d hl = V::per_lane_where(by_library, V::select(fine, by_series, d{} + 0.0), det,
                                   [](double d_lane) { return 0.5 * std::log(d_lane); });
    V::store(in.c + c0, c);
    V::store(in.s + c0, s);
    V::store(in.l00 + c0, hl + q * hd);
    V::store(in.l11 + c0, hl - q * hd);
    V::store(in.l01 + c0, q * off);
  }
  return scalar;
}

}  // namespace
}  // namespace pdmpm::mpm
