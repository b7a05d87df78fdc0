#include "solver/mpm/ductile_lanes.hpp"

#include <cmath>

namespace pdmpm::mpm {

unsigned lanes_needing_fracture_strain(const core::DuctileFailure& rule, const PlaneStressLanes& law, int n) {
  const unsigned all = n >= 32 ? ~0u : (1u << n) - 1u;
  if (std::abs(rule.c) * (2.0 / 3.0) > 700.0) return all;  // e^{cη} may round to zero
  if (rule.rule == core::FailureRule::accumulated) return law.yielded & all;
  unsigned strained = 0;
  for (int l = 0; l < n; ++l) strained |= static_cast<unsigned>(law.alpha[l] > 0.0) << l;
  return (law.yielded | strained) & all;
}

}  // namespace pdmpm::mpm
