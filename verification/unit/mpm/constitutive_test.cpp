// Constitutive laws of MPM points: objectivity for every model and setting,
// small-strain limit = Hooke's law, hyperelastic stress = derivative of the energy.
#include "solver/mpm/constitutive.hpp"

#include <gtest/gtest.h>

#include <random>

#include "solver/mpm/kinematics.hpp"

namespace pdmpm::mpm {
namespace {

Material steel(MaterialModel m) { return {m, {200e9, 0.3, 7800.0}, {300e6, 2e9}}; }

template <int D>
Mat<D> rotation(double angle) {
  Mat<D> Q = Mat<D>::Identity();
  if constexpr (D == 2) Q << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  if constexpr (D == 3) Q = Eigen::AngleAxisd(angle, Vec<3>(1, 2, 3).normalized()).toRotationMatrix();
  return Q;
}

template <int D>
void check_objective(MaterialModel model, core::Setting setting, double strain) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Constitutive<D> law(steel(model), setting);
  for (int trial = 0; trial < 20; ++trial) {
    Mat<D> F = Mat<D>::Identity();
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) F(i, j) += strain * u(rng);
    PointHistory h1, h2;
    const StressResult a = law.update(F, h1);
    const Mat<D> Q = rotation<D>(0.3 + 2.0 * trial);
    const StressResult b = law.update(Q * F, h2);
    const Mat<3> Q3 = embed_deformation<D>(Q);
    // Round-off of the polar decomposition / eigen-solver acts on the strain at the
    // level of ~1e-15 absolute: stress error ~ E·1e-15, energy error ~ E·strain·1e-15.
    const double E = law.material().elastic.E;
    EXPECT_LT((b.kirchhoff - Q3 * a.kirchhoff * Q3.transpose()).norm(), 1e-11 * a.kirchhoff.norm() + 1e-14 * E)
        << name(model) << " " << name(setting);
    EXPECT_NEAR(a.energy, b.energy, 1e-11 * std::abs(a.energy) + 1e-13 * E * strain)
        << name(model) << " " << name(setting) << " " << strain;
    EXPECT_NEAR(h1.eq_plastic_strain, h2.eq_plastic_strain, 1e-12);
  }
}

TEST(Constitutive, ObjectiveForEveryModelAndSetting) {
  for (double strain : {1e-4, 1e-2, 0.2}) {
    for (auto m : {MaterialModel::linear_elastic, MaterialModel::j2}) {
      check_objective<2>(m, core::Setting::plane_stress, strain);
      check_objective<2>(m, core::Setting::plane_strain, strain);
      check_objective<3>(m, core::Setting::solid3d, strain);
    }
    check_objective<2>(MaterialModel::neo_hookean, core::Setting::plane_strain, strain);
    check_objective<3>(MaterialModel::neo_hookean, core::Setting::solid3d, strain);
  }
}

TEST(Constitutive, SmallStrainLimitIsHooke) {
  // For |H| = 1e-7 the log-strain/rotation corrections are O(|H|²) relative.
  Mat<3> H;
  H << 1, 2, -1, 0.5, -3, 1, 2, 0, 1.5;
  H *= 1e-7;
  const Material law = steel(MaterialModel::linear_elastic);
  const core::Elastic& m = law.elastic;
  const Mat<3> eps = 0.5 * (H + H.transpose());
  const Mat<3> hooke = m.lame() * eps.trace() * Mat<3>::Identity() + 2 * m.shear() * eps;
  for (auto model : {MaterialModel::linear_elastic, MaterialModel::neo_hookean}) {
    PointHistory hist;
    const StressResult r =
        Constitutive<3>({model, {200e9, 0.3, 7800}}, core::Setting::solid3d).update(Mat<3>::Identity() + H, hist);
    EXPECT_LT((r.kirchhoff - hooke).norm(), 1e-5 * hooke.norm()) << name(model);
  }
  // Plane stress: σ33 = 0 and ε33 = −ν/(1−ν)(ε11 + ε22).
  PointHistory hist;
  const Mat<2> F2 = Mat<2>::Identity() + H.topLeftCorner<2, 2>();
  const StressResult r = Constitutive<2>(law, core::Setting::plane_stress).update(F2, hist);
  const double c = m.E / (1 - m.nu * m.nu);
  EXPECT_NEAR(r.kirchhoff(0, 0), c * (eps(0, 0) + m.nu * eps(1, 1)), 1e-5 * c * 1e-7);
  EXPECT_EQ(r.kirchhoff(2, 2), 0.0);
  EXPECT_NEAR(r.out_of_plane_strain, -m.nu / (1 - m.nu) * (eps(0, 0) + eps(1, 1)), 1e-5 * 1e-7);
  // Bar: uniaxial stress E ε.
  const StressResult b = Constitutive<1>(law, core::Setting::bar1d).update(Mat<1>(1.0 + 1e-7), hist);
  EXPECT_NEAR(b.kirchhoff(0, 0), m.E * std::log(1.0 + 1e-7), 1e-9);
}

// τ = (∂W/∂F) Fᵀ at a general F, with ∂W/∂F by central differences of W (step 1e-6:
// truncation ~1e-12 and round-off ~1e-10 relative, well inside the 1e-6 bound).
void expect_kirchhoff_is_energy_derivative(const Constitutive<3>& law) {
  Mat<3> F;
  F << 1.2, 0.1, -0.05, 0.03, 0.9, 0.2, -0.1, 0.05, 1.1;
  PointHistory h;
  const StressResult r = law.update(F, h);
  Mat<3> P;
  const double eps = 1e-6;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      Mat<3> Fp = F, Fm = F;
      Fp(i, j) += eps;
      Fm(i, j) -= eps;
      PointHistory a, b;
      P(i, j) = (law.update(Fp, a).energy - law.update(Fm, b).energy) / (2 * eps);
    }
  EXPECT_LT((P * F.transpose() - r.kirchhoff).norm(), 1e-6 * r.kirchhoff.norm());
}

TEST(Constitutive, NeoHookeanStressIsEnergyDerivative) {
  expect_kirchhoff_is_energy_derivative({{MaterialModel::neo_hookean, {1e7, 0.3, 1000}}, core::Setting::solid3d});
}

TEST(Constitutive, HenckyStressIsEnergyDerivative3D) {
  expect_kirchhoff_is_energy_derivative({{MaterialModel::linear_elastic, {1e7, 0.3, 1000}}, core::Setting::solid3d});
}

TEST(Kinematics, PolarLogRecoversRotationAndStretch) {
  for (double angle : {0.0, 0.7, -2.5, 3.1}) {
    Mat<2> U;
    U << 1.3, 0.2, 0.2, 0.8;
    const Mat<2> F = rotation<2>(angle) * U;
    const PolarLog<2> p = polar_log<2>(F);
    EXPECT_LT((p.R - rotation<2>(angle)).norm(), 1e-14);
    Eigen::SelfAdjointEigenSolver<Mat<2>> e(U);
    const Mat<2> lnU =
        e.eigenvectors() * e.eigenvalues().array().log().matrix().asDiagonal() * e.eigenvectors().transpose();
    EXPECT_LT((p.log_U - lnU).norm(), 1e-14);
  }
  Mat<3> U3;
  U3 << 1.3, 0.2, 0.0, 0.2, 0.8, 0.1, 0.0, 0.1, 1.05;
  const Mat<3> Q = rotation<3>(1.1);
  const PolarLog<3> p3 = polar_log<3>(Q * U3);
  EXPECT_LT((p3.R - Q).norm(), 1e-13);
  // Nearly equal stretches: the 2D closed form must not lose digits.
  Mat<2> Ue;
  Ue << 1.0 + 1e-9, 1e-12, 1e-12, 1.0 + 1e-9 + 1e-13;
  const PolarLog<2> pe = polar_log<2>(Ue);
  // Storing 1 + 1e-9 rounds by ≤ 1.1e-16: that bounds what ln U can recover.
  EXPECT_NEAR(pe.log_U(0, 0), std::log1p(1e-9), 2.3e-16);
  EXPECT_NEAR(pe.log_U(0, 1), 1e-12, 1e-20);
}

// 3D: near the identity ln U and R come from series in C's deviator (|X| < 0.1), beyond
// it from the eigen-decomposition; both against the decomposition, at strains from 1e-6
// to 10 % (both paths), under random rotations.
TEST(Kinematics, PolarLog3dBySeriesIsTheEigenDecompositions) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0), angle(-3.1, 3.1);
  for (const double strain : {1e-6, 1e-3, 1e-2, 0.03, 0.1}) {
    double worst_log = 0.0, worst_R = 0.0;
    for (int i = 0; i < 2000; ++i) {
      Mat<3> G;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) G(a, b) = u(rng);
      const Mat<3> Usym = Mat<3>::Identity() + strain * 0.5 * (G + G.transpose());
      const Eigen::AngleAxisd turn(angle(rng), Vec<3>(u(rng), u(rng), u(rng)).normalized());
      const Mat<3> F = turn.toRotationMatrix() * Usym;
      const PolarLog<3> p = polar_log<3>(F);
      Eigen::SelfAdjointEigenSolver<Mat<3>> e(F.transpose() * F);
      const Mat<3>& Q = e.eigenvectors();
      const Vec<3> lam = e.eigenvalues();
      const Mat<3> lnU = Q * (0.5 * lam.array().log()).matrix().asDiagonal() * Q.transpose();
      const Mat<3> R = F * (Q * lam.array().rsqrt().matrix().asDiagonal() * Q.transpose());
      worst_log = std::max(worst_log, (p.log_U - lnU).norm());
      worst_R = std::max(worst_R, (p.R - R).norm());
      EXPECT_LT((p.R.transpose() * p.R - Mat<3>::Identity()).norm(), 1e-14);
    }
    // Both are ln U to round-off; the decomposition's is a few ulps of |C| ≈ √3 (measured
    // ≤ 2e-15 at every strain here), whatever the size of ln U. R to a few ulps.
    EXPECT_LT(worst_log, 5e-15) << "strain " << strain;
    EXPECT_LT(worst_R, 1e-14) << "strain " << strain;
  }
}

TEST(Kinematics, CayleyIncrementOfSkewIsOrthogonal) {
  Mat<3> W;
  W << 0, -2, 1, 2, 0, -3, -1, 3, 0;
  const Mat<3> Q = cayley_increment<3>(W, 0.1);
  EXPECT_LT((Q.transpose() * Q - Mat<3>::Identity()).norm(), 1e-15);
  EXPECT_NEAR(Q.determinant(), 1.0, 1e-15);
}

}  // namespace
}  // namespace pdmpm::mpm
