#pragma once
// MPM-only state of each particle, in arrays indexed like core::Particles so a
// particle can switch between MPM and PD in place (the PD solver ignores these). F,
// τ and the plastic history are kept entry by entry (matrix_arrays.hpp): the stress
// update reads and writes them eight particles at a time.
#include <cstdint>
#include <vector>

#include "solver/core/types.hpp"
#include "solver/mpm/material_point.hpp"
#include "solver/mpm/matrix_arrays.hpp"
#include "solver/mpm/shape_function.hpp"

namespace pdmpm::mpm {

template <int D>
struct ParticleState {
  std::vector<double> mass;                  // m_p = ρ V₀ (kg)
  std::vector<Vec<D>> half_width;            // uGIMP half-widths lp (m)
  MatrixArrays<D, D> F;                      // deformation gradient
  MatrixArrays<3, 3> kirchhoff;              // τ = J σ (Pa), drives the grid forces
  std::vector<double> J;                     // volume ratio (3D, thickness change included)
  std::vector<double> out_of_plane_strain;   // plane stress ε₃₃ / bar lateral strain
  MatrixArrays<3, 3> plastic_strain;         // ε_p (PointHistory::plastic_strain)
  std::vector<double> eq_plastic_strain;     // ε̄_p
  std::vector<double> eq_plastic_hardening;  // ε̂_p used by hardening/failure (non-local models only)
  std::vector<double> energy;                // stored elastic energy density (J/m³ of V₀)
  std::vector<double> dissipation;           // accumulated plastic work density (J/m³ of V₀)
  std::vector<double> damage;                // accumulated ∫ dε̄_p/ε_f (rule "accumulated")
  std::vector<std::uint8_t> failed;          // 1 once the ductile criterion was met
  std::vector<std::uint8_t> initialised;     // 0 for slots not yet set up (particles added later)

  Index size() const { return static_cast<Index>(mass.size()); }
  // Cauchy stress σ = τ / J (Pa), 3×3 (σ₃₃ of plane strain included): derived when
  // asked, not stored — the step needs only τ.
  Mat<3> cauchy(Index p) const { return kirchhoff.get(p) / J[p]; }
  PointHistory history(Index p) const { return {plastic_strain.get(p), eq_plastic_strain[p]}; }
  void set_history(Index p, const PointHistory& h) {
    plastic_strain.set(p, h.plastic_strain);
    eq_plastic_strain[p] = h.eq_plastic_strain;
  }
  void resize(Index n) {
    const std::size_t N = static_cast<std::size_t>(n);
    mass.resize(N, 0.0);
    half_width.resize(N, Vec<D>::Zero());
    F.resize(n, Mat<D>::Identity());
    kirchhoff.resize(n, Mat<3>::Zero());
    J.resize(N, 1.0);
    out_of_plane_strain.resize(N, 0.0);
    plastic_strain.resize(n, Mat<3>::Zero());
    eq_plastic_strain.resize(N, 0.0);
    eq_plastic_hardening.resize(N, 0.0);
    energy.resize(N, 0.0);
    dissipation.resize(N, 0.0);
    damage.resize(N, 0.0);
    failed.resize(N, 0);
    initialised.resize(N, 0);
  }
};

}  // namespace pdmpm::mpm
