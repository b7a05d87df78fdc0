#pragma once
// Isotropic Hooke's law between a logarithmic strain ε and the rotated Kirchhoff
// stress T (Hencky elasticity; small-strain linear elasticity to first order).
// Strains and stresses are 3×3 in the unrotated frame; each setting fixes the
// out-of-plane components its own way.
#include "solver/core/types.hpp"
#include "solver/core/material.hpp"

namespace pdmpm::mpm {

// 3D-type settings (solid3d, plane_strain, uniaxial_strain): T = λ tr ε I + 2μ ε.
inline Mat<3> hooke_3d(double lame, double shear, const Mat<3>& eps) {
  return lame * eps.trace() * Mat<3>::Identity() + 2.0 * shear * eps;
}
inline Mat<3> hooke_3d(const core::Elastic& m, const Mat<3>& eps) { return hooke_3d(m.lame(), m.shear(), eps); }

// Plane stress on the in-plane strains (e₀₁ the tensor shear) with c = E/(1 − ν²) and
// k = −ν/(1 − ν): the in-plane stresses and the elastic ε₃₃.
struct PlaneStressHooke {
  double t00, t11, t01, e33;
};
inline PlaneStressHooke hooke_plane_stress(double c, double nu, double k, double e00, double e11, double e01) {
  const double tr = e00 + e11;
  return {c * ((1.0 - nu) * e00 + nu * tr), c * ((1.0 - nu) * e11 + nu * tr), c * (1.0 - nu) * e01, k * tr};
}

// Plane stress: in-plane 2×2 block of eps used, T₃₃ = 0; returns T and sets the
// elastic out-of-plane strain ε₃₃ = −ν/(1−ν) (ε₁₁ + ε₂₂).
Mat<3> hooke_plane_stress(const core::Elastic& m, const Mat<3>& eps, double& eps33);

// Bar (uniaxial stress): T₁₁ = E ε₁₁, lateral elastic strain −ν ε₁₁.
Mat<3> hooke_bar(const core::Elastic& m, const Mat<3>& eps, double& lateral);

// ½ T : ε_e, the stored energy of an elastic strain and its stress.
inline double elastic_energy(const Mat<3>& T, const Mat<3>& eps_e) { return 0.5 * (T.array() * eps_e.array()).sum(); }

}  // namespace pdmpm::mpm
