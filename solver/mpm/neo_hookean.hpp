#pragma once
// Compressible neo-Hookean solid (as used by Wallstedt & Guilkey 2008 and the
// generalized vortex of Kamojjala et al. 2015):
//   τ = J σ = μ (B − I) + λ ln J I,   W = μ/2 (tr B − 3) − μ ln J + λ/2 (ln J)².
#include "solver/core/types.hpp"
#include "solver/core/material.hpp"

namespace pdmpm::mpm {

// F3 is the full 3×3 deformation gradient (out-of-plane stretch 1 in plane strain
// and uniaxial strain). Returns τ; sets J and the energy density W.
Mat<3> neo_hookean_kirchhoff(const core::Elastic& m, const Mat<3>& F3, double& J, double& energy);

}  // namespace pdmpm::mpm
