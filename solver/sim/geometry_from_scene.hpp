#pragma once
// Turns scene shape specifications into core geometry.
#include <vector>

#include "solver/core/body_sites.hpp"
#include "solver/core/lattice.hpp"
#include "solver/core/particles.hpp"
#include "solver/core/shapes.hpp"
#include "solver/io/scene.hpp"

namespace pdmpm::sim {

template <int D>
core::Geometry<D> make_geometry(const std::vector<io::ShapeSpec>& shapes);

// The scene's lattice: spacing Δx; sites cell-centred by default (the first half a
// spacing inside the body's lower corner, N sites across a length N Δx), or through
// discretization.lattice_origin.
template <int D>
core::Lattice<D> make_lattice(const io::Scene& s, const core::Geometry<D>& g);

// The body's sites: the scene's lattice sites inside its shapes, particles of volume
// Δx^D (× thickness in 2D, × area in 1D). InputError when there is none.
template <int D>
core::BodySites<D> body_sites_of(const io::Scene& s);

// The body's particles (its sites', all).
template <int D>
core::Particles<D> fill_body(const io::Scene& s);

// Real particles whose reference position lies in the region (boundaries included).
template <int D>
std::vector<Index> select_particles(const std::vector<Vec<D>>& x0, Index n_real, const core::Geometry<D>& region,
                                    double spacing);

template <int D>
Vec<D> to_vec(const std::vector<double>& v) {
  Vec<D> out;
  for (int a = 0; a < D; ++a) out[a] = v[a];
  return out;
}

}  // namespace pdmpm::sim
