#pragma once
// Deterministic, race-free particle-to-grid scatter.
//
// Particles are binned into blocks of 4^D cells (stable counting sort: within a
// block, ascending particle index). Blocks get one of 2^D colours by the parity
// of their block coordinates. A particle in cell c writes only to nodes c−1 … c+2
// per axis, so two blocks of the same colour (≥ 4 cells apart on some axis) never
// write to the same node. Colours run one after another; the blocks of a colour
// run in parallel, each by one thread in particle order. Every node therefore sums
// its contributions in the same order whatever the number of threads, and the
// result is bit-identical for any OpenMP team size, without atomics.
#include <array>
#include <vector>

#include "solver/core/types.hpp"
#include "solver/mpm/grid.hpp"
#include "solver/mpm/parallel.hpp"

namespace pdmpm::mpm {

template <int D>
class ScatterSchedule {
 public:
  static constexpr int kBlockCells = 4;
  static constexpr int kColours = 1 << D;

  // cell[k] = cell coordinates of particles[k] (each in [0, cells) per axis). A step
  // rarely moves a particle to another block: when the particles and their blocks are
  // those of the last build, the schedule stands as it is.
  void build(const Grid<D>& grid, const std::vector<Index>& particles, const std::vector<IVec<D>>& cell) {
    Index nb = 1;
    IVec<D> nblocks;
    for (int a = 0; a < D; ++a) {
      nblocks[a] = (grid.cells()[a] + kBlockCells - 1) / kBlockCells;
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
        b += (cell[k][a] / kBlockCells) * s;
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
    for (auto& c : colour_blocks_) c.clear();
    for (Index b = 0; b < nb; ++b) {
      if (start_[b + 1] == start_[b]) continue;
      int colour = 0;
      Index rest = b;
      for (int a = 0; a < D; ++a) {
        colour |= ((rest % nblocks_[a]) & 1) << a;
        rest /= nblocks_[a];
      }
      colour_blocks_[colour].push_back(b);
    }
  }

  // The particles in schedule order (block by block); per-step particle data such as
  // the stencils is stored in this order, so the hot loops read it sequentially.
  const std::vector<Index>& order() const { return order_; }
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
    const bool parallel = static_cast<Index>(order_.size()) >= kParallelMin;
    for (int c = 0; c < kColours; ++c) {
      const std::vector<Index>& blocks = colour_blocks_[c];
      const Index nblk = static_cast<Index>(blocks.size());
// Static chunks: a thread takes a run of neighbouring blocks, so two threads write
// nodes on one cache line only where their runs meet (with blocks dealt out one by
// one, same-colour neighbours 2 nodes apart shared lines on every block: 2 threads
// ran the scatter slower than 1).
#pragma omp parallel for schedule(static) if (parallel)
      for (Index bi = 0; bi < nblk; ++bi) {
        const Index b = blocks[bi];
        fn(start_[b], start_[b + 1]);
      }
    }
  }

 private:
  IVec<D> nblocks_ = IVec<D>::Ones();
  std::uint64_t generation_ = 0;
  std::vector<Index> start_, order_;
  std::vector<Index> particles_, block_;  // of the last build: the particles and their blocks
  std::vector<Index> fill_;               // scratch of build()
  std::array<std::vector<Index>, kColours> colour_blocks_;
};

}  // namespace pdmpm::mpm
