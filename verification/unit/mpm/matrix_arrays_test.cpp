// MatrixArrays: a matrix written whole comes back whole, entry (i, j) of consecutive
// particles is consecutive in its array, and the packed form (a checkpoint's) round-trips.
#include "solver/mpm/matrix_arrays.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace pdmpm::mpm {
namespace {

Mat<3> numbered(Index p) {
  Mat<3> m;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) m(i, j) = 100.0 * p + 10.0 * i + j;
  return m;
}

TEST(MatrixArrays, AMatrixSetIsTheMatrixGotAndItsEntriesLieParticleByParticle) {
  MatrixArrays<3, 3> a;
  a.resize(5, Mat<3>::Identity());
  EXPECT_EQ(a.size(), 5);
  EXPECT_EQ(a.get(4), Mat<3>::Identity());
  for (Index p = 0; p < 5; ++p) a.set(p, numbered(p));
  for (Index p = 0; p < 5; ++p) EXPECT_EQ(a.get(p), numbered(p));
  // Entry (1, 2) of particles 0 … 4 is one array: what the lane passes copy eight at a time.
  for (Index p = 0; p < 5; ++p) EXPECT_EQ(a.entry(1, 2)[p], 100.0 * p + 12.0);
  const std::array<const double*, 4> plane = in_plane(a);
  EXPECT_EQ(plane[0][3], 300.0);  // (0, 0)
  EXPECT_EQ(plane[1][3], 310.0);  // (1, 0)
  EXPECT_EQ(plane[2][3], 301.0);  // (0, 1)
  EXPECT_EQ(plane[3][3], 311.0);  // (1, 1)
}

TEST(MatrixArrays, PackedMatricesRoundTrip) {
  MatrixArrays<2, 2> a;
  a.resize(3, Mat<2>::Zero());
  for (Index p = 0; p < 3; ++p) a.set(p, numbered(p).topLeftCorner<2, 2>());
  const std::vector<Mat<2>> packed = a.packed();
  ASSERT_EQ(packed.size(), 3u);
  MatrixArrays<2, 2> b;
  b.unpack(packed);
  ASSERT_EQ(b.size(), 3);
  for (Index p = 0; p < 3; ++p) EXPECT_EQ(b.get(p), a.get(p));
}

}  // namespace
}  // namespace pdmpm::mpm
