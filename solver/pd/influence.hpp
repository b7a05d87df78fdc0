#pragma once
// Influence functions ω(r) of Deryugin et al. 2023 table 4.1, plus ω = 1/r (the "spherical"
// LPS choice of Deryugin et al. 2023 §5). All take r = |ξ| and the horizon δ.
#include <array>

#include "solver/core/named_enum.hpp"

namespace pdmpm::pd {

enum class Influence { constant, triangular, quadratic, semi_elliptical, exponential, gaussian, inverse_distance };

constexpr std::array<EnumName<Influence>, 7> names(Influence) {
  return {{{Influence::constant, "constant"},
           {Influence::triangular, "triangular"},
           {Influence::quadratic, "quadratic"},
           {Influence::semi_elliptical, "semi_elliptical"},
           {Influence::exponential, "exponential"},
           {Influence::gaussian, "gaussian"},
           {Influence::inverse_distance, "inverse_distance"}}};
}
inline constexpr auto all_influences = enum_values<Influence>();

// ω(r; δ). For inverse_distance, ω = δ/r (scaled by δ so ω is dimensionless;
// every constant below is derived with the same scaling, so results are unchanged).
double influence(Influence w, double r, double delta);


}  // namespace pdmpm::pd
