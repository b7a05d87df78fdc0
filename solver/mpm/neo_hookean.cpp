#include "solver/mpm/neo_hookean.hpp"

#include <cmath>

#include "solver/core/error.hpp"

namespace pdmpm::mpm {

Mat<3> neo_hookean_kirchhoff(const core::Elastic& m, const Mat<3>& F3, double& J, double& energy) {
  J = F3.determinant();
  if (!(J > 0.0)) throw RunError("neo-Hookean: det F ≤ 0 (particle inverted)");
  const double mu = m.shear(), lambda = m.lame();
  // With G = C − I (small at small strain whatever the rotation): J² − 1 = tr G + I₂(G)
  // + det G and ½ tr(B − I) − ln J = ½ (tr G − log1p(J² − 1)). The first-order terms
  // cancel analytically, so W keeps full relative accuracy at small strain.
  const Mat<3> G = F3.transpose() * F3 - Mat<3>::Identity();
  const double trG = G.trace();
  const double I2 = 0.5 * (trG * trG - (G * G).trace());
  const double x = trG + I2 + G.determinant();  // J² − 1
  const double log1p_x = std::log1p(x);
  const double lnJ = 0.5 * log1p_x;
  // x − log1p(x) by its series where the difference would cancel.
  const double x_minus_log1p =
      std::abs(x) < 1e-3 ? x * x * (0.5 - x / 3.0 + x * x / 4.0 - x * x * x / 5.0) : x - log1p_x;
  energy = 0.5 * mu * (x_minus_log1p - I2 - G.determinant()) + 0.5 * lambda * lnJ * lnJ;
  const Mat<3> B_minus_I = F3 * F3.transpose() - Mat<3>::Identity();
  return mu * B_minus_I + lambda * lnJ * Mat<3>::Identity();
}

}  // namespace pdmpm::mpm
