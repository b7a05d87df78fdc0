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

// A distributed process holds its points in another order (own, then other processes'):
// given the whole body's box and the global order, it visits them as the whole body's list
// does (what makes contact sums process-invariant).
TEST(CellList, OrderedBuildVisitsAsTheWholeBodyDoes) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec<2>> body(300);
  for (auto& x : body) x = Vec<2>(u(rng), u(rng));
  const double h = 0.08;
  CellList<2> whole;
  whole.build(body, h);
  // A process's view: points 100…199 first, then 0…99, then 200…299 (global index = stored + shift).
  std::vector<Vec<2>> held;
  std::vector<Index> global;
  for (Index g = 100; g < 200; ++g) held.push_back(body[g]), global.push_back(g);
  for (Index g = 0; g < 100; ++g) held.push_back(body[g]), global.push_back(g);
  for (Index g = 200; g < 300; ++g) held.push_back(body[g]), global.push_back(g);
  std::vector<Index> order;  // stored indices in the global order
  for (Index k = 100; k < 200; ++k) order.push_back(k);
  for (Index k = 0; k < 100; ++k) order.push_back(k);
  for (Index k = 200; k < 300; ++k) order.push_back(k);
  Vec<2> lo = body[0], hi = body[0];
  for (const auto& x : body) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  CellList<2> part;
  part.build(held, h, lo, hi, order);
  for (Index g = 0; g < 300; g += 7) {
    std::vector<Index> a, b;
    whole.for_each_near(body[g], [&](Index j) { a.push_back(j); });
    part.for_each_near(body[g], [&](Index k) { b.push_back(global[k]); });
    EXPECT_EQ(a, b) << "point " << g;
  }
  EXPECT_THROW(part.build(held, h, lo, hi, std::vector<Index>(10, 0)), RunError);
}

}  // namespace
}  // namespace pdmpm::core
