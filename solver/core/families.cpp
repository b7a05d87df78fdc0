#include "solver/core/families.hpp"

#include <cmath>
#include <limits>

#include "solver/core/error.hpp"
#include "solver/core/site_map.hpp"

namespace pdmpm::core {

template <int D>
Families<D> Families<D>::build(const Particles<D>& p, double ratio) {
  Families fam;
  fam.stencil = Stencil<D>::build(ratio);
  if (fam.stencil.size() > std::numeric_limits<std::uint16_t>::max())
    throw RunError("horizon too large: more than 65535 lattice offsets in a family");
  const SiteMap<D> map(p.site, 0);
  const Index n = p.n_real;
  fam.offsets.assign(static_cast<std::size_t>(n) + 1, 0);

  // Two passes (count, then fill) so the arrays are allocated once and exactly.
  std::vector<BondIndex> count(n, 0);
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i) {
    BondIndex c = 0;
    for (const auto& off : fam.stencil.offset) c += map.find(p.site[i] + off) >= 0;
    count[i] = c;
  }
  for (Index i = 0; i < n; ++i) fam.offsets[i + 1] = fam.offsets[i] + count[i];
  // Padding past the last bond: the SIMD kernels read whole blocks of 8 (masked).
  fam.neighbor.assign(fam.n_bonds() + kBondPadding, 0);
  fam.shape.assign(fam.n_bonds() + kBondPadding, 0);
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i) {
    BondIndex b = fam.offsets[i];
    for (int k = 0; k < fam.stencil.size(); ++k) {
      const Index j = map.find(p.site[i] + fam.stencil.offset[k]);
      if (j < 0) continue;
      fam.neighbor[b] = j;
      fam.shape[b] = static_cast<std::uint16_t>(k);
      ++b;
    }
  }
  return fam;
}

template struct Families<1>;
template struct Families<2>;
template struct Families<3>;

}  // namespace pdmpm::core
