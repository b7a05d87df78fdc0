#pragma once
// Deterministic, race-free particle-to-grid scatter.
//
// Particles are binned into blocks of 32 × 4^(D−1) cells (stable counting sort:
// within a block, ascending particle index). Blocks get one of 2^D colours by the
// parity of their block coordinates. A particle in cell c writes only to nodes
// c−1 … c+2 per axis, so two blocks of the same colour (≥ 4 cells apart on some
// axis) never write to the same node, and a node receives from at most one block of
// each colour (a 2^D neighbourhood of blocks). Every node sums its blocks in
// ascending colour and each block's particles in index order — whatever the number
// of threads, so the result is bit-identical for any OpenMP team size, without atomics.
//
// Why 32 cells along the first axis: a lattice body's particles are numbered with
// the first axis fastest, so a block row is a run of consecutive indices, and every
// per-particle pass (stencils, G2P, the stress update) reads the particle arrays in
// those runs. With 4-cell blocks a run was 8 particles at two per cell, too short
// for the hardware prefetcher; 32 cells make it 64 (measured on one thread: the MPM
// step of the mid-resolution central crack 11 % cheaper, of the 200² J2 plate 6 %, the
// stress update most; solver/mpm/README.md). Longer blocks along the first axis would
// leave fewer blocks per colour for the threads on small bodies. The block shape, not the team size,
// sets each node's order of summation, so the results stay the same on any number of
// threads.
//
// The blocks run in phases, one after another; a phase is blocks of one colour,
// run in parallel. On several threads the phases are the colours, each a sweep
// over the whole grid. On one thread that sweep brought every node into cache 2^D
// times, and on a grid larger than the L2 cache P2G and MUSL's remap cost half as
// much again (a 400 × 400 plate against a 200 × 200 one); there the phases go
// instead through the grid in slabs of two block layers along the last axis:
// stage s takes the even layer 2s in the colours whose last-axis parity is even,
// then the odd layer 2s − 1 in the others. A node between an even layer and the odd
// one below it gets the even layer's blocks first in the same stage, one between an
// even layer and the odd one above it a stage earlier: either way its colours
// arrive in ascending order, as in the colour sweep, so the sums are the sweep's to
// the bit while the grid passes through the cache once. (Slabs on two threads put a
// barrier after every few dozen blocks, and on this project's machines that cost
// more than the cache saved.)
#include <omp.h>

#include <algorithm>
#include <vector>

#include "solver/core/types.hpp"
#include "solver/mpm/grid.hpp"
#include "solver/mpm/parallel.hpp"

namespace pdmpm::mpm {

template <int D>
class ScatterSchedule {
 public:
  static constexpr int kBlockCells = 4;       // along every axis but the first
  static constexpr int kLeadBlockCells = 32;  // along the first (top of this file)
  static constexpr int block_cells(int axis) { return axis == 0 ? kLeadBlockCells : kBlockCells; }
  static constexpr int kColours = 1 << D;

  // cell[k] = cell coordinates of particles[k] (each in [0, cells) per axis). A step
  // rarely moves a particle to another block: when the particles and their blocks are
  // those of the last build, the schedule stands as it is.
  void build(const Grid<D>& grid, const std::vector<Index>& particles, const std::vector<IVec<D>>& cell) {
    Index nb = 1;
    IVec<D> nblocks;
    for (int a = 0; a < D; ++a) {
      nblocks[a] = (grid.cells()[a] + block_cells(a) - 1) / block_cells(a);
      nb *= nblocks[a];
    }
    bool same = nblocks == nblocks_ && particles == particles_ && !order_.empty();
    nblocks_ = nblocks;
    std::vector<Index>& block = block_;
    block.resize(particles.size());
    const Index n = static_cast<Index>(particles.size());
#pragma omp parallel for schedule(static) reduction(&& : same) if (n >= kParallelMin)
    for (Index k = 0; k < n; ++k) {
      Index b = 0, s = 1;
      for (int a = 0; a < D; ++a) {
        b += (cell[k][a] / block_cells(a)) * s;
        s *= nblocks_[a];
      }
      same = same && block[k] == b;
      block[k] = b;
    }
    if (same) return;
    ++generation_;
    particles_ = particles;
    start_.assign(static_cast<std::size_t>(nb) + 1, 0);
    for (std::size_t k = 0; k < particles.size(); ++k) ++start_[block[k] + 1];
    for (Index b = 0; b < nb; ++b) start_[b + 1] += start_[b];
    order_.resize(particles.size());
    std::vector<Index>& fill = fill_;
    fill.assign(start_.begin(), start_.end() - 1);
    for (std::size_t k = 0; k < particles.size(); ++k) order_[fill[block[k]]++] = particles[k];
    split_into_lane_groups();
    slabs_ = stages_of(1);
    colour_sweep_ = stages_of(nblocks_[D - 1] / 2 + 1);  // one stage: colour by colour
  }

  // The particles in schedule order (block by block); per-step particle data such as
  // the stencils is stored in this order, so the hot loops read it sequentially.
  const std::vector<Index>& order() const { return order_; }
  // order() cut into the stress update's groups of at most kLaneGroup positions: a run of
  // consecutive particles (its entries of each state array one copy) where one at least
  // kShortestRun long starts, else kLaneGroup positions gathered particle by particle.
  static constexpr int kLaneGroup = 8, kShortestRun = 3;
  struct LaneGroup {
    Index begin, size;  // positions begin … begin + size − 1 of order()
    bool run;           // their particles are order()[begin] … order()[begin] + size − 1
  };
  const std::vector<LaneGroup>& lane_groups() const { return lane_groups_; }
  // Changes whenever order() does: data kept in schedule order is valid while it stands.
  std::uint64_t generation() const { return generation_; }

  // fn(position in order(), particle index) for every particle, scheduled as described above.
  template <class Fn>
  void for_each(Fn&& fn) const {
    for_each_block([&](Index k_begin, Index k_end) {
      for (Index k = k_begin; k < k_end; ++k) fn(k, order_[k]);
    });
  }

  // fn(k_begin, k_end) for every block's run of positions in order(), scheduled so.
  template <class Fn>
  void for_each_block(Fn&& fn) const {
    const bool parallel = static_cast<Index>(order_.size()) >= kParallelMin && omp_get_max_threads() > 1;
    const Phases& phases = parallel ? colour_sweep_ : slabs_;
    const Index nphases = static_cast<Index>(phases.start.size()) - 1;
#pragma omp parallel if (parallel)
    for (Index ph = 0; ph < nphases; ++ph) {
// Static chunks: a thread takes a run of neighbouring blocks, so two threads write
// nodes on one cache line only where their runs meet (with blocks dealt out one by
// one, same-colour neighbours 2 nodes apart shared lines on every block: 2 threads
// ran the scatter slower than 1). The loop's barrier ends the phase.
#pragma omp for schedule(static)
      for (Index bi = phases.start[ph]; bi < phases.start[ph + 1]; ++bi) {
        const Index b = phases.blocks[bi];
        fn(start_[b], start_[b + 1]);
      }
    }
  }

  // Phases of one thread (slabs) or of several (the colours): phase ph is the blocks
  // blocks[start[ph] … start[ph + 1]) (block indices).
  struct Phases {
    std::vector<Index> start, blocks;
  };
  const Phases& phases(bool parallel) const { return parallel ? colour_sweep_ : slabs_; }

 private:
  // The phases whose stages take `layers_per_stage` even layers along the last axis in
  // the colours of even last-axis parity, then as many odd layers, one behind, in the
  // others (see the top of this file); the blocks of a phase in index order.
  Phases stages_of(Index layers_per_stage) const {
    const int top = D - 1;
    Index per_layer = 1;  // blocks in one layer along the last axis
    for (int a = 0; a < top; ++a) per_layer *= nblocks_[a];
    const Index layers = nblocks_[top], span = 2 * layers_per_stage;
    Phases p;
    p.start.assign(1, 0);
    for (Index first = 0; first < layers + 1; first += span)
      for (int colour = 0; colour < kColours; ++colour) {
        const Index parity = colour >> top & 1, lo = first - parity;  // odd layers trail by one
        for (Index layer = std::max<Index>(lo, 0); layer < std::min(lo + span, layers); ++layer) {
          if ((layer & 1) != parity) continue;
          for (Index b = layer * per_layer; b < (layer + 1) * per_layer; ++b)
            if (start_[b + 1] > start_[b] && colour_of(b) == colour) p.blocks.push_back(b);
        }
        if (static_cast<Index>(p.blocks.size()) > p.start.back())
          p.start.push_back(static_cast<Index>(p.blocks.size()));
      }
    return p;
  }

  // A block row is a run of a lattice row, but a row's end, a particle missing (the
  // hybrid's PD region) and, once a body deforms, a lattice row wandering across a block
  // boundary cut it: groups of eight positions taken regardless straddle each cut and go
  // particle by particle (30 % of the groups in the mid central crack's hybrid before the
  // crack). A run per group instead costs a group with idle lanes per cut, which is what
  // the lanes' arithmetic costs: after the crack the runs average five particles. From the
  // stress phase of that hybrid before and after taking runs (solver/mpm/README.md), a
  // particle-by-particle group costs about three times a run's group of the same lanes, so
  // runs shorter than kShortestRun are packed eight positions at a time.
  void split_into_lane_groups() {
    lane_groups_.clear();
    const Index n = static_cast<Index>(order_.size());
    for (Index k = 0; k < n;) {
      Index length = 1;
      while (length < kLaneGroup && k + length < n && order_[k + length] == order_[k] + length) ++length;
      const bool packed = length < kShortestRun && k + length < n;  // so longer than its run
      if (packed) length = std::min<Index>(kLaneGroup, n - k);
      lane_groups_.push_back({k, length, !packed});
      k += length;
    }
  }

  int colour_of(Index b) const {
    int colour = 0;
    for (int a = 0; a < D; ++a) {
      colour |= static_cast<int>((b % nblocks_[a]) & 1) << a;
      b /= nblocks_[a];
    }
    return colour;
  }

  IVec<D> nblocks_ = IVec<D>::Ones();
  std::uint64_t generation_ = 0;
  std::vector<Index> start_, order_;
  std::vector<LaneGroup> lane_groups_;
  std::vector<Index> particles_, block_;  // of the last build: the particles and their blocks
  std::vector<Index> fill_;               // scratch of build()
  Phases slabs_, colour_sweep_;
};

}  // namespace pdmpm::mpm
