#include "solver/mpm/hencky_elastic.hpp"

namespace pdmpm::mpm {

Mat<3> hooke_plane_stress(const core::Elastic& m, const Mat<3>& eps, double& eps33) {
  const PlaneStressHooke h =
      hooke_plane_stress(m.E / (1.0 - m.nu * m.nu), m.nu, -m.nu / (1.0 - m.nu), eps(0, 0), eps(1, 1), eps(0, 1));
  Mat<3> T = Mat<3>::Zero();
  T(0, 0) = h.t00;
  T(1, 1) = h.t11;
  T(0, 1) = T(1, 0) = h.t01;
  eps33 = h.e33;
  return T;
}

Mat<3> hooke_bar(const core::Elastic& m, const Mat<3>& eps, double& lateral) {
  Mat<3> T = Mat<3>::Zero();
  T(0, 0) = m.E * eps(0, 0);
  lateral = -m.nu * eps(0, 0);
  return T;
}

}  // namespace pdmpm::mpm
