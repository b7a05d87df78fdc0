#include "solver/core/stencil.hpp"

#include <gtest/gtest.h>

namespace pdmpm::core {
namespace {

TEST(Stencil, CountsMatchLatticeShells) {
  // Lattice points within radius 3 (excluding the centre): 2D 28, 3D 122.
  EXPECT_EQ(Stencil<2>::build(3.0).size(), 28);
  EXPECT_EQ(Stencil<3>::build(3.0).size(), 122);
  EXPECT_EQ(Stencil<3>::build(3.015).size(), 122);
  EXPECT_EQ(Stencil<1>::build(3.015).size(), 6);
}

TEST(Stencil, RoundOffInRatioStillReachesTheShell) {
  // δ/Δx computed in floating point as 2.9999999999999996 must keep the bond of length 3.
  EXPECT_EQ(Stencil<2>::build(0.0012 / 0.0004).size(), 28);
}

TEST(Stencil, SortedByLengthAndSymmetric) {
  const auto st = Stencil<3>::build(2.5);
  for (int k = 1; k < st.size(); ++k) EXPECT_LE(st.length2[k - 1], st.length2[k]);
  // Every offset's opposite is present.
  for (const auto& o : st.offset) {
    bool found = false;
    for (const auto& q : st.offset) found = found || q == -o;
    EXPECT_TRUE(found);
  }
}

}  // namespace
}  // namespace pdmpm::core
