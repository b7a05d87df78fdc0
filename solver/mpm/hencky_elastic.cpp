#include "solver/mpm/hencky_elastic.hpp"

namespace pdmpm::mpm {

Mat<3> hooke_3d(const core::Elastic& m, const Mat<3>& eps) {
  return m.lame() * eps.trace() * Mat<3>::Identity() + 2.0 * m.shear() * eps;
}

Mat<3> hooke_plane_stress(const core::Elastic& m, const Mat<3>& eps, double& eps33) {
  const double c = m.E / (1.0 - m.nu * m.nu);
  const double tr = eps(0, 0) + eps(1, 1);
  Mat<3> T = Mat<3>::Zero();
  T(0, 0) = c * ((1.0 - m.nu) * eps(0, 0) + m.nu * tr);
  T(1, 1) = c * ((1.0 - m.nu) * eps(1, 1) + m.nu * tr);
  T(0, 1) = T(1, 0) = c * (1.0 - m.nu) * eps(0, 1);
  eps33 = -m.nu / (1.0 - m.nu) * tr;
  return T;
}

Mat<3> hooke_bar(const core::Elastic& m, const Mat<3>& eps, double& lateral) {
  Mat<3> T = Mat<3>::Zero();
  T(0, 0) = m.E * eps(0, 0);
  lateral = -m.nu * eps(0, 0);
  return T;
}

}  // namespace pdmpm::mpm
