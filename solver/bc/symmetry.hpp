#pragma once
// Symmetry planes by mirrored ghost particles: every particle within the family
// radius of a plane gets a mirror image on the other side that copies its
// owner's displacement and velocity, reflected. Planes must pass through a
// lattice site or midway between two, so mirrors land on lattice sites.
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "solver/core/body_sites.hpp"
#include "solver/core/particles.hpp"

namespace pdmpm::bc {

struct SymmetryPlane {
  std::string key;  // for messages
  int axis = 0;
  double position = 0.0;
};

// Throws InputError when a plane is off the lattice, beyond the body's reach or has the
// body on both sides. The body's sites span [lowest, highest] (per axis, the whole body's);
// `reach` is the family radius in metres.
template <int D>
void check_symmetry_planes(const core::Lattice<D>& lattice, const IVec<D>& lowest, const IVec<D>& highest,
                           const std::vector<SymmetryPlane>& planes, double reach, const std::string& file);

// Appends the ghosts of all checked planes (and of their intersections) to p: a mirror of
// every particle of p (real or ghost) within `reach` of a plane whose site is free. In a
// distributed run p is a process's store (own particles and their halo): a mirror within a
// family of an own particle mirrors a particle at least as close to it (both lie on the same
// side of the plane), which is own or in the halo, so every mirror a family needs is made.
template <int D>
void add_symmetry_ghosts(core::Particles<D>& p, const std::vector<SymmetryPlane>& planes, double reach);

// The lowest and highest site coordinates of p's real particles, per axis (lowest >
// highest when there is none).
template <int D>
std::pair<IVec<D>, IVec<D>> real_site_bounds(const core::Particles<D>& p) {
  IVec<D> lowest = IVec<D>::Constant(std::numeric_limits<std::int32_t>::max());
  IVec<D> highest = IVec<D>::Constant(std::numeric_limits<std::int32_t>::min());
  for (Index i = 0; i < p.n_real; ++i) lowest = lowest.cwiseMin(p.site[i]), highest = highest.cwiseMax(p.site[i]);
  return {lowest, highest};
}

// Both, on a one-process body.
template <int D>
void add_symmetry_ghosts(core::Particles<D>& p, const std::vector<SymmetryPlane>& planes, double reach,
                         const std::string& file) {
  const auto [lowest, highest] = real_site_bounds(p);
  check_symmetry_planes(p.lattice, lowest, highest, planes, reach, file);
  add_symmetry_ghosts(p, planes, reach);
}

// The number of mirrors add_symmetry_ghosts makes for a whole body of checked planes,
// from its sites within `reach` of a plane (no other site is mirrored, and a mirror lands
// beyond its plane, where the body has no site): what one process makes, counted by a
// distributed process that holds the body as site keys.
template <int D>
Index mirror_count(const core::BodySites<D>& body, const std::vector<SymmetryPlane>& planes, double reach);

}  // namespace pdmpm::bc
