#pragma once
// The lattice sites of a body in its global (Morton) order, as sorted keys: 8 bytes a
// site, where a particle store costs about 140. A distributed process keeps the whole
// body this way (docs/models/distributed.md, "Ownership") and makes particles only for
// its own sites and its halo; core::fill_lattice makes them for all.
#include <cstdint>
#include <vector>

#include "solver/core/particles.hpp"
#include "solver/core/shapes.hpp"

namespace pdmpm::core {

template <int D>
struct BodySites {
  Lattice<D> lattice;
  double volume = 0.0;               // of every particle
  IVec<D> lowest = IVec<D>::Zero();  // the keys' origin (the lowest site of the body's box)
  std::vector<std::uint64_t> keys;   // increasing: key g is the site of global index g

  Index size() const { return static_cast<Index>(keys.size()); }
  IVec<D> site(Index g) const;
  // The global index of a site, or −1 if the body does not hold it.
  Index find(const IVec<D>& site) const;
  // Particles (fields zero): the real ones at global indices [begin, end), then remote
  // ghosts (a distributed run's halo) at `remote_ghosts`, in that order.
  Particles<D> particles(Index begin, Index end, const std::vector<Index>& remote_ghosts = {}) const;
};

// Every lattice site the geometry contains (a site on a shape's boundary counts as inside).
template <int D>
BodySites<D> body_sites(const Geometry<D>& geometry, const Lattice<D>& lattice, double volume);

}  // namespace pdmpm::core
