// The incremental sub-horizon rebuild (solver/pd/sub_horizon.cpp) after bonds break or heal is a
// full build bit for bit: every array of the structure, and the forces of the model on it, with
// 1 and 2 threads.
#include "solver/pd/sub_horizon.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <cstring>
#include <random>

#include "solver/pd/hpd.hpp"
#include "verification/support/pd_fixtures.hpp"
#include "verification/support/same_bits.hpp"

namespace pdmpm::pd {
namespace {

using test::same_bits;

template <int D>
void expect_same(const SubHorizon<D>& a, const SubHorizon<D>& b, const std::string& where) {
  EXPECT_TRUE(same_bits(a.begin, b.begin)) << where;
  EXPECT_TRUE(same_bits(a.point, b.point)) << where;
  EXPECT_TRUE(same_bits(a.coef, b.coef)) << where;
  EXPECT_TRUE(same_bits(a.axial, b.axial)) << where;
  EXPECT_TRUE(same_bits(a.volume, b.volume)) << where;
  EXPECT_TRUE(same_bits(a.centroid, b.centroid)) << where;
  EXPECT_TRUE(same_bits(a.volume_inverse, b.volume_inverse)) << where;
  EXPECT_TRUE(same_bits(a.inv_volume, b.inv_volume)) << where;
  EXPECT_TRUE(same_bits(a.inv_second_moment, b.inv_second_moment)) << where;
  EXPECT_TRUE(same_bits(a.at_begin, b.at_begin)) << where;
  EXPECT_TRUE(same_bits(a.at_bond, b.at_bond)) << where;
  EXPECT_TRUE(same_bits(a.at_coef, b.at_coef)) << where;
  EXPECT_TRUE(same_bits(a.entry_at, b.entry_at)) << where;
  EXPECT_TRUE(same_bits(a.built_live, b.built_live)) << where;
  EXPECT_EQ(a.n_axial, b.n_axial) << where;
}

// Breaks the bond sides of a random 40 % of the bonds of a few random particles (single sides
// too, so the rule is tested per side), and all but one bond of one particle (both sides),
// which puts its bonds on the axial fallback.
template <int D>
void break_some(System<D>& sys, std::mt19937& rng) {
  const auto& f = sys.families;
  std::uniform_int_distribution<Index> particle(0, sys.n_real() - 1);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (int k = 0; k < 4; ++k) {
    const Index i = particle(rng);
    for (BondIndex b = f.begin(i); b < f.end(i); ++b)
      if (uni(rng) < 0.4) sys.bonds.flags.trial[b] |= kBondBroken;
  }
  const Index lonely = particle(rng);
  for (BondIndex b = f.begin(lonely) + 1; b < f.end(lonely); ++b) {
    sys.bonds.flags.trial[b] |= kBondBroken;
    const Index j = f.neighbor[b];
    for (BondIndex c = f.begin(j); c < f.end(j); ++c)
      if (f.neighbor[c] == lonely) sys.bonds.flags.trial[c] |= kBondBroken;
  }
}

template <int D>
std::vector<Vec<D>> forces(Hpd<D>& hpd, System<D>& sys) {
  ForceRequest req;
  hpd.compute_forces(sys, req);
  return {sys.particles.f.begin(), sys.particles.f.begin() + sys.n_real()};
}

template <int D>
void incremental_equals_full(int sites, double horizon_ratio) {
  test::BlockSpec spec;
  spec.sites = sites;
  spec.horizon_ratio = horizon_ratio;
  spec.setting = D == 2 ? core::Setting::plane_strain : core::Setting::solid3d;
  spec.material = {200e9, 0.3, 7850.0};
  auto sys = test::make_block<D>(spec);
  sys.hpd.law = HpdLaw::linear_elastic;
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (auto& u : sys.particles.u)
    for (int a = 0; a < D; ++a) u[a] = 1e-6 * uni(rng);
  const int saved = omp_get_max_threads();
  Hpd<D> one, two;  // rebuilt incrementally inside compute_forces, with 1 and 2 threads
  one.initialise(sys);
  two.initialise(sys);
  // Three rounds: breaks on the first build, more breaks on an incremental one, then a heal
  // (what a rejected step does) of part of them.
  for (int round = 0; round < 3; ++round) {
    const std::string where = std::to_string(D) + "D round " + std::to_string(round);
    if (round < 2) {
      break_some(sys, rng);
    } else {
      std::bernoulli_distribution heal(0.5);
      for (auto& flag : sys.bonds.flags.trial)
        if (flag && heal(rng)) flag = 0;
    }
    omp_set_num_threads(1);
    const auto f1 = forces(one, sys);
    omp_set_num_threads(2);
    const auto f2 = forces(two, sys);
    omp_set_num_threads(saved);
    Hpd<D> fresh;
    fresh.initialise(sys);
    const auto f0 = forces(fresh, sys);
    if (round == 0) {
      EXPECT_GT(fresh.sub_horizon().n_axial, 0) << where << ": the fallback is not exercised";
    }
    expect_same(one.sub_horizon(), fresh.sub_horizon(), where + ", 1 thread");
    expect_same(two.sub_horizon(), fresh.sub_horizon(), where + ", 2 threads");
    EXPECT_TRUE(same_bits(f1, f0)) << where << ", 1 thread";
    EXPECT_TRUE(same_bits(f2, f0)) << where << ", 2 threads";
  }
}

// 3D at δ = 2.015 Δx keeps the test small (a 3.015 Δx family stores ~0.4 MB per particle); the
// rule does not depend on δ.
TEST(SubHorizon, IncrementalRebuildEqualsAFullBuildBitForBit2D) { incremental_equals_full<2>(14, 3.015); }
TEST(SubHorizon, IncrementalRebuildEqualsAFullBuildBitForBit3D) { incremental_equals_full<3>(8, 2.015); }

}  // namespace
}  // namespace pdmpm::pd
