#include "solver/dist/decomposition.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <set>

#include "solver/core/families.hpp"
#include "solver/core/shapes.hpp"

namespace pdmpm::dist {
namespace {

core::BodySites<2> plate() {
  core::Geometry<2> g;
  g.add(std::make_unique<core::Box<2>>(Vec<2>(0.0, 0.0), Vec<2>(0.030, 0.017)));
  core::Lattice<2> lat;
  lat.spacing = 1e-3;
  lat.origin = Vec<2>(5e-4, 5e-4);
  return core::body_sites<2>(g, lat, 1e-6);
}

TEST(Decomposition, RangesCoverTheBodyOnceAndOwnerRankInvertsThem) {
  for (const Index n : {0, 1, 7, 510, 1000})
    for (int ranks = 1; ranks <= 7; ++ranks) {
      Index next = 0;
      for (int r = 0; r < ranks; ++r) {
        const auto own = owned_range(n, r, ranks);
        EXPECT_EQ(own.begin, next);
        EXPECT_GE(own.end, own.begin);
        next = own.end;
        for (Index g = own.begin; g < own.end; ++g) ASSERT_EQ(owner_rank(g, n, ranks), r) << n << " " << ranks;
      }
      EXPECT_EQ(next, n);
    }
}

TEST(Decomposition, HaloIsExactlyTheOtherProcessesStencilNeighbours) {
  const auto sites = plate();
  const auto body = sites.particles(0, sites.size());
  const auto stencil = core::Stencil<2>::build(3.015);
  const auto own = owned_range(body.n_real, 1, 3);
  const auto halo = halo_of(sites, stencil, own).global;
  std::set<Index> expected;
  for (Index i = own.begin; i < own.end; ++i)
    for (Index j = 0; j < body.n_real; ++j)
      if (!own.contains(j) && (body.x0[i] - body.x0[j]).norm() <= 3.015e-3 * (1 + 1e-10)) expected.insert(j);
  EXPECT_EQ(std::vector<Index>(expected.begin(), expected.end()), halo);
  EXPECT_FALSE(halo.empty());
}

TEST(Decomposition, LocalFamiliesAreTheWholeBodysInTheSameOrder) {
  const auto sites = plate();
  const auto whole = core::Families<2>::build(sites.particles(0, sites.size()), 3.015);
  for (int r = 0; r < 3; ++r) {
    const auto own = owned_range(sites.size(), r, 3);
    const auto [halo, own_bonds] = halo_of(sites, whole.stencil, own);
    // The count a run checks its families against: the whole body's bonds of these particles.
    EXPECT_EQ(own_bonds, whole.offsets[own.end] - whole.offsets[own.begin]);
    const auto local = sites.particles(own.begin, own.end, halo);
    ASSERT_EQ(local.n_real, own.size());
    ASSERT_EQ(local.n_ghost(), static_cast<Index>(halo.size()));
    for (Index g = 0; g < local.n_ghost(); ++g) EXPECT_EQ(local.ghost_owner[g], core::Particles<2>::kRemoteOwner);
    const auto fam = core::Families<2>::build(local, 3.015);
    const auto global = [&](Index j) { return j < local.n_real ? own.begin + j : halo[j - local.n_real]; };
    for (Index i = 0; i < local.n_real; ++i) {
      const Index gi = own.begin + i;
      ASSERT_EQ(fam.end(i) - fam.begin(i), whole.end(gi) - whole.begin(gi)) << "particle " << gi;
      for (BondIndex b = fam.begin(i), w = whole.begin(gi); b < fam.end(i); ++b, ++w) {
        EXPECT_EQ(global(fam.neighbor[b]), whole.neighbor[w]);
        EXPECT_EQ(fam.shape[b], whole.shape[w]);
      }
    }
  }
}

}  // namespace
}  // namespace pdmpm::dist
