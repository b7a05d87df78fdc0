#pragma once
// The uniform square/cubic lattice every particle lives on (docs/discretisation.md). Particles
// carry integer site coordinates, so family membership (|ξ| ≤ δ) is decided
// exactly on integers and bond vectors ξ are exact multiples of the spacing.
#include <cmath>

#include "solver/core/types.hpp"

namespace pdmpm::core {

template <int D>
struct Lattice {
  Vec<D> origin = Vec<D>::Zero();  // position of site (0,…,0)
  double spacing = 1.0;            // Δx

  Vec<D> position(const IVec<D>& site) const { return origin + spacing * site.template cast<double>(); }
  // Nearest site to a point (ties round half away from zero).
  IVec<D> nearest_site(const Vec<D>& x) const {
    IVec<D> s;
    for (int a = 0; a < D; ++a) s[a] = static_cast<std::int32_t>(std::lround((x[a] - origin[a]) / spacing));
    return s;
  }
};

}  // namespace pdmpm::core
