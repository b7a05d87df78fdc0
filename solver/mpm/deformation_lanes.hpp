#pragma once
// The 2D deformation gradient update F ← cayley_increment<2>(L, Δt) F (kinematics.hpp)
// of eight particles at once: the increment's 2 × 2 inverse, its one division per
// point in vector instructions, by the scalar function's arithmetic, so the bits are
// its. In a particle-by-particle loop each division sat in the chain between the
// grid's velocities and the next stage.
// verification/unit/mpm/deformation_lanes_test.cpp compares the lanes with the scalar code.
#include "solver/mpm/lane_variant.hpp"

namespace pdmpm::mpm {

inline constexpr int kDeformationLanes = 8;

// Per lane in: the velocity gradient L = [l00 l01; l10 l11] and F = [f00 f01; f10 f11];
// out: F updated in place.
struct DeformationLanes {
  double l00[kDeformationLanes], l01[kDeformationLanes], l10[kDeformationLanes], l11[kDeformationLanes];
  double f00[kDeformationLanes], f01[kDeformationLanes], f10[kDeformationLanes], f11[kDeformationLanes];
};

void advance_deformation_lanes(DeformationLanes& lanes, double dt);

using DeformationLanesFunction = void (*)(DeformationLanes&, double);
std::vector<LaneVariant<DeformationLanesFunction>> deformation_lanes_variants();

}  // namespace pdmpm::mpm
