#pragma once
// Influence functions ω(r) of Deryugin et al. 2023 table 4.1, plus ω = 1/r (the "spherical"
// LPS choice of Deryugin et al. 2023 §5). All take r = |ξ| and the horizon δ.
#include <array>
#include <optional>
#include <string>
#include <string_view>

namespace pdmpm::pd {

enum class Influence { constant, triangular, quadratic, semi_elliptical, exponential, gaussian, inverse_distance };

inline constexpr std::array<Influence, 7> all_influences = {
    Influence::constant,    Influence::triangular, Influence::quadratic,       Influence::semi_elliptical,
    Influence::exponential, Influence::gaussian,   Influence::inverse_distance};

// ω(r; δ). For inverse_distance, ω = δ/r (scaled by δ so ω is dimensionless;
// every constant below is derived with the same scaling, so results are unchanged).
double influence(Influence w, double r, double delta);

std::string_view name(Influence w);
std::optional<Influence> parse_influence(std::string_view s);
std::string influence_names();  // "constant, triangular, …" for error messages

}  // namespace pdmpm::pd
