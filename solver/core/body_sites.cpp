#include "solver/core/body_sites.hpp"

#include <algorithm>
#include <cmath>

#include "solver/core/morton.hpp"

namespace pdmpm::core {

template <int D>
IVec<D> BodySites<D>::site(Index g) const {
  return morton_site<D>(keys[static_cast<std::size_t>(g)], lowest);
}

template <int D>
Index BodySites<D>::find(const IVec<D>& s) const {
  if (!morton_encodable<D>(s, lowest)) return -1;
  const std::uint64_t key = morton_key<D>(s, lowest);
  const auto it = std::lower_bound(keys.begin(), keys.end(), key);
  return it != keys.end() && *it == key ? static_cast<Index>(it - keys.begin()) : -1;
}

template <int D>
Particles<D> BodySites<D>::particles(Index begin, Index end, const std::vector<Index>& remote_ghosts) const {
  Particles<D> p;
  p.lattice = lattice;
  for (Index g = begin; g < end; ++g) p.push_back(site(g), volume);
  p.n_real = end - begin;
  for (const Index g : remote_ghosts) p.push_back(site(g), volume);
  p.ghost_owner.assign(remote_ghosts.size(), Particles<D>::kRemoteOwner);
  p.ghost_sign.assign(remote_ghosts.size(), Vec<D>::Ones());
  return p;
}

template <int D>
BodySites<D> body_sites(const Geometry<D>& geometry, const Lattice<D>& lattice, double volume) {
  BodySites<D> body;
  body.lattice = lattice;
  body.volume = volume;
  if (geometry.empty()) return body;
  // Sites on a shape boundary count as inside: tolerance far below Δx, far above round-off.
  const double tol = 1e-9 * lattice.spacing;
  const Bounds<D> b = geometry.bounds();
  IVec<D> lo, hi;
  for (int a = 0; a < D; ++a) {
    lo[a] = static_cast<std::int32_t>(std::ceil((b.min[a] - lattice.origin[a] - tol) / lattice.spacing));
    hi[a] = static_cast<std::int32_t>(std::floor((b.max[a] - lattice.origin[a] + tol) / lattice.spacing));
    if (hi[a] < lo[a]) return body;
  }
  body.lowest = lo;
  IVec<D> s = lo;
  while (true) {
    if (geometry.contains(lattice.position(s), tol)) body.keys.push_back(morton_key<D>(s, lo));
    int a = 0;
    for (; a < D; ++a) {
      if (++s[a] <= hi[a]) break;
      s[a] = lo[a];
    }
    if (a == D) break;
  }
  std::sort(body.keys.begin(), body.keys.end());
  return body;
}

template struct BodySites<1>;
template struct BodySites<2>;
template struct BodySites<3>;
template BodySites<1> body_sites(const Geometry<1>&, const Lattice<1>&, double);
template BodySites<2> body_sites(const Geometry<2>&, const Lattice<2>&, double);
template BodySites<3> body_sites(const Geometry<3>&, const Lattice<3>&, double);

}  // namespace pdmpm::core
