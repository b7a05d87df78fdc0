// The scatter schedule: particles grouped by block of 4^D cells in ascending index,
// same-colour blocks far enough apart that their stencils never share a node, and a
// schedule kept from the last build exactly when a fresh build would give the same.
#include "solver/mpm/scatter_schedule.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <set>

namespace pdmpm::mpm {
namespace {

// Cells of n particles scattered over a 40 × 24-cell grid (h = 1).
struct Body {
  Grid<2> grid{Vec<2>::Zero(), 1.0, IVec<2>(41, 25)};
  std::vector<Index> particles;
  std::vector<IVec<2>> cell;
  explicit Body(int n) {
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> cx(0, 39), cy(0, 23);
    for (int p = 0; p < n; ++p) {
      particles.push_back(3 * p);  // not 0..n-1: the schedule carries store indices
      cell.emplace_back(cx(rng), cy(rng));
    }
  }
};

IVec<2> block_of(const IVec<2>& c) { return IVec<2>(c[0] / 4, c[1] / 4); }

TEST(MpmScatterSchedule, GroupsByBlockInIndexOrderAndColoursKeepStencilsApart) {
  const Body b(600);
  ScatterSchedule<2> s;
  s.build(b.grid, b.particles, b.cell);
  std::map<Index, IVec<2>> cell_of;
  for (std::size_t k = 0; k < b.particles.size(); ++k) cell_of[b.particles[k]] = b.cell[k];
  // Visit order: every particle once; within a block ascending; one colour after another.
  std::vector<std::pair<Index, Index>> visits;  // (k, particle)
  s.for_each([&](Index k, Index p) {
#pragma omp critical
    visits.emplace_back(k, p);
  });
  ASSERT_EQ(visits.size(), b.particles.size());
  std::set<Index> seen;
  for (const auto& [k, p] : visits) {
    EXPECT_EQ(s.order()[k], p);
    seen.insert(p);
  }
  EXPECT_EQ(seen.size(), b.particles.size());
  for (std::size_t k = 1; k < s.order().size(); ++k) {
    const IVec<2> b0 = block_of(cell_of[s.order()[k - 1]]), b1 = block_of(cell_of[s.order()[k]]);
    if (b0 == b1) {
      EXPECT_LT(s.order()[k - 1], s.order()[k]) << "ascending within a block";
    }
  }
  // Two particles in different blocks of one colour write disjoint nodes (c−1 … c+2).
  for (Index p : b.particles)
    for (Index q : b.particles) {
      const IVec<2> bp = block_of(cell_of[p]), bq = block_of(cell_of[q]);
      if (bp == bq || ((bp[0] - bq[0]) % 2 != 0) || ((bp[1] - bq[1]) % 2 != 0)) continue;
      const IVec<2> d = (cell_of[p] - cell_of[q]).cwiseAbs();
      EXPECT_TRUE(d[0] >= 4 || d[1] >= 4) << p << " and " << q;
    }
}

TEST(MpmScatterSchedule, KeptScheduleEqualsAFreshBuild) {
  Body b(400);
  ScatterSchedule<2> kept;
  kept.build(b.grid, b.particles, b.cell);
  auto fresh_order = [&] {
    ScatterSchedule<2> f;
    f.build(b.grid, b.particles, b.cell);
    return f.order();
  };
  // A move inside its block keeps the schedule; a move to another block changes it.
  b.cell[5] = IVec<2>((b.cell[5][0] / 4) * 4 + (b.cell[5][0] + 1) % 4, b.cell[5][1]);
  kept.build(b.grid, b.particles, b.cell);
  EXPECT_EQ(kept.order(), fresh_order());
  const std::vector<Index> before = kept.order();
  b.cell[5][0] = (b.cell[5][0] + 8) % 40;
  kept.build(b.grid, b.particles, b.cell);
  EXPECT_EQ(kept.order(), fresh_order());
  EXPECT_NE(kept.order(), before);
  // A particle leaving the active set is a new schedule too.
  b.particles.pop_back();
  b.cell.pop_back();
  kept.build(b.grid, b.particles, b.cell);
  EXPECT_EQ(kept.order(), fresh_order());
  EXPECT_EQ(kept.order().size(), b.particles.size());
}

}  // namespace
}  // namespace pdmpm::mpm
