#pragma once
// What a constitutive update reads and writes for one material point.
#include "solver/core/state_archive.hpp"
#include "solver/core/types.hpp"

namespace pdmpm::mpm {

// Internal variables carried from step to step (plastic models only use them).
struct PointHistory {
  Mat<3> plastic_strain = Mat<3>::Zero();  // ε_p, unrotated (Lagrangian) log strain, traceless
  double eq_plastic_strain = 0.0;          // ε̄_p = ∫ sqrt(2/3 ε̇_p:ε̇_p) dt
};

// Result of one update.
struct StressResult {
  Mat<3> kirchhoff = Mat<3>::Zero();  // τ = J σ in the current (spatial) frame
  double J = 1.0;                     // volume ratio of the 3D material (thickness/lateral change included)
  double energy = 0.0;                // stored elastic energy per reference volume (J/m³)
  double dissipation = 0.0;           // plastic work of this update per reference volume (J/m³)
  double out_of_plane_strain = 0.0;   // plane stress ε₃₃ / bar lateral ε₂₂ (log strain), else 0
};

}  // namespace pdmpm::mpm

// Nine doubles and one: its bytes are its value, so a checkpoint copies them as they are.
template <>
inline constexpr bool pdmpm::core::kBytesAreValue<pdmpm::mpm::PointHistory> = sizeof(pdmpm::mpm::PointHistory) ==
    10 * sizeof(double);
