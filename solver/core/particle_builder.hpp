#pragma once
// Fills a geometry with lattice particles, in Morton order.
#include "solver/core/particles.hpp"
#include "solver/core/shapes.hpp"

namespace pdmpm::core {

// Every lattice site the geometry contains becomes a particle of volume
// `volume` (Δx^D times thickness in 2D or cross-section area in 1D).
template <int D>
Particles<D> fill_lattice(const Geometry<D>& geometry, const Lattice<D>& lattice, double volume);

}  // namespace pdmpm::core
