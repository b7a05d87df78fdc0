#include "solver/pd/stress.hpp"

#include <cmath>

namespace pdmpm::pd {
namespace {

// 3D stress (xx, yy, zz, xy, yz, xz) from the in-plane/3D small strain.
template <int D>
Tensor6 hooke(const Mat<D>& eps, const core::Elastic& m, core::Setting s) {
  Tensor6 out{};
  const double lam = m.lame(), G = m.shear();
  if constexpr (D == 1) {
    out[0] = m.E * eps(0, 0);
  } else if constexpr (D == 2) {
    const double tr = eps.trace();
    if (s == core::Setting::plane_stress) {
      const double k = m.E / (1.0 - m.nu * m.nu);
      out[0] = k * (eps(0, 0) + m.nu * eps(1, 1));
      out[1] = k * (eps(1, 1) + m.nu * eps(0, 0));
      out[3] = k * (1.0 - m.nu) * eps(0, 1);
    } else {
      out[0] = lam * tr + 2.0 * G * eps(0, 0);
      out[1] = lam * tr + 2.0 * G * eps(1, 1);
      out[2] = lam * tr;
      out[3] = 2.0 * G * eps(0, 1);
    }
  } else {
    const double tr = eps.trace();
    out = {lam * tr + 2.0 * G * eps(0, 0),
           lam * tr + 2.0 * G * eps(1, 1),
           lam * tr + 2.0 * G * eps(2, 2),
           2.0 * G * eps(0, 1),
           2.0 * G * eps(1, 2),
           2.0 * G * eps(0, 2)};
  }
  return out;
}

}  // namespace

template <int D>
std::vector<Tensor6> particle_stress(const System<D>& sys) {
  const auto& p = sys.particles;
  const auto& t = sys.table;
  std::vector<Tensor6> out(p.n_real, Tensor6{});
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < p.n_real; ++i) {
    Mat<D> K = Mat<D>::Zero(), N = Mat<D>::Zero();
    sys.for_each_live_bond(i, [&](BondIndex, Index j, int k) {
      const double w = t.weight[k] * p.volume[j];
      K += w * t.xi[k] * t.xi[k].transpose();
      N += w * (p.u[j] - p.u[i]) * t.xi[k].transpose();
    });
    // A particle that has lost the bonds spanning its neighbourhood has no
    // defined strain; report zero stress rather than a singular solve.
    const double scale = std::pow(K.trace() / D, D);
    if (!(std::abs(K.determinant()) > 1e-10 * scale)) continue;
    const Mat<D> H = N * K.inverse();
    const Mat<D> eps = 0.5 * (H + H.transpose());
    out[i] = hooke<D>(eps, sys.material, sys.setting);
  }
  return out;
}

double von_mises(const Tensor6& s) {
  const double a = s[0] - s[1], b = s[1] - s[2], c = s[2] - s[0];
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
}

double triaxiality(const Tensor6& s) {
  const double eq = von_mises(s);
  return eq > 0.0 ? (s[0] + s[1] + s[2]) / 3.0 / eq : 0.0;
}

template std::vector<Tensor6> particle_stress<1>(const System<1>&);
template std::vector<Tensor6> particle_stress<2>(const System<2>&);
template std::vector<Tensor6> particle_stress<3>(const System<3>&);

}  // namespace pdmpm::pd
