// Ductile failure in the elastoplastic LPS model (Noorian et al. eqs 8–9): ε_f = d₀ exp(cη)
// with η the triaxiality of the particle's own stress. A particle fails in the evaluation
// where ε̄_p reaches ε_f (rule "strain") or ∫ dε̄_p/ε_f reaches 1 ("accumulated"), and then
// loses every bond on both sides. c < 0: higher triaxiality, earlier failure.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "solver/pd/lps_plastic.hpp"
#include "verification/support/plastic_paths.hpp"

namespace pdmpm::pd {
namespace {

const double kStrainYield = test::kSmallStrainYield / test::kSmallStrainSteel.E;

test::PlasticBlock<3> block(core::FailureRule rule, double d0, double c) {
  test::PlasticBlock<3> b(
      {.material = test::kSmallStrainSteel, .hardening = test::kSmallStrainHardening, .failure = {true, d0, c, rule}});
  b.request.break_bonds = true;
  b.request.critical_stretch = std::numeric_limits<double>::infinity();  // the ductile rule alone
  return b;
}

Mat<3> uniaxial_like(double eps) {  // the J2 lateral strain of uniaxial stress for a hardening bar
  const double E = test::kSmallStrainSteel.E, Et = test::kSmallStrainHardening.tangent_modulus;
  const double sigma = eps <= kStrainYield ? E * eps : test::kSmallStrainYield + Et * (eps - kStrainYield);
  const double lateral = -test::kSmallStrainSteel.nu * sigma / E - 0.5 * (eps - sigma / E);
  return Vec<3>(eps, lateral, lateral).asDiagonal();
}

Mat<3> simple_shear(double gamma) {
  Mat<3> H = Mat<3>::Zero();
  H(0, 1) = H(1, 0) = 0.5 * gamma;
  return H;
}

// Every particle, every step: it fails exactly when the rule applied to the state of that
// evaluation says so, and then loses every bond on both sides; no other bond breaks.
TEST(LpsPlasticFailure, ParticlesFailExactlyByTheRule) {
  for (core::FailureRule rule : {core::FailureRule::strain, core::FailureRule::accumulated})
    for (auto path : {uniaxial_like, simple_shear}) {
      auto b = block(rule, 20.0 * kStrainYield, -1.5);
      const auto r = b.load_until_failure(path, 0.5 * kStrainYield, 80);  // to 40 ε_y: past ε_f on both paths
      EXPECT_GT(r.failures, 0) << name(rule);
      EXPECT_EQ(r.mismatches, 0) << name(rule) << " after " << r.steps << " steps";
    }
}

// With c < 0 a shear path (η = 0) fails later than a uniaxial one (η = 1/3): at d₀ and at
// d₀ exp(c/3), to the step of the path.
TEST(LpsPlasticFailure, TriaxialityDecidesTheFractureStrain) {
  const double d0 = 20.0 * kStrainYield, c = -1.5, step = 0.2 * kStrainYield;
  const double tension = block(core::FailureRule::strain, d0, c).homogeneous_onset(uniaxial_like, step, 400);
  const double shear = block(core::FailureRule::strain, d0, c).homogeneous_onset(simple_shear, step, 400);
  // 2 %: the path's step in ε̄_p (0.2 ε_y: ≤ 1.7 % of ε_f here); η at small strain is exact to 1e-4.
  EXPECT_NEAR(tension / (d0 * std::exp(c / 3.0)), 1.0, 0.02);
  EXPECT_NEAR(shear / d0, 1.0, 0.02);
}

// A rejected evaluation leaves the bonds and the accumulated damage as they were.
TEST(LpsPlasticFailure, RejectUndoesAFailure) {
  const double d0 = 5.0 * kStrainYield, c = 0.0;
  auto b = block(core::FailureRule::accumulated, d0, c);
  const int live = b.live_sides(b.centre);
  b.stress_under(simple_shear(40.0 * kStrainYield));  // far beyond ε_f in one evaluation
  EXPECT_EQ(b.live_sides(b.centre), 0);
  b.model.reject();
  b.sys.bonds.reject();
  EXPECT_EQ(b.live_sides(b.centre), live);
  b.stress_under(simple_shear(kStrainYield));  // elastic: no flow, no failure
  EXPECT_EQ(b.live_sides(b.centre), live);
}

}  // namespace
}  // namespace pdmpm::pd
