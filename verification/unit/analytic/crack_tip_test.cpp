#include "solver/analytic/crack_tip.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace pdmpm::analytic {
namespace {

// A short crack is Griffith's σ√(πa); a wider crack raises K; and Tada's polynomial factor only
// corrects Feddersen's secant formula √sec(πα/2), by less than 0.3 % for α ≤ 0.7 (both in
// Tada, Paris & Irwin §2.1).
TEST(CentreCrack, ShortCrackIsGriffithsAndWideningRaisesK) {
  EXPECT_DOUBLE_EQ(centre_crack_factor(0.0), 1.0);
  EXPECT_NEAR(centre_crack_k1(10e6, 0.01, 1e9), 10e6 * std::sqrt(M_PI * 0.01), 1.0);
  double previous = 1.0;
  for (double alpha = 0.1; alpha <= 0.7001; alpha += 0.1) {
    const double f = centre_crack_factor(alpha), feddersen = std::sqrt(1.0 / std::cos(0.5 * M_PI * alpha));
    EXPECT_GT(f, previous);
    EXPECT_NEAR(f / feddersen, 1.0, 3e-3) << "α = " << alpha;
    previous = f;
  }
}

WilliamsModeOne field(core::Setting s) {
  WilliamsModeOne w;
  w.k1 = 1e6;
  w.material.E = 70e9, w.material.nu = 0.33;
  w.setting = s;
  return w;
}

// The displacement gradient by central differences of the displacement, and the stress by
// Hooke's law of its symmetric part: the three formulas describe one field.
TEST(WilliamsModeOne, GradientAndStressAgreeWithTheDisplacement) {
  for (core::Setting s : {core::Setting::plane_stress, core::Setting::plane_strain}) {
    const WilliamsModeOne w = field(s);
    for (double th : {-2.5, -1.0, 0.3, 1.7, 2.9}) {
      const double r = 1e-3, x = r * std::cos(th), y = r * std::sin(th), h = 1e-9;
      const auto g = w.displacement_gradient(x, y);
      const auto up = w.displacement(x + h, y), um = w.displacement(x - h, y);
      const auto vp = w.displacement(x, y + h), vm = w.displacement(x, y - h);
      const double scale = std::abs(g[0]) + std::abs(g[1]) + std::abs(g[2]) + std::abs(g[3]);
      EXPECT_NEAR(g[0], (up[0] - um[0]) / (2 * h), 1e-6 * scale);
      EXPECT_NEAR(g[1], (vp[0] - vm[0]) / (2 * h), 1e-6 * scale);
      EXPECT_NEAR(g[2], (up[1] - um[1]) / (2 * h), 1e-6 * scale);
      EXPECT_NEAR(g[3], (vp[1] - vm[1]) / (2 * h), 1e-6 * scale);
      const double E = w.material.E, nu = w.material.nu, G = w.material.shear();
      const double exx = g[0], eyy = g[3], exy = 0.5 * (g[1] + g[2]);
      double sxx, syy;
      if (s == core::Setting::plane_stress) {
        sxx = E / (1 - nu * nu) * (exx + nu * eyy), syy = E / (1 - nu * nu) * (eyy + nu * exx);
      } else {
        const double lam = w.material.lame();
        sxx = lam * (exx + eyy) + 2 * G * exx, syy = lam * (exx + eyy) + 2 * G * eyy;
      }
      const auto sig = w.stress(x, y);
      const double sscale = std::abs(sig[0]) + std::abs(sig[1]) + std::abs(sig[2]);
      EXPECT_NEAR(sig[0], sxx, 1e-9 * sscale);
      EXPECT_NEAR(sig[1], syy, 1e-9 * sscale);
      EXPECT_NEAR(sig[2], 2 * G * exy, 1e-9 * sscale);
    }
  }
}

// The crack faces (θ = ±π) carry no traction, and ahead of the tip σ_yy = K/√(2πr).
TEST(WilliamsModeOne, FacesAreFreeAndTheLigamentCarriesK) {
  const WilliamsModeOne w = field(core::Setting::plane_stress);
  const double r = 2e-3, eps = 1e-12;
  for (double sgn : {1.0, -1.0}) {
    const auto s = w.stress(-r, sgn * eps);
    EXPECT_NEAR(s[1], 0.0, 1e-6 * w.k1 / std::sqrt(r));
    EXPECT_NEAR(s[2], 0.0, 1e-6 * w.k1 / std::sqrt(r));
  }
  EXPECT_NEAR(w.stress(r, 0.0)[1], w.k1 / std::sqrt(2 * M_PI * r), 1e-9 * w.k1);
}

}  // namespace
}  // namespace pdmpm::analytic
