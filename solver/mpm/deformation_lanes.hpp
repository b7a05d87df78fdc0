#pragma once
// The 2D deformation gradient update F ← cayley_increment<2>(L, Δt) F (kinematics.hpp)
// of eight particles at once: the increment's 2 × 2 inverse, its one division per
// point in vector instructions, by the scalar function's arithmetic, so the bits are
// its. In a particle-by-particle loop each division sat in the chain between the
// grid's velocities and the next stage.
// The velocity gradient that drives it, L = Σ v_I ⊗ ∇S_I over a 3 × 3 stencil, is
// gathered into the lanes a stencil row (three nodes' x, y) per instruction, the nodes
// summed in the scalar loop's order (Simulation<2>::velocity_gradient), so its bits too.
// verification/unit/mpm/deformation_lanes_test.cpp compares the lanes with the scalar code.
#include <vector>

#include "solver/core/types.hpp"
#include "solver/mpm/lane_variant.hpp"
#include "solver/mpm/shape_function.hpp"

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

// l00 … l11 of lane l from stencil[min(l, n − 1)] (3 × 3 nodes; a last group of fewer
// than eight repeats its last particle) and the nodes' velocities; row_stride = nodes
// per grid row.
void velocity_gradient_lanes(DeformationLanes& lanes, const Stencil<2>* stencil, int n, const Vec<2>* grid_velocity,
                             Index row_stride);

using VelocityGradientLanesFunction = void (*)(DeformationLanes&, const Stencil<2>*, int, const Vec<2>*, Index);
std::vector<LaneVariant<VelocityGradientLanesFunction>> velocity_gradient_lanes_variants();

// The 3D velocity gradient L = Σ v_I ⊗ ∇S_I of one particle over its 3 × 3 × 3 stencil, a
// stencil row (three nodes' x, y, z) per instruction and the nodes added in the scalar
// loop's order (Simulation<3>::velocity_gradient), so its bits; stride = node index
// steps along x (1), y and z.
Mat<3> velocity_gradient_rows3(const Stencil<3>& stencil, const Vec<3>* grid_velocity, const IVec<3>& stride);

using VelocityGradientRows3Function = Mat<3> (*)(const Stencil<3>&, const Vec<3>*, const IVec<3>&);
std::vector<LaneVariant<VelocityGradientRows3Function>> velocity_gradient_rows3_variants();

}  // namespace pdmpm::mpm
