#pragma once
// Finite-strain kinematics of one material point: the polar decomposition
// F = R U with the Lagrangian logarithmic strain ln U, and the incrementally
// objective update of F from the velocity gradient.
#include "solver/core/types.hpp"

namespace pdmpm::mpm {

template <int D>
struct PolarLog {
  Mat<D> R;      // rotation (proper orthogonal)
  Mat<D> log_U;  // ln U, symmetric
};

// Requires det F > 0 (throws RunError otherwise: the particle has inverted).
template <int D>
PolarLog<D> polar_log(const Mat<D>& F);

// ΔF over a step with constant velocity gradient L: the Cayley (midpoint,
// Hughes & Winget 1980) form (I − ½ L dt)⁻¹ (I + ½ L dt). It is second-order
// accurate and exactly orthogonal when L is skew, so a rigid rotation leaves
// U, and hence every stress, unchanged to round-off.
template <int D>
Mat<D> cayley_increment(const Mat<D>& L, double dt);

}  // namespace pdmpm::mpm
