#include "solver/bc/symmetry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "solver/core/error.hpp"
#include "solver/core/site_map.hpp"

namespace pdmpm::bc {

namespace {

std::int32_t reach_in_sites(double reach, double dx) {
  return static_cast<std::int32_t>(std::floor(reach / dx * (1.0 + 1e-10)));
}

// Twice the plane's site coordinate (an integer for a checked plane).
template <int D>
double twice_site(const core::Lattice<D>& lattice, const SymmetryPlane& plane) {
  return 2.0 * (plane.position - lattice.origin[plane.axis]) / lattice.spacing;
}

}  // namespace

template <int D>
void check_symmetry_planes(const core::Lattice<D>& lattice, const IVec<D>& lowest, const IVec<D>& highest,
                           const std::vector<SymmetryPlane>& planes, double reach, const std::string& file) {
  const double dx = lattice.spacing;
  for (const auto& plane : planes) {
    const int a = plane.axis;
    const double twice = twice_site(lattice, plane);
    const double rounded = std::round(twice);
    if (std::abs(twice - rounded) > 1e-6)
      throw InputError(file, plane.key + ".position",
                       "a symmetry plane must pass through lattice sites or midway between them "
                       "(position = origin + k Δx/2)");
    // The plane must touch the body (within the family reach of a particle): one
    // farther away mirrors nothing, and its site coordinate may not fit an integer.
    const auto reach_sites = reach_in_sites(reach, dx);
    const double lo = lowest[a], hi = highest[a];
    if (!(rounded >= 2.0 * (lo - reach_sites) && rounded <= 2.0 * (hi + reach_sites)))
      throw InputError(file, plane.key + ".position",
                       fmt::format("the plane at {} m lies beyond the body's reach; a symmetry plane must touch the "
                                   "body (between {} and {} m on this axis)",
                                   plane.position, lattice.origin[a] + (lo - reach_sites) * dx,
                                   lattice.origin[a] + (hi + reach_sites) * dx));
    if (2.0 * lo < rounded && 2.0 * hi > rounded)
      throw InputError(file, plane.key, "the body lies on both sides of this symmetry plane; keep only one half");
  }
}

template <int D>
void add_symmetry_ghosts(core::Particles<D>& p, const std::vector<SymmetryPlane>& planes, double reach) {
  const auto reach_sites = reach_in_sites(reach, p.lattice.spacing);
  for (const auto& plane : planes) {
    const int a = plane.axis;
    const auto two_p = static_cast<std::int32_t>(std::round(twice_site(p.lattice, plane)));
    std::set<std::vector<std::int32_t>> occupied;
    for (const auto& s : p.site) occupied.insert(std::vector<std::int32_t>(s.data(), s.data() + D));
    const Index existing = p.size();
    for (Index i = 0; i < existing; ++i) {
      IVec<D> m = p.site[i];
      m[a] = two_p - m[a];
      if (m[a] == p.site[i][a]) continue;                                  // on the plane: its own mirror
      if (std::abs(2 * p.site[i][a] - two_p) > 2 * reach_sites) continue;  // too far to be in a family
      std::vector<std::int32_t> key(m.data(), m.data() + D);
      if (occupied.count(key)) continue;
      occupied.insert(key);
      // A mirror's owner is a particle of p: a real one, or a remote ghost whose values
      // arrive before the mirrors are updated (core::Particles::update_ghosts).
      const bool mirror = i >= p.n_real && p.ghost_owner[i - p.n_real] != core::Particles<D>::kRemoteOwner;
      const Index owner = mirror ? p.ghost_owner[i - p.n_real] : i;
      Vec<D> sign = mirror ? p.ghost_sign[i - p.n_real] : Vec<D>::Ones();
      sign[a] = -sign[a];
      p.push_back(m, p.volume[i]);
      p.ghost_owner.push_back(owner);
      p.ghost_sign.push_back(sign);
    }
  }
}

template <int D>
Index mirror_count(const core::BodySites<D>& body, const std::vector<SymmetryPlane>& planes, double reach) {
  if (planes.empty()) return 0;
  const auto reach_sites = reach_in_sites(reach, body.lattice.spacing);
  core::Particles<D> near;
  near.lattice = body.lattice;
  for (Index g = 0; g < body.size(); ++g) {
    const IVec<D> site = body.site(g);
    const auto within = [&](const SymmetryPlane& plane) {
      return std::abs(2.0 * site[plane.axis] - std::round(twice_site(body.lattice, plane))) <= 2.0 * reach_sites;
    };
    if (std::any_of(planes.begin(), planes.end(), within)) near.push_back(site, body.volume);
  }
  near.n_real = near.size();
  add_symmetry_ghosts(near, planes, reach);
  return near.n_ghost();
}

template void check_symmetry_planes<1>(const core::Lattice<1>&, const IVec<1>&, const IVec<1>&,
                                       const std::vector<SymmetryPlane>&, double, const std::string&);
template void check_symmetry_planes<2>(const core::Lattice<2>&, const IVec<2>&, const IVec<2>&,
                                       const std::vector<SymmetryPlane>&, double, const std::string&);
template void check_symmetry_planes<3>(const core::Lattice<3>&, const IVec<3>&, const IVec<3>&,
                                       const std::vector<SymmetryPlane>&, double, const std::string&);
template void add_symmetry_ghosts<1>(core::Particles<1>&, const std::vector<SymmetryPlane>&, double);
template void add_symmetry_ghosts<2>(core::Particles<2>&, const std::vector<SymmetryPlane>&, double);
template void add_symmetry_ghosts<3>(core::Particles<3>&, const std::vector<SymmetryPlane>&, double);
template Index mirror_count<1>(const core::BodySites<1>&, const std::vector<SymmetryPlane>&, double);
template Index mirror_count<2>(const core::BodySites<2>&, const std::vector<SymmetryPlane>&, double);
template Index mirror_count<3>(const core::BodySites<3>&, const std::vector<SymmetryPlane>&, double);

}  // namespace pdmpm::bc
