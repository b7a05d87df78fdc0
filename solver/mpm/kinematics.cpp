#include "solver/mpm/kinematics.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

#include "solver/core/error.hpp"

namespace pdmpm::mpm {

namespace {

// ln of a symmetric positive definite 2×2 matrix without dividing by a small
// eigenvalue gap: ln U = ½ ln(det U) I + q (U − m I), q = (ln λ₁ − ln λ₂)/(λ₁ − λ₂).
Mat<2> log_spd2(const Mat<2>& U) {
  const double m = 0.5 * (U(0, 0) + U(1, 1));
  const double hd = 0.5 * (U(0, 0) - U(1, 1));
  const double b = 0.5 * (U(0, 1) + U(1, 0));
  const double r = std::hypot(hd, b);
  const double x = r / m;  // < 1 for positive definite U
  // atanh(x)/x, with its series where the quotient would lose digits.
  const double ratio = x < 1e-4 ? 1.0 + x * x / 3.0 : std::atanh(x) / x;
  const double q = ratio / m;
  Mat<2> out;
  const double half_log_det = 0.5 * std::log((m - r) * (m + r));
  out(0, 0) = half_log_det + q * hd;
  out(1, 1) = half_log_det - q * hd;
  out(0, 1) = out(1, 0) = q * b;
  return out;
}

}  // namespace

template <>
PolarLog<1> polar_log<1>(const Mat<1>& F) {
  if (!(F(0, 0) > 0.0)) throw RunError("deformation gradient with det F ≤ 0 (particle inverted)");
  PolarLog<1> p;
  p.R.setIdentity();
  p.log_U(0, 0) = std::log(F(0, 0));
  return p;
}

template <>
PolarLog<2> polar_log<2>(const Mat<2>& F) {
  if (!(F.determinant() > 0.0)) throw RunError("deformation gradient with det F ≤ 0 (particle inverted)");
  // The rotation of a 2×2 polar decomposition is the one that makes RᵀF symmetric.
  const double theta = std::atan2(F(1, 0) - F(0, 1), F(0, 0) + F(1, 1));
  const double c = std::cos(theta), s = std::sin(theta);
  PolarLog<2> p;
  p.R << c, -s, s, c;
  Mat<2> U = p.R.transpose() * F;
  U = 0.5 * (U + U.transpose()).eval();
  p.log_U = log_spd2(U);
  return p;
}

template <>
PolarLog<3> polar_log<3>(const Mat<3>& F) {
  if (!(F.determinant() > 0.0)) throw RunError("deformation gradient with det F ≤ 0 (particle inverted)");
  const Mat<3> C = F.transpose() * F;
  Eigen::SelfAdjointEigenSolver<Mat<3>> eig(C);
  const Vec<3> lam = eig.eigenvalues();
  const Mat<3>& Q = eig.eigenvectors();
  Vec<3> half_log, inv_sqrt;
  for (int i = 0; i < 3; ++i) {
    half_log[i] = 0.5 * std::log(lam[i]);
    inv_sqrt[i] = 1.0 / std::sqrt(lam[i]);
  }
  PolarLog<3> p;
  p.log_U = Q * half_log.asDiagonal() * Q.transpose();
  p.R = F * (Q * inv_sqrt.asDiagonal() * Q.transpose());
  return p;
}

template <int D>
Mat<D> cayley_increment(const Mat<D>& L, double dt) {
  const Mat<D> I = Mat<D>::Identity();
  const Mat<D> A = I - 0.5 * dt * L;
  return A.inverse() * (I + 0.5 * dt * L);
}

template Mat<1> cayley_increment(const Mat<1>&, double);
template Mat<2> cayley_increment(const Mat<2>&, double);
template Mat<3> cayley_increment(const Mat<3>&, double);

}  // namespace pdmpm::mpm
