// Closed-form bond constants (docs/models/pmb.md and docs/models/lps.md) against values worked out by hand,
// their signs, and how they scale with δ, E and G₀.
#include "solver/pd/constants.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace pdmpm::pd {
namespace {

constexpr double pi = std::numbers::pi;
const double e1 = std::exp(-1.0);
const core::Setting all_settings[] = {core::Setting::bar1d, core::Setting::plane_stress, core::Setting::plane_strain, core::Setting::solid3d};

// Relative tolerance for closed forms evaluated two ways in double: a handful
// of roundings, amplified ≤ ~300× by the cancellation in the exponential moments.
constexpr double tight = 1e-13;

TEST(Constants, InfluenceMomentsByHand) {
  const double d = 2.0;  // δ ≠ 1 so the δ^{n+1} scaling is exercised
  // ∫₀^δ ω rⁿ dr with q = r/δ: δ^{n+1} ∫₀¹ ω(q) qⁿ dq.
  EXPECT_NEAR(influence_moment(Influence::constant, 3, d), 16.0 / 4.0, tight * 4.0);
  EXPECT_NEAR(influence_moment(Influence::triangular, 3, d), 16.0 / 20.0, tight);  // 1/4 − 1/5
  EXPECT_NEAR(influence_moment(Influence::quadratic, 3, d), 16.0 / 24.0, tight);   // 1/4 − 2/6 + 1/8
  EXPECT_NEAR(influence_moment(Influence::semi_elliptical, 3, d), 16.0 / 12.0, tight);
  EXPECT_NEAR(influence_moment(Influence::exponential, 3, d), 16.0 * (6.0 - 16.0 * e1), tight);
  EXPECT_NEAR(influence_moment(Influence::gaussian, 3, d), 16.0 * (0.5 - e1), tight);
  EXPECT_NEAR(influence_moment(Influence::inverse_distance, 3, d), 16.0 / 3.0, tight * 16.0);  // ∫ δ r² dr
  // Low orders of the recursions.
  EXPECT_NEAR(influence_moment(Influence::exponential, 0, d), 2.0 * (1.0 - e1), tight);
  EXPECT_NEAR(influence_moment(Influence::exponential, 1, d), 4.0 * (1.0 - 2.0 * e1), tight);
  EXPECT_NEAR(influence_moment(Influence::gaussian, 0, d), 2.0 * 0.5 * std::sqrt(pi) * std::erf(1.0), tight);
  EXPECT_NEAR(influence_moment(Influence::gaussian, 1, d), 4.0 * 0.5 * (1.0 - e1), tight);
  EXPECT_NEAR(influence_moment(Influence::gaussian, 2, d), 8.0 * (0.25 * std::sqrt(pi) * std::erf(1.0) - 0.5 * e1),
              tight);
  // J₄ = (3/2) J₂ − e⁻¹/2 = (3/8)√π erf 1 − (5/4) e⁻¹.
  EXPECT_NEAR(influence_moment(Influence::gaussian, 4, d), 32.0 * (0.375 * std::sqrt(pi) * std::erf(1.0) - 1.25 * e1),
              tight * 32.0);
}

TEST(Constants, MicromodulusByHand) {
  const core::Elastic m{1.0, 0.25, 1.0};
  // E = 1, δ = 1, unit measure, ω = 1.
  EXPECT_NEAR(pmb_micromodulus(Influence::constant, core::Setting::solid3d, m, 1.0, 1.0), 12.0 / pi, tight);  // 6/((1−2ν)π)
  EXPECT_NEAR(pmb_micromodulus(Influence::constant, core::Setting::bar1d, m, 1.0, 1.0), 2.0, tight);
  EXPECT_NEAR(pmb_micromodulus(Influence::constant, core::Setting::plane_strain, m, 1.0, 1.0), 9.6 / pi, tight);  // 48/(5π)
  const core::Elastic ps{1.0, 1.0 / 3.0, 1.0};
  EXPECT_NEAR(pmb_micromodulus(Influence::constant, core::Setting::plane_stress, ps, 1.0, 1.0), 9.0 / pi, tight);
  // Triangular 3D: I₃ = 1/20, (1 − 2ν) = ½ → c = 3E/(2π(1−2ν)I₃) = 60/π.
  EXPECT_NEAR(pmb_micromodulus(Influence::triangular, core::Setting::solid3d, m, 1.0, 1.0), 60.0 / pi, tight * 20);
}

TEST(Constants, WeightedVolumeByHand) {
  // ω = 1: 3D 4πδ⁵/5, 2D 2πhδ⁴/4, 1D 2Aδ³/3.
  EXPECT_NEAR(lps_weighted_volume(Influence::constant, core::Setting::solid3d, 1.0, 1.0), 4.0 * pi / 5.0, tight);
  EXPECT_NEAR(lps_weighted_volume(Influence::constant, core::Setting::plane_strain, 1.0, 0.5), pi / 4.0, tight);
  EXPECT_NEAR(lps_weighted_volume(Influence::constant, core::Setting::bar1d, 1.0, 3.0), 2.0, tight);
  // ω = δ/r: 3D 4πδ·δ⁴/4 = πδ⁵.
  EXPECT_NEAR(lps_weighted_volume(Influence::inverse_distance, core::Setting::solid3d, 2.0, 1.0), 32.0 * pi, tight * 100);
}

TEST(Constants, CriticalStretchByHand) {
  const core::Elastic m{200e9, 0.25, 7850.0};
  const double G0 = 500.0, d = 3e-3;
  // 3D, ω = 1 (Silling & Askari 2005): s₀ = sqrt(5G₀/(9Kδ)).
  EXPECT_NEAR(critical_stretch(Influence::constant, core::Setting::solid3d, m, G0, d, 1.0),
              std::sqrt(5.0 * G0 / (9.0 * m.bulk() * d)), 1e-15);
  // 1D, ω = 1: G₀ = (c s₀² A/2)(δ³/3) with c = 2E/(Aδ²) → s₀ = sqrt(3G₀/(Eδ)).
  EXPECT_NEAR(critical_stretch(Influence::constant, core::Setting::bar1d, m, G0, d, 1e-6), std::sqrt(3.0 * G0 / (m.E * d)),
              1e-15);
}

TEST(Constants, AllPositiveAndFinite) {
  for (core::Setting s : all_settings)
    for (Influence w : all_influences) {
      const core::Elastic m{70e9, s == core::Setting::plane_stress ? 1.0 / 3.0 : 0.25, 2700.0};
      const double meas = s == core::Setting::solid3d ? 1.0 : 1e-3;
      SCOPED_TRACE(std::string(name(s)) + " " + std::string(name(w)));
      for (int n = 0; n <= 5; ++n) {
        if (w == Influence::inverse_distance && n == 0) continue;  // ∫ δ/r dr diverges
        EXPECT_GT(influence_moment(w, n, 2e-3), 0.0) << "n = " << n;
      }
      EXPECT_GT(pmb_micromodulus(w, s, m, 2e-3, meas), 0.0);
      EXPECT_GT(lps_weighted_volume(w, s, 2e-3, meas), 0.0);
      const double s0 = critical_stretch(w, s, m, 1e3, 2e-3, meas);
      EXPECT_TRUE(std::isfinite(s0));
      EXPECT_GT(s0, 0.0);
    }
}

TEST(Constants, ScalingWithHorizonModulusAndFractureEnergy) {
  const double d = 2e-3, k = 1.7;
  for (core::Setting s : all_settings) {
    const int dim = dimension(s);
    const core::Elastic m{100e9, s == core::Setting::plane_stress ? 1.0 / 3.0 : 0.25, 1.0};
    const core::Elastic m2{2.0 * m.E, m.nu, 1.0};
    const double meas = s == core::Setting::solid3d ? 1.0 : 1e-3;
    for (Influence w : all_influences) {
      SCOPED_TRACE(std::string(name(s)) + " " + std::string(name(w)));
      // c ∝ E / δ^{d+1} (measure fixed), m ∝ δ^{d+2}, s₀ ∝ sqrt(G₀ / (E δ)).
      const double c = pmb_micromodulus(w, s, m, d, meas);
      EXPECT_NEAR(pmb_micromodulus(w, s, m, k * d, meas) / c, std::pow(k, -(dim + 1)), 1e-12);
      EXPECT_NEAR(pmb_micromodulus(w, s, m2, d, meas) / c, 2.0, 1e-14);
      EXPECT_NEAR(pmb_micromodulus(w, s, m, d, 2.0 * meas) / c, s == core::Setting::solid3d ? 1.0 : 0.5, 1e-14);
      const double mv = lps_weighted_volume(w, s, d, meas);
      EXPECT_NEAR(lps_weighted_volume(w, s, k * d, meas) / mv, std::pow(k, dim + 2), 1e-12);
      const double s0 = critical_stretch(w, s, m, 1e3, d, meas);
      EXPECT_NEAR(critical_stretch(w, s, m, 1e3, k * d, meas) / s0, 1.0 / std::sqrt(k), 1e-12);
      EXPECT_NEAR(critical_stretch(w, s, m2, 1e3, d, meas) / s0, 1.0 / std::sqrt(2.0), 1e-14);
      EXPECT_NEAR(critical_stretch(w, s, m, 4e3, d, meas) / s0, 2.0, 1e-14);
      EXPECT_NEAR(critical_stretch(w, s, m, 1e3, d, 2.0 * meas) / s0, 1.0, 1e-14);  // G₀ is per unit area
    }
  }
}

TEST(Constants, LpsDilatationTermVanishesAtThePmbPoissonRatio) {
  // The LPS volumetric coefficient A (3K − 5G in 3D, 2(κ₂ − 2G) in 2D) is zero
  // exactly at the Cauchy ν of a pair potential.
  EXPECT_NEAR(lps_coefficients(core::Setting::solid3d, {1.0, 0.25, 1.0}).A, 0.0, 1e-15);
  EXPECT_NEAR(lps_coefficients(core::Setting::plane_strain, {1.0, 0.25, 1.0}).A, 0.0, 1e-15);
  EXPECT_NEAR(lps_coefficients(core::Setting::plane_stress, {1.0, 1.0 / 3.0, 1.0}).A, 0.0, 1e-15);
  const auto c3 = lps_coefficients(core::Setting::solid3d, {1.0, 0.3, 1.0});
  EXPECT_EQ(c3.d, 3);
  EXPECT_NEAR(c3.gamma, 1.0 / 3.0, 1e-16);
  EXPECT_NEAR(c3.B, 15.0 / 2.6, 1e-14);  // 15G, G = E/(2(1+ν))
  const auto c1 = lps_coefficients(core::Setting::bar1d, {3.0, 0.3, 1.0});
  EXPECT_EQ(c1.B, 3.0);
  EXPECT_EQ(c1.A, 0.0);
}

TEST(Constants, LpsWithInverseDistanceEqualsPmbAtQuarterPoissonRatio) {
  // Deryugin et al. 2023 §5: with ω = 1/|ξ| and ν = 1/4, LPS reduces to PMB with constant ω.
  // The LPS pair force (t_ij + t_ji) = 2 B ω e / m with ω = δ/|ξ| must equal
  // PMB's c e/|ξ|, i.e. 2Bδ/m = c.
  const double d = 3e-3, h = 1e-3;
  const core::Elastic q{200e9, 0.25, 1.0}, third{200e9, 1.0 / 3.0, 1.0};
  struct Case {
    core::Setting s;
    core::Elastic m;
    double meas;
  };
  for (const Case& k :
       {Case{core::Setting::solid3d, q, 1.0}, Case{core::Setting::plane_strain, q, h}, Case{core::Setting::plane_stress, third, h}}) {
    const double B = lps_coefficients(k.s, k.m).B;
    const double mv = lps_weighted_volume(Influence::inverse_distance, k.s, d, k.meas);
    EXPECT_NEAR(2.0 * B * d / mv / pmb_micromodulus(Influence::constant, k.s, k.m, d, k.meas), 1.0, 1e-14) << name(k.s);
  }
}

TEST(Constants, MadenciOterkusByHand) {
  // docs/models/lps.md with E = 1, ν = 1/4 (G = 0.4, K = 2/3, κ₂ = λ + G = 0.8), δ = 1, unit measure.
  const core::Elastic m{1.0, 0.25, 1.0};
  const auto m3 = madenci_oterkus(core::Setting::solid3d, m, 1.0, 1.0);
  EXPECT_NEAR(m3.a, 0.5 * (2.0 / 3.0 - 5.0 * 0.4 / 3.0), 1e-15);
  EXPECT_NEAR(m3.b, 15.0 * 0.4 / (2.0 * pi), 1e-15);
  EXPECT_NEAR(m3.d, 9.0 / (4.0 * pi), 1e-15);
  const auto m2 = madenci_oterkus(core::Setting::plane_strain, m, 1.0, 1.0);
  EXPECT_NEAR(m2.a, 0.5 * (0.8 - 0.8), 1e-15);
  EXPECT_NEAR(m2.b, 6.0 * 0.4 / pi, 1e-15);
  EXPECT_NEAR(m2.d, 2.0 / pi, 1e-15);
  const auto m1 = madenci_oterkus(core::Setting::bar1d, m, 1.0, 1.0);
  EXPECT_EQ(m1.a, 0.0);
  EXPECT_NEAR(m1.b, 0.5, 1e-16);
  EXPECT_NEAR(m1.d, 0.5, 1e-16);
}

}  // namespace
}  // namespace pdmpm::pd
