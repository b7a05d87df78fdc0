#include "solver/core/families.hpp"

#include <gtest/gtest.h>

#include "solver/core/particle_builder.hpp"

namespace pdmpm::core {
namespace {

Particles<2> square(int n) {
  Lattice<2> lat;
  Geometry<2> g;
  g.add(std::make_unique<Box<2>>(Vec<2>::Zero(), Vec<2>::Constant(n - 1)));
  return fill_lattice<2>(g, lat, 1.0);
}

TEST(Families, InteriorFamilyIsTheFullStencilAndBondsAreSymmetric) {
  const auto p = square(12);
  const auto fam = Families<2>::build(p, 3.0);
  Index interior_count = 0;
  for (Index i = 0; i < p.n_real; ++i) {
    const bool interior = (p.site[i].array() >= 3).all() && (p.site[i].array() <= 8).all();
    if (interior) {
      EXPECT_EQ(fam.end(i) - fam.begin(i), 28);
      ++interior_count;
    }
    for (BondIndex b = fam.begin(i); b < fam.end(i); ++b) {
      const Index j = fam.neighbor[b];
      EXPECT_EQ(p.site[j] - p.site[i], fam.stencil.offset[fam.shape[b]]);
      bool back = false;
      for (BondIndex c = fam.begin(j); c < fam.end(j); ++c) back = back || fam.neighbor[c] == i;
      EXPECT_TRUE(back);
    }
  }
  EXPECT_EQ(interior_count, 36);
}

TEST(Families, SingleParticleHasAnEmptyFamily) {
  const auto p = square(1);
  const auto fam = Families<2>::build(p, 3.0);
  EXPECT_EQ(fam.n_bonds(), 0);
  EXPECT_EQ(fam.n_owners(), 1);
}

}  // namespace
}  // namespace pdmpm::core
