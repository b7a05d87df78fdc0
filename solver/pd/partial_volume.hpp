#pragma once
// Partial-volume factor β(|ξ|): the fraction of neighbour j's cell that lies
// inside the horizon (docs/discretisation.md).
//  none     β = 1 for |ξ| ≤ δ.
//  seed001  Deryugin et al. 2023 eq 7.2: 1 for |ξ| ≤ δ − Δx/2, (δ + Δx/2 − |ξ|)/Δx up to δ, 0 beyond.
//  extended the same ramp continued to δ + Δx/2 (family reaches δ + Δx/2).
#include <array>

#include "solver/core/named_enum.hpp"

namespace pdmpm::pd {

enum class PartialVolume { none, seed001, extended };
constexpr std::array<EnumName<PartialVolume>, 3> names(PartialVolume) {
  return {{{PartialVolume::none, "none"}, {PartialVolume::seed001, "seed001"}, {PartialVolume::extended, "extended"}}};
}

double partial_volume(PartialVolume pv, double r, double delta, double dx);
// Largest bond length with β > 0, in units of Δx (the family radius).
double family_ratio(PartialVolume pv, double delta, double dx);


}  // namespace pdmpm::pd
