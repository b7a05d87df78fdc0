#pragma once
// Symmetry planes by mirrored ghost particles: every particle within the family
// radius of a plane gets a mirror image on the other side that copies its
// owner's displacement and velocity, reflected. Planes must pass through a
// lattice site or midway between two, so mirrors land on lattice sites.
#include <string>
#include <vector>

#include "solver/core/particles.hpp"

namespace pdmpm::bc {

struct SymmetryPlane {
  std::string key;  // for messages
  int axis = 0;
  double position = 0.0;
};

// Appends the ghosts of all planes (and of their intersections) to p.
// `reach` is the family radius in metres. Throws InputError when a plane is off
// the lattice or the body lies on both sides of it.
template <int D>
void add_symmetry_ghosts(core::Particles<D>& p, const std::vector<SymmetryPlane>& planes, double reach,
                         const std::string& file);

}  // namespace pdmpm::bc
