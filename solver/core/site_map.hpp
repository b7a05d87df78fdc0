#pragma once
// Dense map from lattice site to particle index over the particles' bounding
// box (padded): the O(N) neighbour look-up for lattice particles. A site with
// no particle maps to -1.
#include <vector>

#include "solver/core/particles.hpp"

namespace pdmpm::core {

template <int D>
class SiteMap {
 public:
  SiteMap(const std::vector<IVec<D>>& sites, int pad);
  Index find(const IVec<D>& s) const {
    std::int64_t k = 0;
    for (int a = D - 1; a >= 0; --a) {
      const std::int32_t c = s[a] - lo_[a];
      if (c < 0 || c >= extent_[a]) return -1;
      k = k * extent_[a] + c;
    }
    return cell_[k];
  }

 private:
  IVec<D> lo_, extent_;
  std::vector<Index> cell_;
};

}  // namespace pdmpm::core
