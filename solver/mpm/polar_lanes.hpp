#pragma once
// polar_log<2> (kinematics.hpp) of eight deformation gradients at once. Each lane
// does polar_log<2>'s arithmetic — the square roots and divisions in vector
// instructions, the logarithm by the same library call per lane — so the bits are
// the scalar function's. A lane whose F is inverted (det F ≤ 0, or not finite) or
// whose ln U leaves the series' range (r/m ≥ 0.1, strain differences above ~10 %)
// is flagged instead, for the caller to hand to polar_log<2> itself.
// verification/unit/mpm/polar_lanes_test.cpp compares the lanes with polar_log<2>.
#include "solver/mpm/lane_variant.hpp"

namespace pdmpm::mpm {

inline constexpr int kPolarLanes = 8;

// F = [f00 f01; f10 f11] per lane in; R = [c −s; s c] and ln U = [l00 l01; l01 l11] out.
struct PolarLanes {
  double f00[kPolarLanes], f10[kPolarLanes], f01[kPolarLanes], f11[kPolarLanes];
  double c[kPolarLanes], s[kPolarLanes], l00[kPolarLanes], l01[kPolarLanes], l11[kPolarLanes];
};

// Returns a bit per lane (bit l: lane l) the caller must compute with polar_log<2>.
unsigned polar_log_lanes(PolarLanes& lanes);

using PolarLanesFunction = unsigned (*)(PolarLanes&);
std::vector<LaneVariant<PolarLanesFunction>> polar_lanes_variants();

}  // namespace pdmpm::mpm
