#include "solver/dist/decomposition.hpp"

#include <algorithm>
#include <stdexcept>

#include "solver/core/site_map.hpp"

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
std::vector<Index> halo_of(const core::Particles<D>& body, const core::Stencil<D>& stencil, OwnedRange own) {
  if (body.n_ghost() > 0) throw std::invalid_argument("halo_of: the body has ghosts (symmetry planes)");
  const core::SiteMap<D> map(body.site, 0);
  std::vector<std::uint8_t> in_halo(static_cast<std::size_t>(body.n_real), 0);
  for (Index i = own.begin; i < own.end; ++i)
    for (const auto& off : stencil.offset) {
      const Index j = map.find(body.site[i] + off);
      if (j >= 0 && !own.contains(j)) in_halo[j] = 1;
    }
  std::vector<Index> halo;
  for (Index j = 0; j < body.n_real; ++j)
    if (in_halo[j]) halo.push_back(j);
  return halo;
}

template <int D>
core::Particles<D> local_store(const core::Particles<D>& body, OwnedRange own, const std::vector<Index>& halo) {
  core::Particles<D> p;
  p.lattice = body.lattice;
  const auto copy = [&](Index g) {
    p.push_back(body.site[g], body.volume[g]);
    const Index i = p.size() - 1;
    p.u[i] = body.u[g];
    p.v[i] = body.v[g];
    p.b[i] = body.b[g];
    p.kind[i] = body.kind[g];
  };
  for (Index g = own.begin; g < own.end; ++g) copy(g);
  p.n_real = own.size();
  for (const Index g : halo) {
    copy(g);
    p.ghost_owner.push_back(core::Particles<D>::kRemoteOwner);
    p.ghost_sign.push_back(Vec<D>::Ones());
  }
  return p;
}

template std::vector<Index> halo_of<1>(const core::Particles<1>&, const core::Stencil<1>&, OwnedRange);
template std::vector<Index> halo_of<2>(const core::Particles<2>&, const core::Stencil<2>&, OwnedRange);
template std::vector<Index> halo_of<3>(const core::Particles<3>&, const core::Stencil<3>&, OwnedRange);
template core::Particles<1> local_store<1>(const core::Particles<1>&, OwnedRange, const std::vector<Index>&);
template core::Particles<2> local_store<2>(const core::Particles<2>&, OwnedRange, const std::vector<Index>&);
template core::Particles<3> local_store<3>(const core::Particles<3>&, OwnedRange, const std::vector<Index>&);

}  // namespace pdmpm::dist
