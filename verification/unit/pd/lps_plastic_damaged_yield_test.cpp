// damaged_yield = "live_bonds" (docs/models/lps_plastic.md, "Damaged particles"): a particle
// with broken bonds reads its equivalent stress over its live bonds' weighted volume, so its
// live bonds follow the intact J2 law; an intact particle is untouched. The damaged centre
// here has lost the half of its family below it (a centrally symmetric family: the other half
// holds exactly half of every even bond moment), so under a homogeneous deviatoric strain its
// live bonds see what an intact particle's do; the plastic work stays the forces' dissipation.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/pd/lps_plastic.hpp"
#include "verification/support/plastic_paths.hpp"

namespace pdmpm::pd {
namespace damaged_yield_test {

const core::Elastic kSteel{215e9, 0.33, 7800.0};
const core::J2Hardening kHardening{2.15e6, 20e9};  // σ_y = 1e-5 E: small strains

template <int D>
test::PlasticBlock<D> block(core::Setting s, bool live_bonds) {
  test::PlasticBlock<D> b({.material = kSteel, .hardening = kHardening, .setting = s});
  b.sys.yield_on_live_bonds = live_bonds;
  return b;
}

// Breaks (not cuts: they stay in the reference family) the centre's bonds whose offset points
// into the lower half space (last non-zero component negative).
template <int D>
void break_lower_half(test::PlasticBlock<D>& b) {
  auto& sys = b.sys;
  for (BondIndex k = sys.families.begin(b.centre); k < sys.families.end(b.centre); ++k) {
    const Vec<D>& xi = sys.table.xi[sys.families.shape[k]];
    int a = D - 1;
    while (a > 0 && xi[a] == 0.0) --a;
    if (xi[a] < 0.0) {
      sys.bonds.flags.trial[k] |= kBondBroken;
      sys.bonds.flags.committed[k] |= kBondBroken;
    }
  }
}

// ε̄_p of the centre along a pure shear to 6 γ_y, one accepted step at a time; `centre_work`
// adds up the work the model books for the centre, V σ̄ Δε̄_p.
template <int D>
std::vector<double> shear_path(test::PlasticBlock<D>& b, double* centre_work = nullptr) {
  const double gamma_y = 2.0 * (1.0 + kSteel.nu) * kHardening.yield_stress / (std::sqrt(3.0) * kSteel.E);
  std::vector<double> ep;
  double before = 0.0;
  for (int k = 1; k <= 24; ++k) {
    b.shear(6.0 * gamma_y * k / 24);
    b.model.accept();
    ep.push_back(b.eq_plastic_strain());
    if (centre_work)
      *centre_work += b.sys.particles.volume[b.centre] * b.model.equivalent_stress(b.centre) * (ep.back() - before);
    before = ep.back();
  }
  return ep;
}

template <int D>
void check(core::Setting s) {
  // Intact: the option changes nothing, bit for bit.
  auto off = block<D>(s, false), on = block<D>(s, true);
  EXPECT_EQ(shear_path(off), shear_path(on)) << name(s);

  // Damaged, read on the live bonds: the intact particle's ε̄_p along the whole path.
  auto intact = block<D>(s, true), damaged = block<D>(s, true), late = block<D>(s, false);
  break_lower_half(damaged);
  break_lower_half(late);
  double intact_centre_work = 0.0;
  const auto ep_intact = shear_path(intact, &intact_centre_work), ep_damaged = shear_path(damaged),
             ep_late = shear_path(late);
  double worst = 0.0;
  for (std::size_t k = 0; k < ep_intact.size(); ++k)
    worst = std::max(worst, std::abs(ep_damaged[k] - ep_intact[k]) / std::max(ep_intact.back(), 1e-300));
  // 1e-9 of the final ε̄_p: half sums of a symmetric family against whole ones differ by round-off.
  EXPECT_LT(worst, 1e-9) << name(s);
  EXPECT_GT(ep_intact.back(), 0.0) << name(s);
  // The plastic work is the forces' dissipation: the damaged centre's live bonds flow as the
  // intact centre's, and it has half of them, so it dissipates half (every other particle is
  // the same in both blocks). 1e-9: round-off of the half sums, as above.
  EXPECT_GT(intact_centre_work, 0.0);
  EXPECT_NEAR((intact.model.plastic_work() - damaged.model.plastic_work()) / intact_centre_work, 0.5, 1e-9) << name(s);
  // Read on the reference family, the damaged centre yields late: less flow at every step.
  for (std::size_t k = 0; k < ep_intact.size(); ++k)
    if (ep_intact[k] > 0.0) {
      EXPECT_LT(ep_late[k], ep_intact[k]) << name(s) << " step " << k;
    }
}

TEST(LpsPlasticDamagedYield, LiveBondsFollowTheIntactLaw3d) { check<3>(core::Setting::solid3d); }
TEST(LpsPlasticDamagedYield, LiveBondsFollowTheIntactLawPlaneStrain) { check<2>(core::Setting::plane_strain); }
TEST(LpsPlasticDamagedYield, LiveBondsFollowTheIntactLawPlaneStress) { check<2>(core::Setting::plane_stress); }

}  // namespace damaged_yield_test
}  // namespace pdmpm::pd
