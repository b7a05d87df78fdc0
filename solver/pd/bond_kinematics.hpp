#pragma once
// Deformed bond length and extension. e = |ξ+η| − |ξ| is computed as
// (2ξ·η + η·η) / (|ξ+η| + |ξ|): no cancellation, so tiny strains (patch tests,
// small-amplitude waves) keep full relative precision.
#include <cmath>

#include "solver/core/types.hpp"

namespace pdmpm::pd {

template <int D>
struct DeformedBond {
  Vec<D> y;     // ξ + η
  double l;     // |ξ + η|
  double e;     // extension |ξ+η| − |ξ|
};

template <int D>
inline DeformedBond<D> deform(const Vec<D>& xi, double L, const Vec<D>& eta) {
  DeformedBond<D> b;
  b.y = xi + eta;
  b.l = b.y.norm();
  b.e = (2.0 * xi.dot(eta) + eta.squaredNorm()) / (b.l + L);
  return b;
}

}  // namespace pdmpm::pd
