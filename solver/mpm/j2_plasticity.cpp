#include "solver/mpm/j2_plasticity.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "solver/core/error.hpp"

namespace pdmpm::mpm {

namespace {
const double kSqrt3over2 = std::sqrt(1.5);
}  // namespace

J2Constants::J2Constants(const core::Elastic& m, const core::J2Hardening& j2)
    : E(m.E),
      nu(m.nu),
      G(m.shear()),
      lame(m.lame()),
      H(j2.hardening_modulus(m.E)),
      yield_stress(j2.yield_stress),
      plane_stress_modulus(m.E / (1.0 - m.nu * m.nu)),
      thickness_strain(-m.nu / (1.0 - m.nu)),
      c1(m.E / (3.0 * (1.0 - m.nu))) {}

J2Result j2_return_3d(const J2Constants& k, const Mat<3>& eps, PointHistory& h, double hardening_offset) {
  const double G = k.G, H = k.H;
  const Mat<3> eps_e_trial = eps - h.plastic_strain;
  const Mat<3> T_trial = hooke_3d(k.lame, G, eps_e_trial);
  const Mat<3> s = T_trial - (T_trial.trace() / 3.0) * Mat<3>::Identity();
  const double s_norm = s.norm();
  const double q = kSqrt3over2 * s_norm;  // von Mises equivalent of the trial stress
  const double kappa = k.yield_stress + H * (h.eq_plastic_strain + hardening_offset);
  J2Result r;
  if (q <= kappa) {
    r.T = T_trial;
    r.energy = elastic_energy(T_trial, eps_e_trial);
    return r;
  }
  // Linear hardening makes the consistency condition linear in Δε̄_p.
  const double d_alpha = (q - kappa) / (3.0 * G + H);
  const Mat<3> n = s / s_norm;                       // unit deviatoric direction
  const Mat<3> d_eps_p = kSqrt3over2 * d_alpha * n;  // |Δε_p| = sqrt(3/2) Δε̄_p
  h.plastic_strain += d_eps_p;
  h.eq_plastic_strain += d_alpha;
  r.T = T_trial - 2.0 * G * d_eps_p;
  r.d_eq_plastic = d_alpha;
  r.dissipation = (r.T.array() * d_eps_p.array()).sum();
  r.energy = elastic_energy(r.T, eps - h.plastic_strain);
  return r;
}

J2Result j2_return_plane_stress(const J2Constants& k, const Mat<3>& eps, PointHistory& h, double hardening_offset) {
  const double G = k.G, H = k.H, E = k.E, nu = k.nu;
  // The elastic trial on the in-plane block (the strains are symmetric: ε_e,10 = ε_e,01).
  const double e00 = eps(0, 0) - h.plastic_strain(0, 0), e11 = eps(1, 1) - h.plastic_strain(1, 1);
  const double e01 = eps(0, 1) - h.plastic_strain(0, 1);
  const auto [t00, t11, t01, e33_el] =
      hooke_plane_stress(k.plane_stress_modulus, nu, k.thickness_strain, e00, e11, e01);
  // Spectral coordinates of the in-plane stress in the common eigenbasis of the
  // plane-stress elasticity and the projection P (eigenvalues 1/3, 1, 2).
  const double a1 = (t00 + t11) * kInvSqrt2;
  const double a2 = (t11 - t00) * kInvSqrt2;
  const double a3 = t01;
  const double alpha0 = h.eq_plastic_strain + hardening_offset;
  // φ²(Δγ) = σᵀPσ after the return, f(Δγ) = ½φ² − ⅓ κ²(α₀ + sqrt(2/3) Δγ φ).
  const double s1 = a1 * a1 * kThird, s2 = a2 * a2 + 2.0 * a3 * a3;
  J2Result r;
  {
    // f(0): the elastic check, most points of a body most steps.
    const double kappa = k.yield_stress + H * alpha0;
    if (0.5 * (s1 + s2) - kThird * (kappa * kappa) <= 0.0) {
      r.T(0, 0) = t00;
      r.T(1, 1) = t11;
      r.T(0, 1) = r.T(1, 0) = t01;
      r.out_of_plane = e33_el + h.plastic_strain(2, 2);
      // ½ T : ε_e summed as elastic_energy sums the 3×3 array (pairwise), T₃₃ = 0.
      const double p00 = t00 * e00, p11 = t11 * e11, p01 = t01 * e01;
      r.energy = 0.5 * ((p00 + p11) + (p01 + p01));
      return r;
    }
  }
  const double c1 = k.c1;     // (elastic eigenvalue) × (P eigenvalue), mode 1
  const double c2 = 2.0 * G;  // modes 2 and 3
  auto f = [&](double dg) {
    return plane_stress_consistency(dg, s1, s2, c1, c2, k.yield_stress, H, alpha0,
                                    [](double x) { return std::sqrt(x); });
  };
  // f decreases monotonically in Δγ and is convex (Simo & Hughes 1998 §3.4.2): Newton
  // from the left of the root approaches it from one side. Start at the root of the same
  // condition with both modes scaled by one modulus, the mean c̄ = (c₁s₁ + c₂s₂)/(s₁ + s₂):
  // φ²(Δγ) ≥ φ₀²/(1 + c̄Δγ)² (Jensen: 1/(1 + cΔγ)² is convex in c), so that root lies at or
  // left of f's, and it solves in closed form (linear hardening):
  //   Δγ₀ = (φ₀/√2 − κ₀/√3) / (c̄κ₀/√3 + (√2/3) H φ₀),  φ₀² = s₁ + s₂, κ₀ = σ_y + H α₀.
  // It is exact where s₁ = 0 or c₁ = c₂; from it Newton takes one or two steps where it
  // took four or five from Δγ = 0 (measured on a yielding plate).
  // The bracket [lo, hi] tightens with every iterate's sign; a step that leaves it
  // (possible only where f is not convex) bisects, and the upper end is searched for
  // only then — an evaluation fewer per yielding point otherwise.
  const double start =
      plane_stress_newton_start(s1, s2, c1, c2, k.yield_stress + H * alpha0, H, [](double x) { return std::sqrt(x); });
  const double dg0 = start > 0.0 && start - start == 0.0 ? start : 0.0;
  double lo = 0.0, hi = std::numeric_limits<double>::infinity();
  double dg = dg0;
  PlaneStressConsistency<double> fv = f(dg0);
  if (fv.f > 0.0)
    lo = dg0;
  else
    hi = dg0;
  // f's terms are O(κ²): the tolerance is relative to the yield stress at the start of the
  // step, κ_n = σ_y + H α₀ (σ_y if that is less). Relative to σ_y² it lay below a hardened
  // point's round-off (~1e-16 κ²), and the loop ran to its limit: the dog-bone's gauge at
  // κ ≈ 4σ_y spent a third of its run here.
  const double kappa_n = std::max(k.yield_stress, k.yield_stress + H * alpha0);
  const double scale = kappa_n * kappa_n;
  for (int it = 0; it < 200; ++it) {
    if (std::abs(fv.f) <= 1e-15 * scale || (std::isfinite(hi) && hi - lo <= 1e-16 * hi)) break;
    double next = dg - fv.step;
    if (!(next > lo && next < hi)) {
      if (std::isinf(hi)) {  // find an upper end: f(hi) ≤ 0
        hi = 1.0 / c2;
        while (f(hi).f > 0.0) {
          lo = hi;
          hi *= 2.0;
          if (hi > 1e12 / c2) throw RunError("plane-stress return map: no bracket for the consistency parameter");
        }
      }
      next = 0.5 * (lo + hi);
    }
    dg = next;
    fv = f(dg);
    if (fv.f > 0.0)
      lo = dg;
    else
      hi = dg;
  }
  const PlaneStressReciprocals<double> d = plane_stress_reciprocals(dg, c1, c2);
  const double b1 = a1 * d.r1, b2 = a2 * d.r2, b3 = a3 * d.r2;
  Mat<3> T = Mat<3>::Zero();
  T(0, 0) = (b1 - b2) * kInvSqrt2;
  T(1, 1) = (b1 + b2) * kInvSqrt2;
  T(0, 1) = T(1, 0) = b3;
  // Δε_p = Δγ P σ (tensor components: the engineering shear 2Δγσ₁₂ halves to Δγσ₁₂).
  Mat<3> d_eps_p = Mat<3>::Zero();
  d_eps_p(0, 0) = dg * (2.0 * T(0, 0) - T(1, 1)) * kThird;
  d_eps_p(1, 1) = dg * (2.0 * T(1, 1) - T(0, 0)) * kThird;
  d_eps_p(0, 1) = d_eps_p(1, 0) = dg * T(0, 1);
  d_eps_p(2, 2) = -(d_eps_p(0, 0) + d_eps_p(1, 1));
  const double d_alpha = kSqrt2over3 * dg * std::sqrt(s1 * d.r1 * d.r1 + s2 * d.r2 * d.r2);
  h.plastic_strain += d_eps_p;
  h.eq_plastic_strain += d_alpha;
  r.T = T;
  r.d_eq_plastic = d_alpha;
  r.dissipation = (T.array() * d_eps_p.array()).sum();
  const Mat<3> eps_e = eps - h.plastic_strain;
  r.energy = 0.5 * (T(0, 0) * eps_e(0, 0) + T(1, 1) * eps_e(1, 1) + 2.0 * T(0, 1) * eps_e(0, 1));
  r.out_of_plane = -nu / E * (T(0, 0) + T(1, 1)) + h.plastic_strain(2, 2);
  return r;
}

J2Result j2_return_bar(const core::Elastic& m, const core::J2Hardening& j2, const Mat<3>& eps, PointHistory& h,
                       double hardening_offset) {
  const double E = m.E, H = j2.hardening_modulus(m.E);
  const double ep = h.plastic_strain(0, 0);
  const double T_trial = E * (eps(0, 0) - ep);
  const double kappa = j2.yield_stress + H * (h.eq_plastic_strain + hardening_offset);
  J2Result r;
  double T = T_trial;
  if (std::abs(T_trial) > kappa) {
    const double d_alpha = (std::abs(T_trial) - kappa) / (E + H);
    const double sign = T_trial > 0.0 ? 1.0 : -1.0;
    T = T_trial - E * d_alpha * sign;
    // Isochoric flow: lateral plastic strains are −½ of the axial one.
    Mat<3> d_eps_p = Mat<3>::Zero();
    d_eps_p(0, 0) = sign * d_alpha;
    d_eps_p(1, 1) = d_eps_p(2, 2) = -0.5 * sign * d_alpha;
    h.plastic_strain += d_eps_p;
    h.eq_plastic_strain += d_alpha;
    r.d_eq_plastic = d_alpha;
    r.dissipation = T * sign * d_alpha;
  }
  r.T(0, 0) = T;
  const double eps_e = eps(0, 0) - h.plastic_strain(0, 0);
  r.energy = 0.5 * T * eps_e;
  r.out_of_plane = -m.nu * eps_e + h.plastic_strain(1, 1);
  return r;
}

}  // namespace pdmpm::mpm
