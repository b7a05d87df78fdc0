#include "solver/hybrid/settings.hpp"

#include <cmath>
#include <sstream>

#include "solver/core/error.hpp"

namespace pdmpm::hybrid {

void Settings::validate(const std::string& file) const {
  radii.validate(file);
  if (shrink_every < 1) {
    std::ostringstream m;
    m << "must be an integer ≥ 1 (got " << shrink_every << ")";
    throw InputError(file, "hybrid.shrink_every", m.str());
  }
}

}  // namespace pdmpm::hybrid
