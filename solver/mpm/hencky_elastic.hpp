#pragma once
// Isotropic Hooke's law between a logarithmic strain ε and the rotated Kirchhoff
// stress T (Hencky elasticity; small-strain linear elasticity to first order).
// Strains and stresses are 3×3 in the unrotated frame; each setting fixes the
// out-of-plane components its own way.
#include "solver/core/types.hpp"
#include "solver/core/material.hpp"

namespace pdmpm::mpm {

// 3D-type settings (solid3d, plane_strain, uniaxial_strain): T = λ tr ε I + 2μ ε.
Mat<3> hooke_3d(const core::Elastic& m, const Mat<3>& eps);

// Plane stress: in-plane 2×2 block of eps used, T₃₃ = 0; returns T and sets the
// elastic out-of-plane strain ε₃₃ = −ν/(1−ν) (ε₁₁ + ε₂₂).
Mat<3> hooke_plane_stress(const core::Elastic& m, const Mat<3>& eps, double& eps33);

// Bar (uniaxial stress): T₁₁ = E ε₁₁, lateral elastic strain −ν ε₁₁.
Mat<3> hooke_bar(const core::Elastic& m, const Mat<3>& eps, double& lateral);

// ½ T : ε_e, the stored energy of an elastic strain and its stress.
inline double elastic_energy(const Mat<3>& T, const Mat<3>& eps_e) { return 0.5 * (T.array() * eps_e.array()).sum(); }

}  // namespace pdmpm::mpm
