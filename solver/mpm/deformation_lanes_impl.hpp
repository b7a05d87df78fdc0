#pragma once
// The lane arithmetic of deformation_lanes.hpp, compiled once per instruction set (lane_set.hpp;
// lanes.hpp stops any other includer).
#include "solver/mpm/deformation_lanes.hpp"
#include "solver/mpm/lanes.hpp"

namespace pdmpm::mpm {
namespace {

template <int W>
inline void advance_deformation_by(DeformationLanes& in, double dt) {
  using V = Lanes<W>;
  using d = typename V::d;
  const double h = 0.5 * dt;
  for (int c0 = 0; c0 < kDeformationLanes; c0 += W) {
    const d L00 = V::load(in.l00 + c0), L01 = V::load(in.l01 + c0), L10 = V::load(in.l10 + c0);
    const d L11 = V::load(in.l11 + c0);
    // A = I − ½Δt L, B = I + ½Δt L, C = A⁻¹ B (cayley_increment<2>).
    const d a00 = 1.0 - h * L00, a01 = 0.0 - h * L01, a10 = 0.0 - h * L10, a11 = 1.0 - h * L11;
    const d b00 = 1.0 + h * L00, b01 = 0.0 + h * L01, b10 = 0.0 + h * L10, b11 = 1.0 + h * L11;
    const d inv_det = 1.0 / (a00 * a11 - a10 * a01);
    const d i00 = a11 * inv_det, i01 = -a01 * inv_det, i10 = -a10 * inv_det, i11 = a00 * inv_det;
    const d c00 = i00 * b00 + i01 * b10, c01 = i00 * b01 + i01 * b11;
    const d c10 = i10 * b00 + i11 * b10, c11 = i10 * b01 + i11 * b11;
    const d F00 = V::load(in.f00 + c0), F01 = V::load(in.f01 + c0), F10 = V::load(in.f10 + c0);
    const d F11 = V::load(in.f11 + c0);
    V::store(in.f00 + c0, c00 * F00 + c01 * F10);
    V::store(in.f01 + c0, c00 * F01 + c01 * F11);
    V::store(in.f10 + c0, c10 * F00 + c11 * F10);
    V::store(in.f11 + c0, c10 * F01 + c11 * F11);
  }
}

}  // namespace
}  // namespace pdmpm::mpm
