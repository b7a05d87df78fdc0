// Elastoplastic LPS in the 2D settings. The out-of-plane strain is not a PD degree of
// freedom: each particle carries the axial deviator q_p (docs/models/lps_plastic.md, "2D"),
// eliminated by ε_zz = 0 (plane strain) or σ_zz = 0 (plane stress). Checked here: below
// yield the model is elastic 2D LPS; homogeneous paths follow J2 exactly as integrated by
// an independent return map (MPM's: Simo & Taylor's projected plane-stress return and the
// 3D radial return); equibiaxial plane stress yields at σ_y (a return on the in-plane
// deviator alone never would); flow is isochoric in 3D; reject() restores q_p.
// Small strains (ε_y = 1e-5) isolate the constitutive algorithm from the bond kinematics'
// geometric nonlinearity.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/mpm/j2_plasticity.hpp"
#include "solver/pd/lps_plastic.hpp"
#include "verification/support/plastic_paths.hpp"

namespace pdmpm::pd {
namespace {

const core::Elastic kSteel{215e9, 0.33, 7800.0};
const double kYield = 2.15e6;                      // σ_y = 1e-5 E
const core::J2Hardening kHardening{kYield, 20e9};  // E_t ≈ E/11: hardening visible on the scale of σ_y

test::PlasticBlock<2> plate(core::Setting s, bool isotropic = true) {
  return test::PlasticBlock<2>({.material = kSteel, .hardening = kHardening, .isotropic = isotropic, .setting = s});
}

const core::Setting kPlanar[] = {core::Setting::plane_stress, core::Setting::plane_strain};

// The in-plane strain embedded in 3D (ε_zz = 0; the plane-stress return finds its own).
Mat<3> embed(const Mat<2>& e) {
  Mat<3> out = Mat<3>::Zero();
  out.topLeftCorner<2, 2>() = e;
  return out;
}

TEST(LpsPlastic2d, BelowYieldItIsElasticLps) {
  for (core::Setting s : kPlanar) {
    auto b = plate(s, false);
    for (Index i = 0; i < b.sys.n_real(); ++i) {
      const Vec<2> x = b.sys.particles.x0[i];
      b.sys.particles.u[i] = Vec<2>(1e-10 * std::sin(x[1] * 700.0), 2e-10 * std::cos(x[0] * 500.0) + 1e-7 * x[0] * x[1]);
    }
    // 1e-12: the same sums in another order, and the mean stress through K, G instead of κ₂.
    EXPECT_LT(b.difference_from_elastic_lps(), 1e-12) << name(s);
    EXPECT_EQ(b.eq_plastic_strain(), 0.0) << name(s);
  }
}

// Plane stress, uniaxial along a lattice axis and a skew one: the analytic bilinear curve.
TEST(LpsPlastic2d, PlaneStressUniaxialFollowsTheBilinearCurve) {
  const double E = kSteel.E, nu = kSteel.nu, Et = kHardening.tangent_modulus, ey = kYield / E;
  auto bilinear = [&](double e) { return e <= ey ? E * e : kYield + Et * (e - ey); };
  const Mat<2> skew = Eigen::Rotation2Dd(0.45).toRotationMatrix();
  for (const Mat<2>& R : {Mat<2>(Mat<2>::Identity()), skew}) {
    auto b = plate(core::Setting::plane_stress);
    double lateral = 0.0, worst = 0.0, worst_lateral = 0.0, worst_shear = 0.0;
    for (int k = 1; k <= 30; ++k) {
      const double eps = 10.0 * ey * k / 30;
      const Mat<2> s = b.uniaxial(eps, lateral, R);
      b.model.accept();
      const double exact = bilinear(eps), ep = eps - exact / E;
      worst = std::max(worst, std::abs(s(0, 0) - exact) / kYield);
      worst_lateral = std::max(worst_lateral, std::abs(lateral - (-nu * exact / E - 0.5 * ep)) / eps);
      worst_shear = std::max(worst_shear, std::abs(s(0, 1)) / kYield);
    }
    const char* axis = R.isIdentity() ? "[10]" : "skew";
    // 1e-3 of σ_y: only the O(ε) = 1e-4 bond nonlinearity separates the two.
    EXPECT_LT(worst, 1e-3) << axis << ": worst |σ − σ_J2| / σ_y";
    EXPECT_LT(worst_lateral, 1e-3) << axis << ": lateral strain −νσ/E − ε_p/2";
    EXPECT_LT(worst_shear, 1e-3) << axis;
    const double ep_expected = 10.0 * ey - bilinear(10.0 * ey) / E;
    EXPECT_NEAR(b.eq_plastic_strain() / ep_expected, 1.0, 1e-3) << axis;
    EXPECT_EQ(b.model.out_of_plane_stress(b.centre), 0.0);
  }
}

// A general in-plane path (stretch, shear, then unloading) against the independent
// return of MPM's J2 on the same strain: stresses (σ_zz too) and ε̄_p.
TEST(LpsPlastic2d, GeneralPathMatchesAnIndependentJ2Return) {
  const double ey = kYield / kSteel.E;
  Mat<2> direction;
  direction << 1.0, 0.3, 0.3, -0.2;
  for (core::Setting s : kPlanar) {
    auto b = plate(s);
    mpm::PointHistory h;
    double worst = 0.0, worst_ep = 0.0;
    for (int k = 1; k <= 40; ++k) {
      const double load = k <= 30 ? 10.0 * k / 30 : 10.0 - 0.4 * (k - 30);  // to 10 ε_y, back to 6 ε_y
      const Mat<2> e = load * ey * direction;
      const Mat<2> pd_stress = b.stress_under(e);
      b.model.accept();
      const auto ref = s == core::Setting::plane_stress ? mpm::j2_return_plane_stress(kSteel, kHardening, embed(e), h, 0.0)
                                                         : mpm::j2_return_3d(kSteel, kHardening, embed(e), h, 0.0);
      worst = std::max(worst, (pd_stress - ref.T.topLeftCorner<2, 2>()).cwiseAbs().maxCoeff() / kYield);
      worst = std::max(worst, std::abs(b.model.out_of_plane_stress(b.centre) - ref.T(2, 2)) / kYield);
      worst_ep = std::max(worst_ep, std::abs(b.eq_plastic_strain() - h.eq_plastic_strain) / ey);
    }
    EXPECT_GT(h.eq_plastic_strain, 5.0 * ey) << name(s);
    // 1e-3: the bond kinematics' O(ε) nonlinearity and the log strain of the reference (O(ε²)).
    EXPECT_LT(worst, 1e-3) << name(s) << ": max |σ_PD − σ_J2| / σ_y";
    EXPECT_LT(worst_ep, 1e-3) << name(s) << ": max |ε̄_p − ε̄_p,J2| / ε_y";
  }
}

// Equibiaxial plane stress has no in-plane deviator, yet J2 yields at σ = σ_y: the axial
// deviator q carries it. Elastic slope E/(1 − ν), first yield within the 1 % step.
TEST(LpsPlastic2d, EquibiaxialPlaneStressYieldsAtTheYieldStress) {
  auto b = plate(core::Setting::plane_stress);
  const double slope = kSteel.E / (1.0 - kSteel.nu), ey_biaxial = kYield / slope;
  const double step = 0.01 * ey_biaxial;
  double first_yield = 0.0, worst_slope = 0.0;
  for (int k = 90; k <= 110; ++k) {
    const double eps = step * k;
    const double sigma = b.stress_under(eps * Mat<2>::Identity())(0, 0);
    b.model.accept();
    if (b.eq_plastic_strain() == 0.0)
      worst_slope = std::max(worst_slope, std::abs(sigma / (slope * eps) - 1.0));
    else if (first_yield == 0.0)
      first_yield = eps;
  }
  EXPECT_LT(worst_slope, 1e-3);
  ASSERT_GT(first_yield, 0.0) << "equibiaxial plane stress never yielded";
  EXPECT_GE(first_yield, ey_biaxial * (1.0 - 1e-6));
  EXPECT_LE(first_yield - step, ey_biaxial * (1.0 + 1e-6));
}

// Isochoric flow in 3D: tr σ = 3K (θ + ε_zz) along a plastic path, ε_zz the model's.
TEST(LpsPlastic2d, FlowIsIsochoricInThreeDimensions) {
  const double ey = kYield / kSteel.E, K = kSteel.bulk();
  for (core::Setting s : kPlanar) {
    auto b = plate(s);
    double lateral = 0.0, worst = 0.0;
    for (int k = 1; k <= 20; ++k) {
      const Mat<2> sigma = b.uniaxial(10.0 * ey * k / 20, lateral);
      b.model.accept();
      const double ezz = s == core::Setting::plane_stress ? (*b.model.out_of_plane_strain())[b.centre] : 0.0;
      const double trace = sigma.trace() + b.model.out_of_plane_stress(b.centre);
      worst = std::max(worst, std::abs(trace - 3.0 * K * (b.dilatation() + ezz)) / kYield);
    }
    EXPECT_GT(b.eq_plastic_strain(), 0.0);
    // 1e-6: the lateral strain is solved to 1e-9 σ_y; the O(ε) bond terms differ between σ and θ.
    EXPECT_LT(worst, 1e-6) << name(s);
  }
}

TEST(LpsPlastic2d, RejectRestoresTheAxialPlasticStrain) {
  auto b = plate(core::Setting::plane_stress);
  const double ey = kYield / kSteel.E;
  b.stress_under(10.0 * ey * Mat<2>::Identity());
  b.model.accept();
  const double ezz = (*b.model.out_of_plane_strain())[b.centre];
  b.stress_under(20.0 * ey * Mat<2>::Identity());
  b.model.reject();
  b.stress_under(10.0 * ey * Mat<2>::Identity());
  // Re-evaluating a state already on the yield surface: Newton's last step, round-off.
  EXPECT_NEAR((*b.model.out_of_plane_strain())[b.centre], ezz, 1e-12 * std::abs(ezz));
}

}  // namespace
}  // namespace pdmpm::pd
