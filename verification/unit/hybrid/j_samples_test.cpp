// hybrid::j_samples reads MPM and PD particles through one material law: under the same
// homogeneous deformation a PD particle and a material point give the same sample.
#include "solver/hybrid/j_samples.hpp"

#include <gtest/gtest.h>

#include "verification/support/hybrid_body.hpp"

namespace pdmpm::hybrid {
namespace {

const Vec<2> kCentre(0.015, 0.0075);  // the plate's centre: ≥ 2δ from every edge
const double kRadius = 1.2e-3;        // the centre's 4 nearest sites and their neighbours

Mat<2> stretch() {
  Mat<2> H;
  H << 4e-4, 1e-4, -0.5e-4, -1.2e-4;  // elastic: σ well below σ_y = 250 MPa
  return H;
}

std::vector<core::JSample> samples(Mode mode, const mpm::PointHistory* history = nullptr) {
  Settings s;
  s.mode = mode;
  test::HybridBody body(s);
  body.hybrid->start();
  auto& p = body.particles();
  const Mat<2> H = stretch();
  for (Index i = 0; i < p.n_real; ++i) {
    p.u[i] = H * p.x0[i];
    if (mode != Mode::pd) {
      if (history)
        body.mpm->set_state(i, Mat<2>::Identity() + H, *history);
      else
        body.mpm->set_deformation_gradient(i, Mat<2>::Identity() + H);
    }
  }
  const core::ParticleKind kind = mode == Mode::pd ? core::ParticleKind::pd : core::ParticleKind::mpm;
  for (Index i = 0; i < p.n_real; ++i)
    if ((p.x0[i] - kCentre).norm() < kRadius) {
      EXPECT_EQ(p.kind[i], kind) << "particle " << i;
    }
  return j_samples(*body.hybrid, kCentre, kRadius);
}

TEST(HybridJSamples, PdAndMpmGiveTheSameSampleOfAnAffineField) {
  const auto pd = samples(Mode::pd), mpm = samples(Mode::expand);  // expand without a pre-crack: all MPM
  ASSERT_EQ(pd.size(), mpm.size());
  ASSERT_GT(pd.size(), 0u);
  for (std::size_t k = 0; k < pd.size(); ++k) {
    EXPECT_EQ(pd[k].X, mpm[k].X);
    const double s = mpm[k].stress.norm();
    EXPECT_LT((pd[k].grad_u - stretch()).norm(), 1e-12 * stretch().norm());  // complete family: F exact
    EXPECT_LT((mpm[k].grad_u - stretch()).norm(), 1e-15);
    EXPECT_LT((pd[k].stress - mpm[k].stress).norm(), 1e-9 * s);
    EXPECT_NEAR(pd[k].energy, mpm[k].energy, 1e-9 * mpm[k].energy);
    EXPECT_GT(mpm[k].energy, 0.0);
  }
}

// W = elastic energy + σ_y ε̄_p + ½ H ε̄_p² (H = E E_t/(E − E_t) of the plate: 200 GPa, 2 GPa).
TEST(HybridJSamples, EnergyAddsThePlasticWorkOfAMonotonicPath) {
  mpm::PointHistory h;
  h.eq_plastic_strain = 0.01;
  const auto elastic = samples(Mode::expand), plastic = samples(Mode::expand, &h);
  ASSERT_EQ(elastic.size(), plastic.size());
  const double H = 200e9 * 2e9 / (200e9 - 2e9);
  for (std::size_t k = 0; k < elastic.size(); ++k)
    EXPECT_NEAR(plastic[k].energy - elastic[k].energy, 250e6 * 0.01 + 0.5 * H * 1e-4, 1e-6 * 250e6 * 0.01);
}

}  // namespace
}  // namespace pdmpm::hybrid
