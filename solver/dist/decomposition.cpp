#include "solver/dist/decomposition.hpp"

#include <algorithm>
#include <stdexcept>

namespace pdmpm::dist {

OwnedRange owned_range(Index n, int rank, int ranks) {
  const auto at = [&](int r) { return static_cast<Index>(static_cast<std::int64_t>(n) * r / ranks); };
  return {at(rank), at(rank + 1)};
}

int owner_rank(Index g, Index n, int ranks) {
  // The range formula rounds down, so the estimate is off by at most one either way.
  int r = static_cast<int>(static_cast<std::int64_t>(g) * ranks / std::max<Index>(n, 1));
  r = std::clamp(r, 0, ranks - 1);
  while (r > 0 && g < owned_range(n, r, ranks).begin) --r;
  while (r + 1 < ranks && g >= owned_range(n, r, ranks).end) ++r;
  return r;
}

template <int D>
Halo halo_of(const core::BodySites<D>& body, const core::Stencil<D>& stencil, OwnedRange own) {
  Halo halo;
  for (Index i = own.begin; i < own.end; ++i) {
    const IVec<D> site = body.site(i);
    for (const auto& off : stencil.offset) {
      const Index j = body.find(site + off);
      halo.own_bonds += j >= 0;
      if (j >= 0 && !own.contains(j)) halo.global.push_back(j);
    }
  }
  std::sort(halo.global.begin(), halo.global.end());
  halo.global.erase(std::unique(halo.global.begin(), halo.global.end()), halo.global.end());
  return halo;
}

template Halo halo_of<1>(const core::BodySites<1>&, const core::Stencil<1>&, OwnedRange);
template Halo halo_of<2>(const core::BodySites<2>&, const core::Stencil<2>&, OwnedRange);
template Halo halo_of<3>(const core::BodySites<3>&, const core::Stencil<3>&, OwnedRange);

}  // namespace pdmpm::dist
