#include "solver/core/cell_list.hpp"
#include "solver/core/error.hpp"

#include <gtest/gtest.h>

#include <random>
#include <set>

namespace pdmpm::core {
namespace {

TEST(CellList, FindsEveryPointWithinOneCell) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec<3>> pts(500);
  for (auto& x : pts) x = Vec<3>(u(rng), u(rng), u(rng));
  CellList<3> cl;
  const double h = 0.1;
  cl.build(pts, h);
  for (std::size_t i = 0; i < pts.size(); i += 37) {
    std::set<Index> near;
    cl.for_each_near(pts[i], [&](Index j) { near.insert(j); });
    for (std::size_t j = 0; j < pts.size(); ++j)
      if ((pts[j] - pts[i]).norm() < h) {
        EXPECT_TRUE(near.count(static_cast<Index>(j)));
      }
  }
}

TEST(CellList, RejectsNonFinitePositions) {
  std::vector<Vec<2>> pts{Vec<2>(0, 0), Vec<2>(std::nan(""), 0)};
  CellList<2> cl;
  EXPECT_THROW(cl.build(pts, 1.0), RunError);
}

}  // namespace
}  // namespace pdmpm::core
