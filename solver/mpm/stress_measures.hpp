#pragma once
// Scalar measures of a 3×3 Cauchy stress used for output and failure.
#include <cmath>

#include "solver/core/types.hpp"

namespace pdmpm::mpm {

inline double mean_stress(const Mat<3>& s) { return s.trace() / 3.0; }

// σ_eq = sqrt(3/2 s:s), s = dev σ.
inline double von_mises(const Mat<3>& s) {
  const Mat<3> dev = s - mean_stress(s) * Mat<3>::Identity();
  return std::sqrt(1.5 * (dev.array() * dev.array()).sum());
}

// Stress triaxiality η = σ_m / σ_eq; 0 for a stress-free point, ±∞ never returned:
// a purely hydrostatic state (σ_eq below 1e-12 |σ_m|) reports η = ±1e12.
inline double triaxiality(const Mat<3>& s) {
  const double m = mean_stress(s), q = von_mises(s);
  if (q == 0.0 && m == 0.0) return 0.0;
  if (q <= 1e-12 * std::abs(m)) return m > 0.0 ? 1e12 : -1e12;
  return m / q;
}

// Ductile fracture strain of docs/models/planned.md (Noorian et al. eqs 8–9): ε_f = d₀ exp(c η).
inline double fracture_strain(double d0, double c, double eta) { return d0 * std::exp(c * eta); }

}  // namespace pdmpm::mpm
