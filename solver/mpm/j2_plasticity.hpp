#pragma once
// Von Mises (J2) plasticity with linear isotropic hardening, integrated by
// backward-Euler return mapping on an additive split of the logarithmic strain,
// ε = ε_e + ε_p (Lagrangian log-strain plasticity). Yield: σ_eq ≤ σ_y + H ε̂_p with
// H = E E_t / (E − E_t), so uniaxial stress follows σ_y + E_t (ε − σ_y/E).
// ε̂_p = ε̄_p + hardening_offset (the offset carries the non-local correction).
#include "solver/core/types.hpp"
#include "solver/mpm/hencky_elastic.hpp"
#include "solver/mpm/material_point.hpp"
#include "solver/core/material.hpp"

namespace pdmpm::mpm {

struct J2Result {
  Mat<3> T = Mat<3>::Zero();  // rotated Kirchhoff stress
  double out_of_plane = 0.0;  // plane stress ε₃₃ / bar lateral strain (total, log)
  double energy = 0.0;        // ½ T : ε_e
  double dissipation = 0.0;   // T : Δε_p
  double d_eq_plastic = 0.0;  // Δε̄_p of this update
};

// The material constants the returns use, computed once per material: each is a
// division, and a division in every point's dependency chain costs more than the
// rest of an elastic update (same expressions, so the same values).
struct J2Constants {
  J2Constants(const core::Elastic& m, const core::J2Hardening& j2);
  double E, nu, G, lame, H, yield_stress;
  double plane_stress_modulus;  // E/(1 − ν²)
  double thickness_strain;      // −ν/(1 − ν): ε₃₃ per in-plane trace, plane stress
  double c1;                    // E/(3(1 − ν)), plane-stress spectral mode 1
};

// Where the plane-stress return's Newton iteration starts (j2_return_plane_stress,
// plane_stress_lanes_impl.hpp): the root of its consistency condition with both spectral modes
// scaled by their mean modulus c̄ = (c₁s₁ + c₂s₂)/(s₁ + s₂), in closed form for linear
// hardening, with S = s₁ + s₂ = φ₀², κ₀ = σ_y + H α₀:
//   Δγ₀ = S (φ₀/√2 − κ₀/√3) / (κ₀ (c₁s₁ + c₂s₂)/√3 + (√2/3) H φ₀ S).
// Not positive or not finite: 0. T is double or a lane vector (sqrt_of its square root),
// the same operations on both, so both give the same bits.
template <class T, class Sqrt>
inline T plane_stress_newton_start(T s1, T s2, double c1, double c2, T kappa0, double H, Sqrt sqrt_of) {
  const double inv_sqrt2 = 0.70710678118654752440, inv_sqrt3 = 0.57735026918962576451;
  const double sqrt2_over3 = 0.47140452079103168293;
  const T S = s1 + s2, phi0 = sqrt_of(S);
  const T num = S * (inv_sqrt2 * phi0 - inv_sqrt3 * kappa0);
  const T den = inv_sqrt3 * (kappa0 * (c1 * s1 + c2 * s2)) + sqrt2_over3 * H * (phi0 * S);
  return num / den;
}

// Constants of the plane-stress return, as multiplications: a division by 3 or √2 costs a
// yielding point as much as a step of its iteration (j2_return_plane_stress and
// plane_stress_lanes_impl.hpp use the same ones, so the two give the same bits).
inline constexpr double kInvSqrt2 = 0.70710678118654752440;
inline constexpr double kThird = 1.0 / 3.0;
inline constexpr double kSqrt2over3 = 0.81649658092772603273;  // √(2/3)

// The plane-stress return's spectral reciprocals 1/(1 + c₁Δγ) and 1/(1 + c₂Δγ) from one
// division, 1/((1 + c₁Δγ)(1 + c₂Δγ)): divisions and square roots are what the yielding
// points' iterations wait on (issue 19's profile: a third of the stress update).
template <class T>
struct PlaneStressReciprocals {
  T r1, r2;
};
template <class T>
inline PlaneStressReciprocals<T> plane_stress_reciprocals(T dg, double c1, double c2) {
  const T a = 1.0 + c1 * dg, b = 1.0 + c2 * dg, r = 1.0 / (a * b);
  return {b * r, a * r};
}

// The consistency function of the plane-stress return at Δγ with linear hardening,
//   f(Δγ) = ½φ² − ⅓κ²,  φ² = s₁/(1 + c₁Δγ)² + s₂/(1 + c₂Δγ)²,  κ = σ_y + H(α₀ + √⅔ Δγ φ),
// and its Newton step f/f′. With φ′ = ½(φ²)′/φ, f′ = ½(φ²)′ − ⅔κH√⅔(φ + Δγφ′); the step is
// formed as fφ/(f′φ), in which φ cancels, so an evaluation costs one division for the
// reciprocals, one square root and one division for the step. (φ = 0 means zero deviatoric
// stress, which never yields.) T is double or a lane vector: the same operations on both.
template <class T>
struct PlaneStressConsistency {
  T f, step;
};
template <class T, class Sqrt>
inline PlaneStressConsistency<T> plane_stress_consistency(T dg, T s1, T s2, double c1, double c2, double yield_stress,
                                                          double H, T alpha0, Sqrt sqrt_of) {
  const PlaneStressReciprocals<T> d = plane_stress_reciprocals(dg, c1, c2);
  const T q1 = s1 * d.r1 * d.r1, q2 = s2 * d.r2 * d.r2;
  const T p2 = q1 + q2, p = sqrt_of(p2);
  const T dp2 = -2.0 * (c1 * q1 * d.r1 + c2 * q2 * d.r2);
  const T kappa = yield_stress + H * (alpha0 + kSqrt2over3 * dg * p);
  const T df_times_p = 0.5 * dp2 * p - (2.0 * kThird) * kappa * (H * kSqrt2over3) * (p2 + 0.5 * dg * dp2);
  const T f = 0.5 * p2 - kThird * (kappa * kappa);
  return {f, f * p / df_times_p};
}

// solid3d, plane_strain, uniaxial_strain: radial return (Simo & Hughes 1998, box 3.1).
J2Result j2_return_3d(const J2Constants& k, const Mat<3>& eps, PointHistory& h, double hardening_offset);
inline J2Result j2_return_3d(const core::Elastic& m, const core::J2Hardening& j2, const Mat<3>& eps, PointHistory& h,
                             double hardening_offset) {
  return j2_return_3d(J2Constants(m, j2), eps, h, hardening_offset);
}

// Plane stress (σ₃₃ = σ₁₃ = σ₂₃ = 0): the plane-stress projected return map of
// Simo & Taylor (1986) / Simo & Hughes (1998) §3.4, solved for the consistency
// parameter by safeguarded Newton in the spectral basis of the projection P.
J2Result j2_return_plane_stress(const J2Constants& k, const Mat<3>& eps, PointHistory& h, double hardening_offset);
inline J2Result j2_return_plane_stress(const core::Elastic& m, const core::J2Hardening& j2, const Mat<3>& eps,
                                       PointHistory& h, double hardening_offset) {
  return j2_return_plane_stress(J2Constants(m, j2), eps, h, hardening_offset);
}

// Bar (uniaxial stress): 1D return map.
J2Result j2_return_bar(const core::Elastic& m, const core::J2Hardening& j2, const Mat<3>& eps, PointHistory& h,
                       double hardening_offset);

}  // namespace pdmpm::mpm
