#include "solver/core/particle_builder.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "solver/core/morton.hpp"

namespace pdmpm::core {

template <int D>
Particles<D> fill_lattice(const Geometry<D>& geometry, const Lattice<D>& lattice, double volume) {
  Particles<D> p;
  p.lattice = lattice;
  if (geometry.empty()) return p;

  // Sites on a shape boundary count as inside: tolerance far below Δx, far above round-off.
  const double tol = 1e-9 * lattice.spacing;
  const Bounds<D> b = geometry.bounds();
  IVec<D> lo, hi;
  for (int a = 0; a < D; ++a) {
    lo[a] = static_cast<std::int32_t>(std::ceil((b.min[a] - lattice.origin[a] - tol) / lattice.spacing));
    hi[a] = static_cast<std::int32_t>(std::floor((b.max[a] - lattice.origin[a] + tol) / lattice.spacing));
    if (hi[a] < lo[a]) return p;
  }

  std::vector<IVec<D>> sites;
  IVec<D> s = lo;
  while (true) {
    if (geometry.contains(lattice.position(s), tol)) sites.push_back(s);
    int a = 0;
    for (; a < D; ++a) {
      if (++s[a] <= hi[a]) break;
      s[a] = lo[a];
    }
    if (a == D) break;
  }

  std::vector<std::uint64_t> key(sites.size());
  for (std::size_t k = 0; k < sites.size(); ++k) key[k] = morton_key<D>(sites[k], lo);
  std::vector<std::size_t> order(sites.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return key[x] < key[y]; });

  for (std::size_t k : order) p.push_back(sites[k], volume);
  p.n_real = p.size();
  return p;
}

template Particles<1> fill_lattice(const Geometry<1>&, const Lattice<1>&, double);
template Particles<2> fill_lattice(const Geometry<2>&, const Lattice<2>&, double);
template Particles<3> fill_lattice(const Geometry<3>&, const Lattice<3>&, double);

}  // namespace pdmpm::core
