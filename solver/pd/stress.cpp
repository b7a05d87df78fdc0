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

// σ : ε of the 3D stress and the in-plane/3D strain (ε_zz of plane stress does no work: σ_zz = 0).
template <int D>
double double_contraction(const Tensor6& s, const Mat<D>& eps) {
  if constexpr (D == 1) {
    return s[0] * eps(0, 0);
  } else if constexpr (D == 2) {
    return s[0] * eps(0, 0) + s[1] * eps(1, 1) + 2.0 * s[3] * eps(0, 1);
  } else {
    return s[0] * eps(0, 0) + s[1] * eps(1, 1) + s[2] * eps(2, 2) +
        2.0 * (s[3] * eps(0, 1) + s[4] * eps(1, 2) + s[5] * eps(0, 2));
  }
}

}  // namespace

template <int D>
ParticleStrain<D> particle_strain(const System<D>& sys, Index i) {
  const auto& p = sys.particles;
  const auto& t = sys.table;
  Mat<D> K = Mat<D>::Zero(), N = Mat<D>::Zero();
  sys.for_each_live_bond(i, [&](BondIndex, Index j, int k) {
    const double w = t.weight[k] * p.volume[j];
    K += w * t.xi[k] * t.xi[k].transpose();
    N += w * (p.u[j] - p.u[i]) * t.xi[k].transpose();
  });
  // A particle that has lost the bonds spanning its neighbourhood has no
  // defined strain; report zero stress rather than a singular solve.
  ParticleStrain<D> o;
  const double scale = std::pow(K.trace() / D, D);
  if (!(std::abs(K.determinant()) > 1e-10 * scale)) return o;
  o.grad_u = N * K.inverse();
  const Mat<D> eps = 0.5 * (o.grad_u + o.grad_u.transpose());
  o.stress = hooke<D>(eps, sys.material, sys.setting);
  o.energy = 0.5 * double_contraction<D>(o.stress, eps);
  return o;
}

template <int D>
std::vector<ParticleStrain<D>> particle_strain(const System<D>& sys) {
  std::vector<ParticleStrain<D>> out(sys.particles.n_real);
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < sys.particles.n_real; ++i) out[i] = particle_strain(sys, i);
  return out;
}

template <int D>
std::vector<Tensor6> particle_stress(const System<D>& sys) {
  const std::vector<ParticleStrain<D>> strain = particle_strain(sys);
  std::vector<Tensor6> out(strain.size());
  for (std::size_t i = 0; i < strain.size(); ++i) out[i] = strain[i].stress;
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

template ParticleStrain<1> particle_strain<1>(const System<1>&, Index);
template ParticleStrain<2> particle_strain<2>(const System<2>&, Index);
template ParticleStrain<3> particle_strain<3>(const System<3>&, Index);
template std::vector<ParticleStrain<1>> particle_strain<1>(const System<1>&);
template std::vector<ParticleStrain<2>> particle_strain<2>(const System<2>&);
template std::vector<ParticleStrain<3>> particle_strain<3>(const System<3>&);
template std::vector<Tensor6> particle_stress<1>(const System<1>&);
template std::vector<Tensor6> particle_stress<2>(const System<2>&);
template std::vector<Tensor6> particle_stress<3>(const System<3>&);

}  // namespace pdmpm::pd
