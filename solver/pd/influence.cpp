#include "solver/pd/influence.hpp"

#include <cmath>

namespace pdmpm::pd {

double influence(Influence w, double r, double delta) {
  const double q = r / delta;
  switch (w) {
    case Influence::constant: return 1.0;
    case Influence::triangular: return 1.0 - q;
    case Influence::quadratic: return (1.0 - q * q) * (1.0 - q * q);
    case Influence::semi_elliptical: return 1.0 - q * q;
    case Influence::exponential: return std::exp(-q);
    case Influence::gaussian: return std::exp(-q * q);
    case Influence::inverse_distance: return 1.0 / q;
  }
  return 0.0;
}

std::string_view name(Influence w) {
  switch (w) {
    case Influence::constant: return "constant";
    case Influence::triangular: return "triangular";
    case Influence::quadratic: return "quadratic";
    case Influence::semi_elliptical: return "semi_elliptical";
    case Influence::exponential: return "exponential";
    case Influence::gaussian: return "gaussian";
    case Influence::inverse_distance: return "inverse_distance";
  }
  return "?";
}

std::optional<Influence> parse_influence(std::string_view s) {
  for (Influence w : all_influences)
    if (name(w) == s) return w;
  return std::nullopt;
}

std::string influence_names() {
  std::string out;
  for (Influence w : all_influences) {
    if (!out.empty()) out += ", ";
    out += name(w);
  }
  return out;
}

}  // namespace pdmpm::pd
