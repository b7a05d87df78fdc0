#include "solver/mpm/kinematics.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

#include "solver/core/error.hpp"
#include "solver/mpm/series_log_exp.hpp"

namespace pdmpm::mpm {

namespace {

// atanh(x)/x for 0 ≤ x < 1: below 0.1 (strains under ~10 %, every step of a metal body)
// by its series (series_log_exp.hpp), no library call.
double atanh_over_x(double x) { return x < kSeriesLimit ? atanh_over_x_series(x * x) : std::atanh(x) / x; }

// ln of a symmetric positive definite 2×2 matrix U of determinant det_U without
// dividing by a small eigenvalue gap: with eigenvalues m ± r,
// ln U = ½ ln(det U) I + q (U − m I), q = (ln(m + r) − ln(m − r))/(2r) = atanh(r/m)/r,
// both divisions by m as one reciprocal (polar_lanes_impl.hpp: the same operations).
Mat<2> log_spd2(const Mat<2>& U, double det_U) {
  const double m = 0.5 * (U(0, 0) + U(1, 1));
  const double hd = 0.5 * (U(0, 0) - U(1, 1));
  const double b = 0.5 * (U(0, 1) + U(1, 0));
  const double r = std::sqrt(hd * hd + b * b);
  const double inv_m = 1.0 / m;
  const double q = atanh_over_x(r * inv_m) * inv_m;  // r/m < 1 for positive definite U
  Mat<2> out;
  const double half_log_det = series_half_log(det_U);
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
  // Scalar code on purpose: Eigen's packet products read R back as 16-byte loads
  // over two 8-byte stores, a store-forwarding stall on every point (the same
  // arithmetic: a sum of two products rounds alike in either order).
  const double f00 = F(0, 0), f01 = F(0, 1), f10 = F(1, 0), f11 = F(1, 1);
  const double det = f00 * f11 - f10 * f01;
  if (!(det > 0.0)) throw RunError("deformation gradient with det F ≤ 0 (particle inverted)");
  // The rotation of a 2×2 polar decomposition is the one that makes RᵀF symmetric:
  // R = [c −s; s c] with (c, s) ∥ (F₀₀ + F₁₁, F₁₀ − F₀₁) — a norm, no angle needed.
  const double a = f00 + f11, b = f10 - f01;
  const double inv = 1.0 / std::sqrt(a * a + b * b);
  const double c = a * inv, s = b * inv;
  PolarLog<2> p;
  p.R << c, -s, s, c;
  // U = RᵀF, symmetrised.
  const double u00 = c * f00 + s * f10, u11 = -s * f01 + c * f11;
  const double u01 = c * f01 + s * f11, u10 = -s * f00 + c * f10;
  Mat<2> U;
  U << 0.5 * (u00 + u00), 0.5 * (u01 + u10), 0.5 * (u10 + u01), 0.5 * (u11 + u11);
  p.log_U = log_spd2(U, det);  // det U = det F
  return p;
}

namespace {

// ½ ln C and C^(−1/2) of a symmetric positive definite 3×3 C near a multiple of the
// identity: with m = tr C/3 and X = (C − mI)/m (the deviatoric stretch, |X| ~ 2 × the
// shear strain), ln C = (ln m) I + Σ (−1)^(k+1) X^k/k and C^(−1/2) = m^(−1/2) Σ a_k X^k,
// a_k = binom(−1/2, k), summed until |X|^k < 1e-17 |X| (six terms at |X| ~ 1e-3,
// seventeen at 0.1). False (nothing written) where |X| ≥ 0.1: the eigen-decomposition
// takes those. The powers are not formed: by Cayley–Hamilton X³ = e₁X² − e₂X + e₃I
// (e₁ = tr X, e₂ = ½(e₁² − tr X²), e₃ = det X), so X^k = α_k I + β_k X + γ_k X² with
// α_{k+1} = e₃γ_k, β_{k+1} = α_k − e₂γ_k, γ_{k+1} = β_k + e₁γ_k — three scalars a term
// where a matrix product was (the 3D stress update's longest chain).
bool half_log_and_inverse_root_by_series(const Mat<3>& C, Mat<3>& half_log_C, Mat<3>& inv_root_C) {
  const double m = C.trace() / 3.0;
  if (!(m > 0.0)) return false;
  const Mat<3> I = Mat<3>::Identity();
  const Mat<3> X = (C - m * I) / m;
  const double r = X.norm();  // Frobenius ≥ spectral: |X^k| ≤ r^k
  if (!(r < kSeriesLimit)) return false;
  const Mat<3> X2 = X * X;
  const double e1 = X.trace(), e2 = 0.5 * (e1 * e1 - X2.trace()), e3 = X.determinant();
  // Σ (−1)^(k+1) X^k/k and Σ a_k X^k as coefficients of I, X, X²; the k = 1 terms first.
  double log_i = 0.0, log_x = 1.0, log_x2 = 0.0;
  double root_i = 1.0, root_x = -0.5, root_x2 = 0.0;
  double alpha = 0.0, beta = 1.0, gamma = 0.0;  // X^1
  double a = -0.5, bound = r;
  for (int k = 2; bound > 1e-17 * r; ++k) {
    const double next_alpha = e3 * gamma, next_beta = alpha - e2 * gamma, next_gamma = beta + e1 * gamma;
    alpha = next_alpha, beta = next_beta, gamma = next_gamma;
    bound *= r;
    a *= -(2.0 * k - 1.0) / (2.0 * k);
    const double c = (k % 2 == 0 ? -1.0 : 1.0) / k;
    log_i += c * alpha, log_x += c * beta, log_x2 += c * gamma;
    root_i += a * alpha, root_x += a * beta, root_x2 += a * gamma;
  }
  half_log_C = (series_half_log(m) + 0.5 * log_i) * I + (0.5 * log_x) * X + (0.5 * log_x2) * X2;
  inv_root_C = (1.0 / std::sqrt(m)) * (root_i * I + root_x * X + root_x2 * X2);
  return true;
}

}  // namespace

template <>
PolarLog<3> polar_log<3>(const Mat<3>& F) {
  if (!(F.determinant() > 0.0)) throw RunError("deformation gradient with det F ≤ 0 (particle inverted)");
  const Mat<3> C = F.transpose() * F;
  PolarLog<3> p;
  // ln U = ½ ln C and R = F U⁻¹ = F C^(−1/2): by series near the identity (a yielding 20³
  // cube's stress update took 20 % less time than with the decomposition), else from the
  // eigen-decomposition of C.
  Mat<3> inv_root_C;
  if (!half_log_and_inverse_root_by_series(C, p.log_U, inv_root_C)) {
    Eigen::SelfAdjointEigenSolver<Mat<3>> eig(C);
    const Vec<3> lam = eig.eigenvalues();
    const Mat<3>& Q = eig.eigenvectors();
    Vec<3> half_log, inv_sqrt;
    for (int i = 0; i < 3; ++i) {
      half_log[i] = 0.5 * std::log(lam[i]);
      inv_sqrt[i] = 1.0 / std::sqrt(lam[i]);
    }
    p.log_U = Q * half_log.asDiagonal() * Q.transpose();
    inv_root_C = Q * inv_sqrt.asDiagonal() * Q.transpose();
  }
  p.R = F * inv_root_C;
  return p;
}

template <int D>
Mat<D> cayley_increment(const Mat<D>& L, double dt) {
  const Mat<D> I = Mat<D>::Identity();
  if constexpr (D == 2) {
    // Scalar code for the 2D hot path, Eigen's arithmetic (the 2×2 inverse by
    // 1/det times the adjugate, then sums of two products) without its packet
    // stores and reloads.
    const double h = 0.5 * dt;
    const double a00 = 1.0 - h * L(0, 0), a01 = 0.0 - h * L(0, 1), a10 = 0.0 - h * L(1, 0), a11 = 1.0 - h * L(1, 1);
    const double b00 = 1.0 + h * L(0, 0), b01 = 0.0 + h * L(0, 1), b10 = 0.0 + h * L(1, 0), b11 = 1.0 + h * L(1, 1);
    const double inv_det = 1.0 / (a00 * a11 - a10 * a01);
    const double i00 = a11 * inv_det, i01 = -a01 * inv_det, i10 = -a10 * inv_det, i11 = a00 * inv_det;
    Mat<2> out;
    out << i00 * b00 + i01 * b10, i00 * b01 + i01 * b11, i10 * b00 + i11 * b10, i10 * b01 + i11 * b11;
    return out;
  } else {
    const Mat<D> A = I - 0.5 * dt * L;
    return A.inverse() * (I + 0.5 * dt * L);
  }
}

template Mat<1> cayley_increment(const Mat<1>&, double);
template Mat<2> cayley_increment(const Mat<2>&, double);
template Mat<3> cayley_increment(const Mat<3>&, double);

}  // namespace pdmpm::mpm
