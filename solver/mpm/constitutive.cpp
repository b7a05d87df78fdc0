#include "solver/mpm/constitutive.hpp"

#include <cmath>
#include <limits>

#include "solver/mpm/hencky_elastic.hpp"
#include "solver/mpm/j2_plasticity.hpp"
#include "solver/mpm/kinematics.hpp"
#include "solver/mpm/neo_hookean.hpp"
#include "solver/mpm/series_log_exp.hpp"

namespace pdmpm::mpm {

template <int D>
Mat<3> embed(const Mat<D>& A) {
  Mat<3> out = Mat<3>::Zero();
  out.template topLeftCorner<D, D>() = A;
  return out;
}

template <int D>
Mat<3> embed_deformation(const Mat<D>& F) {
  Mat<3> out = Mat<3>::Identity();
  out.template topLeftCorner<D, D>() = F;
  return out;
}

template <int D>
StressResult Constitutive<D>::update(const Mat<D>& F, PointHistory& history, double hardening_offset) const {
  if (m_.model == MaterialModel::neo_hookean) {
    StressResult r;
    r.kirchhoff = neo_hookean_kirchhoff(m_.elastic, embed_deformation<D>(F), r.J, r.energy);
    return r;
  }
  return update(polar_log<D>(F), history, hardening_offset);
}

template <int D>
StressResult Constitutive<D>::update(const PolarLog<D>& pl, PointHistory& history, double hardening_offset) const {
  // Log-strain laws: work in the unrotated frame, then rotate back with R.
  StressResult r;
  const Mat<3> eps = embed<D>(pl.log_U);
  Mat<3> T;
  double out_of_plane = 0.0;  // plane stress ε₃₃ or bar lateral strain
  if (m_.model == MaterialModel::linear_elastic) {
    switch (setting_) {
      case core::Setting::plane_stress:
        T = hooke_plane_stress(m_.elastic, eps, out_of_plane);
        break;
      case core::Setting::bar1d:
        T = hooke_bar(m_.elastic, eps, out_of_plane);
        break;
      default:
        T = hooke_3d(m_.elastic, eps);
        break;
    }
    r.energy = setting_ == core::Setting::plane_stress
        ? 0.5 * (T(0, 0) * eps(0, 0) + T(1, 1) * eps(1, 1) + 2.0 * T(0, 1) * eps(0, 1))
        : elastic_energy(T, eps);
  } else {
    J2Result j;
    switch (setting_) {
      case core::Setting::plane_stress:
        j = j2_return_plane_stress(j2_, eps, history, hardening_offset);
        break;
      case core::Setting::bar1d:
        j = j2_return_bar(m_.elastic, m_.j2, eps, history, hardening_offset);
        break;
      default:
        j = j2_return_3d(j2_, eps, history, hardening_offset);
        break;
    }
    T = j.T;
    out_of_plane = j.out_of_plane;
    r.energy = j.energy;
    r.dissipation = j.dissipation;
  }
  // Volume ratio from the log strain: J = exp(tr ε) with the setting's out-of-plane part.
  double trace = eps.trace();
  if (setting_ == core::Setting::plane_stress) trace += out_of_plane;
  if (setting_ == core::Setting::bar1d) trace += 2.0 * out_of_plane;
  r.J = series_exp(trace);
  r.out_of_plane_strain = out_of_plane;
  if constexpr (D == 2) {
    // τ = R T Rᵀ with R = diag(R₂, 1): the in-plane block rotates, T₃₃ stays (the
    // 3×3 product's arithmetic less its terms with a zero factor).
    const Mat<2>& R = pl.R;
    Mat<2> RT;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) RT(i, j) = R(i, 0) * T(0, j) + R(i, 1) * T(1, j);
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) r.kirchhoff(i, j) = RT(i, 0) * R(j, 0) + RT(i, 1) * R(j, 1);
    r.kirchhoff(2, 2) = T(2, 2);
  } else {
    const Mat<3> R = embed_deformation<D>(pl.R);
    r.kirchhoff = R * T * R.transpose();
  }
  return r;
}

template <int D>
std::optional<PlaneStressLaw> Constitutive<D>::plane_stress_law() const {
  if (D != 2 || setting_ != core::Setting::plane_stress || !log_strain()) return std::nullopt;
  if (m_.model != MaterialModel::linear_elastic && m_.model != MaterialModel::j2) return std::nullopt;
  PlaneStressLaw law{
      j2_.plane_stress_modulus, j2_.nu, j2_.thickness_strain, j2_.yield_stress, j2_.H, j2_.E, j2_.G, j2_.c1};
  if (m_.model == MaterialModel::linear_elastic) {  // J2 that never yields
    law.yield_stress = std::numeric_limits<double>::infinity();
    law.hardening = 0.0;
  }
  return law;
}

template class Constitutive<1>;
template class Constitutive<2>;
template class Constitutive<3>;
template Mat<3> embed<1>(const Mat<1>&);
template Mat<3> embed<2>(const Mat<2>&);
template Mat<3> embed<3>(const Mat<3>&);
template Mat<3> embed_deformation<1>(const Mat<1>&);
template Mat<3> embed_deformation<2>(const Mat<2>&);
template Mat<3> embed_deformation<3>(const Mat<3>&);

}  // namespace pdmpm::mpm
