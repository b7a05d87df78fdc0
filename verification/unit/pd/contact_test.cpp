// Short-range contact: the Verlet-listed forces equal a brute-force sum over all
// pairs, also after particles moved far enough to force a list rebuild.
#include "solver/pd/contact.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "verification/support/pd_fixtures.hpp"

namespace pdmpm::pd {
namespace {

// f_i = Σ_j (c_s/δ)(|y| − d_ij) y/|y| V_j over every j with |y| < d_ij (Deryugin et al. 2023 eq 6.2–6.4).
template <int D>
std::vector<Vec<D>> brute_force(const System<D>& sys, const ContactParameters& prm, double c) {
  const auto& p = sys.particles;
  const double reach = prm.max_distance * sys.spacing(), k = prm.stiffness_factor * c / sys.delta;
  std::vector<Vec<D>> f(p.n_real, Vec<D>::Zero());
  for (Index i = 0; i < p.n_real; ++i)
    for (Index j = 0; j < p.size(); ++j) {
      const Vec<D> y = p.position(j) - p.position(i);
      const double l = y.norm(), d = std::min(prm.distance_factor * (p.x0[j] - p.x0[i]).norm(), reach);
      if (j != i && l > 0.0 && l < d) f[i] += k * (l - d) * p.volume[j] / l * y;
    }
  return f;
}

TEST(ShortRangeContact, VerletListEqualsAllPairsAcrossRebuilds) {
  test::BlockSpec spec;
  spec.sites = 8;
  spec.setting = core::Setting::plane_strain;
  auto sys = test::make_block<2>(spec);
  ContactParameters prm;
  prm.bonded_pairs = true;  // every pair counts: no bonds needed to compare
  const double c = 1e20;
  ShortRangeContact<2> contact(prm, c);
  const double dx = sys.spacing();
  // The upper half slides past the lower one by 1.2 Δx per step, the two rows at
  // the interface pressed to 0.8 Δx apart: from step 2 on, pairs come within reach
  // whose reference distance exceeded the list's reach + skin at the previous build,
  // so a stale list would miss them.
  const double yc = 3.5 * dx + sys.particles.x0[0][1];
  for (int step = 0; step < 5; ++step) {
    for (Index i = 0; i < sys.n_real(); ++i) {
      const double side = sys.particles.x0[i][1] > yc ? 1.0 : -1.0;
      sys.particles.u[i] = Vec<2>(side * 0.6 * dx * step, -side * 0.1 * dx * (step > 0));
    }
    for (auto& f : sys.particles.f) f.setZero();
    const auto pairs = contact.add_forces(sys);
    const auto expected = brute_force(sys, prm, c);
    double worst = 0.0, scale = 1e-300;
    for (Index i = 0; i < sys.n_real(); ++i) {
      worst = std::max(worst, (sys.particles.f[i] - expected[i]).norm());
      scale = std::max(scale, expected[i].norm());
    }
    if (step >= 1) {
      EXPECT_GT(pairs, 0) << "step " << step;
    }
    EXPECT_LE(worst, 1e-12 * scale) << "step " << step;  // the same terms, summed in another order
  }
}

}  // namespace
}  // namespace pdmpm::pd
