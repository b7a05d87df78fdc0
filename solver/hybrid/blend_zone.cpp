#include "solver/hybrid/blend_zone.hpp"

#include <cmath>
#include <limits>

namespace pdmpm::hybrid {

using core::ParticleKind;

template <int D>
void classify_blended(const RegionMap<D>& map, const BlendBand& band, std::span<ParticleKind> kind,
                      std::span<const std::uint8_t> removed, std::vector<double>& beta) {
  const Index n = map.n_real();
  const core::Stencil<D> ball = core::Stencil<D>::build(band.zone());
  // Squared distance (lattice units) to the nearest PD particle, marked from the PD side
  // (O(N_pd · zone)). Only a PD particle with a site within one bond reach that holds no
  // PD particle can be the nearest: a unit step from the nearest one towards the particle
  // comes closer, so that site holds none.
  std::vector<int> nearest(static_cast<std::size_t>(n), std::numeric_limits<int>::max());
  auto is_pd = [&](Index j) { return j >= 0 && j < n && !removed[j] && kind[j] == ParticleKind::pd; };
  for (Index i = 0; i < n; ++i) {
    if (!is_pd(i)) continue;
    bool rim = false;
    for (const auto& off : map.bonds().offset)
      if (!is_pd(map.find(map.site(i) + off))) {
        rim = true;
        break;
      }
    if (!rim) continue;
    for (int k = 0; k < ball.size(); ++k) {
      const Index j = map.find(map.site(i) + ball.offset[k]);
      if (j >= 0 && j < n && !removed[j] && kind[j] != ParticleKind::pd)
        nearest[j] = std::min(nearest[j], ball.length2[k]);
    }
  }
  beta.assign(static_cast<std::size_t>(map.size()), 0.0);
  for (Index i = 0; i < n; ++i) {
    if (removed[i]) continue;
    if (kind[i] == ParticleKind::pd) {
      beta[i] = 1.0;
      continue;
    }
    const bool in_zone = nearest[i] != std::numeric_limits<int>::max();
    kind[i] = in_zone ? ParticleKind::transition : ParticleKind::mpm;
    if (in_zone) beta[i] = band.weight(std::sqrt(static_cast<double>(nearest[i])));
  }
  for (Index g = n; g < map.size(); ++g) kind[g] = kind[map.owner(g)], beta[g] = beta[map.owner(g)];
}

template void classify_blended<2>(const RegionMap<2>&, const BlendBand&, std::span<ParticleKind>,
                                  std::span<const std::uint8_t>, std::vector<double>&);
template void classify_blended<3>(const RegionMap<3>&, const BlendBand&, std::span<ParticleKind>,
                                  std::span<const std::uint8_t>, std::vector<double>&);

}  // namespace pdmpm::hybrid
