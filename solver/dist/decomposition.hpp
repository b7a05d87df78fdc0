#pragma once
// How a body is split between processes, without MPI (so it is unit-tested in one
// process): each process owns a contiguous range of the real particles' global
// index. Particles are numbered in Morton order (core/particle_builder.hpp), so a
// range is a compact block of space — a space-filling-curve partition, which
// needs no partitioner and keeps every sum over particles in one global order.
// A process also holds its halo: every particle another process owns that is a
// stencil neighbour of one of its own, so its families are built exactly as in a
// one-process run (families are built by lattice offsets, core/families.hpp).
#include <vector>

#include "solver/core/body_sites.hpp"
#include "solver/core/particles.hpp"
#include "solver/core/stencil.hpp"

namespace pdmpm::dist {

// Global indices [begin, end) a process owns.
struct OwnedRange {
  Index begin = 0, end = 0;
  Index size() const { return end - begin; }
  bool contains(Index g) const { return g >= begin && g < end; }
};

// Process `rank` of `ranks` owns [⌊n·rank/ranks⌋, ⌊n·(rank+1)/ranks⌋).
OwnedRange owned_range(Index n, int rank, int ranks);
// The process that owns global index g (the inverse of owned_range).
int owner_rank(Index g, Index n, int ranks);

// The halo of `own`: the global indices, increasing, of the sites outside it that are a
// stencil neighbour of a site in it; and the bonds own's sites have in the whole body (their
// stencil neighbours), which the process's families must hold — a store missing one of them
// is found (a halo too thin).
struct Halo {
  std::vector<Index> global;
  std::int64_t own_bonds = 0;
};
template <int D>
Halo halo_of(const core::BodySites<D>& body, const core::Stencil<D>& stencil, OwnedRange own);

}  // namespace pdmpm::dist
