#pragma once
// Stress output (docs/models/lps.md): non-local deformation gradient from intact bonds,
//   F − I = (Σ ω β η⊗ξ V_j)(Σ ω β ξ⊗ξ V_j)⁻¹,
// small strain ε = sym(F − I) and Hooke's law for the setting. Written as the
// 3D tensor (xx, yy, zz, xy, yz, xz) so every dimension shares one format.
#include <array>
#include <vector>

#include "solver/pd/system.hpp"

namespace pdmpm::pd {

using Tensor6 = std::array<double, 6>;

// The small-strain state behind the stress output of one particle.
template <int D>
struct ParticleStrain {
  Mat<D> grad_u = Mat<D>::Zero();  // F − I from the intact bonds (zero where undefined)
  Tensor6 stress{};                // Hooke's law of sym(F − I) for the setting
  double energy = 0.0;             // ½ σ : ε (J/m³), the elastic energy density of that strain
};

template <int D>
ParticleStrain<D> particle_strain(const System<D>& sys, Index i);
template <int D>
std::vector<ParticleStrain<D>> particle_strain(const System<D>& sys);
template <int D>
std::vector<Tensor6> particle_stress(const System<D>& sys);

double von_mises(const Tensor6& s);
// Stress triaxiality η = σ_m / σ_eq (0 where σ_eq = 0).
double triaxiality(const Tensor6& s);

}  // namespace pdmpm::pd
