// The scatter schedule: particles grouped by block of 32 × 4^(D−1) cells in ascending index,
// same-colour blocks far enough apart that their stencils never share a node, every
// node summing its particles in the order of a colour-by-colour sweep (so the slab
// order of the phases changes no bit), the order cut into lane groups (mostly runs of consecutive particles),
// and a schedule kept from the last build exactly when a fresh build would give the same.
#include "solver/mpm/scatter_schedule.hpp"

#include <gtest/gtest.h>

#include <omp.h>

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

IVec<2> block_of(const IVec<2>& c) {
  return IVec<2>(c[0] / ScatterSchedule<2>::block_cells(0), c[1] / ScatterSchedule<2>::block_cells(1));
}

TEST(MpmScatterSchedule, GroupsByBlockInIndexOrderAndColoursKeepStencilsApart) {
  const Body b(600);
  ScatterSchedule<2> s;
  s.build(b.grid, b.particles, b.cell);
  std::map<Index, IVec<2>> cell_of;
  for (std::size_t k = 0; k < b.particles.size(); ++k) cell_of[b.particles[k]] = b.cell[k];
  // Visit order: every particle once; within a block ascending.
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

// Cells of n particles scattered uniformly over a grid of `cells` cells.
template <int D>
struct RandomBody {
  Grid<D> grid;
  std::vector<Index> particles;
  std::vector<IVec<D>> cell;
  RandomBody(const IVec<D>& cells, int n) : grid{Vec<D>::Zero(), 1.0, IVec<D>(cells.array() + 1)} {
    std::mt19937 rng(11);
    for (int p = 0; p < n; ++p) {
      particles.push_back(2 * p + 1);  // not 0..n-1: the schedule carries store indices
      IVec<D> c;
      for (int a = 0; a < D; ++a) c[a] = std::uniform_int_distribution<int>(0, cells[a] - 1)(rng);
      cell.push_back(c);
    }
  }
};

// node → the particles that write it (nodes c − 1 … c + 2 of cell c per axis), in the
// order given by visit(fn), which calls fn(particle) for every particle in its order.
template <int D, class Visit>
std::map<Index, std::vector<Index>> node_sums(const RandomBody<D>& b, Visit&& visit) {
  std::map<Index, std::vector<Index>> sums;  // by the node's linear index (coordinates shifted by 1)
  visit([&](Index p) {
    const IVec<D>& c = b.cell[static_cast<std::size_t>((p - 1) / 2)];
    for (int n = 0; n < (1 << (2 * D)); ++n) {
      Index node = 0, stride = 1;
      for (int a = 0; a < D; ++a) {
        node += (c[a] + ((n >> (2 * a)) & 3)) * stride;  // c − 1 + offset, shifted by 1
        stride *= b.grid.n[a] + 2;
      }
#pragma omp critical
      sums[node].push_back(p);
    }
  });
  return sums;
}

template <int D>
void expect_node_order_of_a_colour_sweep(const IVec<D>& cells, int n) {
  const RandomBody<D> b(cells, n);
  ScatterSchedule<D> s;
  s.build(b.grid, b.particles, b.cell);
  // A block's colour from its block coordinates: their parities.
  auto colour_of = [](const IVec<D>& block) {
    int colour = 0;
    for (int a = 0; a < D; ++a) colour |= (block[a] & 1) << a;
    return colour;
  };
  // The reference: colour by colour, each colour's blocks in index order.
  const auto sweep = node_sums<D>(b, [&](auto&& fn) {
    for (int colour = 0; colour < (1 << D); ++colour)
      for (const Index p : s.order()) {
        const IVec<D>& c = b.cell[static_cast<std::size_t>((p - 1) / 2)];  // particles are 2k + 1
        IVec<D> block;
        for (int a = 0; a < D; ++a) block[a] = c[a] / ScatterSchedule<D>::block_cells(a);
        if (colour_of(block) == colour) fn(p);
      }
  });
  // One thread goes through slabs in several stages, more threads colour by colour;
  // every phase is blocks of one colour.
  const auto& slabs = s.phases(false);
  const auto& sweep_phases = s.phases(true);
  ASSERT_GT(slabs.start.size() - 1, 2u << D) << "the grid should need several stages";
  ASSERT_EQ(sweep_phases.start.size() - 1, 1u << D);
  for (const auto* phases : {&slabs, &sweep_phases})
    for (std::size_t ph = 0; ph + 1 < phases->start.size(); ++ph) {
      std::set<int> colours;
      for (Index i = phases->start[ph]; i < phases->start[ph + 1]; ++i) {
        IVec<D> block;  // the block index's coordinates
        Index rest = phases->blocks[static_cast<std::size_t>(i)];
        for (int a = 0; a < D; ++a) {
          const int per_axis = (cells[a] + ScatterSchedule<D>::block_cells(a) - 1) / ScatterSchedule<D>::block_cells(a);
          block[a] = static_cast<int>(rest % per_axis), rest /= per_axis;
        }
        colours.insert(colour_of(block));
      }
      EXPECT_EQ(colours.size(), 1u) << "phase " << ph;
    }
  const int threads_before = omp_get_max_threads();
  for (int threads : {1, 2, 3}) {
    omp_set_num_threads(threads);
    const auto phased = node_sums<D>(b, [&](auto&& fn) { s.for_each([&](Index, Index p) { fn(p); }); });
    EXPECT_EQ(phased, sweep) << threads << " threads";
  }
  omp_set_num_threads(threads_before);
}

TEST(MpmScatterSchedule, EveryNodeSumsInTheOrderOfAColourSweep) {
  // Several stages in each dimension; more than kParallelMin particles, so the phases
  // run in parallel on more than one thread.
  expect_node_order_of_a_colour_sweep<1>(IVec<1>(600), 5000);
  expect_node_order_of_a_colour_sweep<2>(IVec<2>(80, 200), 5000);
  expect_node_order_of_a_colour_sweep<3>(IVec<3>(40, 40, 48), 5000);
}

// Why the blocks are long along the first axis: on a lattice body numbered first axis
// fastest (two particles per cell), each block row is a run of consecutive store indices
// as long as the block, which the per-particle passes then stream.
TEST(MpmScatterSchedule, ALatticeBlockRowIsARunOfConsecutiveIndices) {
  const int nx = 200, ny = 40;  // particles; the grid has nx / 2 × ny / 2 cells
  Grid<2> grid{Vec<2>::Zero(), 1.0, IVec<2>(nx / 2 + 1, ny / 2 + 1)};
  std::vector<Index> particles;
  std::vector<IVec<2>> cell;
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) {
      particles.push_back(y * nx + x);
      cell.emplace_back(x / 2, y / 2);
    }
  ScatterSchedule<2> s;
  s.build(grid, particles, cell);
  std::map<Index, int> runs;  // run length → how many
  Index length = 1;
  for (std::size_t k = 1; k <= s.order().size(); ++k)
    if (k < s.order().size() && s.order()[k] == s.order()[k - 1] + 1) {
      ++length;
    } else {
      ++runs[length];
      length = 1;
    }
  // Rows of 64 in the three full blocks, of 8 in the last; the last block's top row runs
  // on into the first row of the next block layer (its indices continue), 4 times.
  const Index full = 2 * ScatterSchedule<2>::kLeadBlockCells, last = nx - 3 * full, layers = ny / 8;
  const std::map<Index, int> expected{
      {last, ny - (layers - 1)}, {full, 3 * ny - (layers - 1)}, {last + full, layers - 1}};
  EXPECT_EQ(runs, expected);
}

// The stress update's groups: the order cut into runs of at most eight consecutive
// particles where a run of at least three starts, else eight positions gathered particle
// by particle; together they cover the order once, in order.
TEST(MpmScatterSchedule, TheOrderIsCutIntoLaneGroupsMostlyRuns) {
  using S = ScatterSchedule<2>;
  const int nx = 90, ny = 16;
  Grid<2> grid{Vec<2>::Zero(), 1.0, IVec<2>(nx / 2 + 1, ny / 2 + 1)};
  std::vector<Index> particles;
  std::vector<IVec<2>> cell;
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) {
      const bool hole = y >= 5 && y < 9 && x >= 40 && x < 43;  // as the hybrid's PD region leaves
      const bool sparse = y == 12 && x % 2 == 1;               // runs of one
      if (!hole && !sparse) {
        particles.push_back(y * nx + x);
        cell.emplace_back(x / 2, y / 2);
      }
    }
  S s;
  s.build(grid, particles, cell);
  const std::vector<Index>& order = s.order();
  auto run_from = [&](Index k) {  // the run of consecutive particles starting at position k, capped
    Index length = 1;
    while (length < S::kLaneGroup && k + length < static_cast<Index>(order.size()) &&
           order[k + length] == order[k] + length)
      ++length;
    return length;
  };
  Index next = 0, runs = 0, gathered = 0;
  for (const S::LaneGroup& g : s.lane_groups()) {
    EXPECT_EQ(g.begin, next) << "groups cover the order in order";
    ASSERT_GE(g.size, 1);
    ASSERT_LE(g.size, S::kLaneGroup);
    bool consecutive = true;
    for (Index l = 1; l < g.size; ++l) consecutive = consecutive && order[g.begin + l] == order[g.begin] + l;
    EXPECT_EQ(g.run, consecutive);
    const Index run = run_from(g.begin);
    if (run >= S::kShortestRun) {
      EXPECT_TRUE(g.run);
      EXPECT_EQ(g.size, run) << "a run is taken whole (up to eight)";
    } else if (g.begin + g.size < static_cast<Index>(order.size())) {
      EXPECT_EQ(g.size, S::kLaneGroup) << "short runs are packed eight positions at a time";
    }
    runs += g.run && g.size == S::kLaneGroup;
    gathered += !g.run;
    next = g.begin + g.size;
  }
  EXPECT_EQ(next, static_cast<Index>(order.size()));
  EXPECT_GT(runs, 100);    // the lattice rows
  EXPECT_GT(gathered, 0);  // the sparse row
  EXPECT_LT(gathered, runs);
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
  b.cell[5][1] = (b.cell[5][1] + 8) % 24;  // two blocks along the second axis
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
