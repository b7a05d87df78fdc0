#include "solver/mpm/neo_hookean.hpp"

#include <cmath>

#include "solver/core/error.hpp"

namespace pdmpm::mpm {

Mat<3> neo_hookean_kirchhoff(const Material& m, const Mat<3>& F3, double& J, double& energy) {
  J = F3.determinant();
  if (!(J > 0.0)) throw RunError("neo-Hookean: det F ≤ 0 (particle inverted)");
  const double mu = m.shear(), lambda = m.lame(), lnJ = std::log(J);
  const Mat<3> B = F3 * F3.transpose();
  energy = 0.5 * mu * (B.trace() - 3.0) - mu * lnJ + 0.5 * lambda * lnJ * lnJ;
  return mu * (B - Mat<3>::Identity()) + lambda * lnJ * Mat<3>::Identity();
}

}  // namespace pdmpm::mpm
