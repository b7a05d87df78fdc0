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

}  // namespace pdmpm::pd
