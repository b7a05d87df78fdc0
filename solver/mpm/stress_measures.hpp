#pragma once
// Scalar measures of a 3×3 Cauchy stress used for output and failure.
#include <cmath>

#include "solver/core/types.hpp"

namespace pdmpm::mpm {

// The sums below are written out in a fixed order — the one Eigen's reductions take in
// the generic x86-64 build (trace: s₀₀ + (s₁₁ + s₂₂); s:s: pairs of the column-major
// elements, then the ninth) — so every build gives the same bits, and the plane-stress
// lanes (ductile_lanes.hpp) can repeat them.
inline double mean_stress(const Mat<3>& s) { return (s(0, 0) + (s(1, 1) + s(2, 2))) / 3.0; }

// σ_eq = sqrt(3/2 s:s), s = dev σ.
inline double von_mises(const Mat<3>& s) {
  const double m = mean_stress(s);
  double sq[9];  // column-major squares of dev σ = σ − m I
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) {
      const double d = s(r, c) - m * (r == c ? 1.0 : 0.0);
      sq[3 * c + r] = d * d;
    }
  const double even = (sq[0] + sq[2]) + (sq[4] + sq[6]), odd = (sq[1] + sq[3]) + (sq[5] + sq[7]);
  return std::sqrt(1.5 * ((even + odd) + sq[8]));
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
