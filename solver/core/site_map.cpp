#include "solver/core/site_map.hpp"

#include "solver/core/error.hpp"

namespace pdmpm::core {

template <int D>
SiteMap<D>::SiteMap(const std::vector<IVec<D>>& sites, int pad) {
  lo_ = IVec<D>::Zero();
  extent_ = IVec<D>::Ones();
  if (sites.empty()) {
    cell_.assign(1, -1);
    return;
  }
  IVec<D> lo = sites[0], hi = sites[0];
  for (const auto& s : sites) {
    lo = lo.cwiseMin(s);
    hi = hi.cwiseMax(s);
  }
  lo_ = lo - IVec<D>::Constant(pad);
  extent_ = hi - lo + IVec<D>::Constant(2 * pad + 1);
  std::int64_t total = 1;
  for (int a = 0; a < D; ++a) total *= extent_[a];
  if (total > (std::int64_t{1} << 34))
    throw RunError("lattice bounding box has too many sites for the dense site map");
  cell_.assign(static_cast<std::size_t>(total), -1);
  for (std::size_t i = 0; i < sites.size(); ++i) {
    std::int64_t k = 0;
    for (int a = D - 1; a >= 0; --a) k = k * extent_[a] + (sites[i][a] - lo_[a]);
    if (cell_[k] != -1) throw RunError("two particles occupy the same lattice site");
    cell_[k] = static_cast<Index>(i);
  }
}

template class SiteMap<1>;
template class SiteMap<2>;
template class SiteMap<3>;

}  // namespace pdmpm::core
