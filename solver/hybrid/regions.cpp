#include "solver/hybrid/regions.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "solver/core/error.hpp"

namespace pdmpm::hybrid {

using core::ParticleKind;

namespace {

void check_radius(const std::string& file, const std::string& key, double r) {
  if (!(std::isfinite(r) && r > 0.0)) {
    std::ostringstream m;
    m << "must be a positive, finite number of horizons δ (got " << r << ")";
    throw InputError(file, key, m.str());
  }
}

// Calls f(j) for every real particle j whose site is an offset of `ball` away
// from i's: the one place that measures distance (reference configuration,
// exact on the lattice; see regions.hpp). Stops early, and returns true, when f
// returns true.
template <int D, class F>
bool any_within(const RegionMap<D>& map, Index i, const core::Stencil<D>& ball, F&& f) {
  for (const auto& off : ball.offset) {
    const Index j = map.find(map.site(i) + off);
    if (j >= 0 && j < map.n_real() && f(j)) return true;
  }
  return false;
}

template <int D>
void check_shapes(const RegionMap<D>& map, std::span<const ParticleKind> kind, std::span<const std::uint8_t> removed) {
  if (kind.size() != static_cast<std::size_t>(map.size()))
    throw RunError("hybrid regions: one kind per particle expected (real and ghosts)");
  if (removed.size() < static_cast<std::size_t>(map.n_real()))
    throw RunError("hybrid regions: the removed mask must cover every real particle");
}

template <int D>
void check_index(const RegionMap<D>& map, Index i) {
  if (i < 0 || i >= map.n_real()) throw RunError("hybrid regions: particle index out of the real particles");
}

// Makes every non-removed, non-PD real particle within `ball` of i PD, appending it to `made`.
template <int D>
void convert_ball(const RegionMap<D>& map, Index i, const core::Stencil<D>& ball, std::span<ParticleKind> kind,
                  std::span<const std::uint8_t> removed, std::vector<Index>& made) {
  any_within(map, i, ball, [&](Index j) {
    if (!removed[j] && kind[j] != ParticleKind::pd) {
      kind[j] = ParticleKind::pd;
      made.push_back(j);
    }
    return false;
  });
}

}  // namespace

void RegionRadii::validate(const std::string& file) const {
  check_radius(file, "hybrid.pd_radius", pd_radius);
  check_radius(file, "hybrid.expand_trigger", expand_trigger);
  check_radius(file, "hybrid.expand_radius", expand_radius);
  check_radius(file, "hybrid.keep_radius", keep_radius);
  // Everything within l_ext of a trigger becomes PD, so the new transition
  // particles are beyond l_ext: with l_crit < l_ext the same trigger cannot
  // fire again at once, otherwise one broken bond would grow the region forever.
  if (expand_trigger >= expand_radius) {
    std::ostringstream m;
    m << "must be smaller than hybrid.expand_radius (got " << expand_trigger << " ≥ " << expand_radius << ")";
    throw InputError(file, "hybrid.expand_trigger", m.str());
  }
}

template <int D>
RegionMap<D>::RegionMap(const core::Particles<D>& p, double horizon_ratio, double family_ratio,
                        const RegionRadii& radii)
    : lattice_(p.lattice),
      site_(p.site),
      ghost_owner_(p.ghost_owner),
      n_real_(p.n_real),
      map_(p.site, 0),
      keep_ratio_(radii.keep_radius * horizon_ratio) {
  radii.validate();
  if (!(horizon_ratio > 0.0 && family_ratio > 0.0))
    throw RunError("hybrid regions: the horizon and the bond reach must be positive");
  bonds_ = core::Stencil<D>::build(family_ratio);
  pd_ball_ = core::Stencil<D>::build(radii.pd_radius * horizon_ratio);
  trigger_ball_ = core::Stencil<D>::build(radii.expand_trigger * horizon_ratio);
  expand_ball_ = core::Stencil<D>::build(radii.expand_radius * horizon_ratio);
}

template <int D>
void classify(const RegionMap<D>& map, std::span<ParticleKind> kind, std::span<const std::uint8_t> removed) {
  check_shapes<D>(map, kind, removed);
  const Index n = map.n_real();
  for (Index i = 0; i < n; ++i)
    if (!removed[i] && kind[i] != ParticleKind::pd) kind[i] = ParticleKind::mpm;
  // Marking from the PD side costs O(N_pd · bonds). Ghosts need no visit: the
  // body lies on one side of each symmetry plane, so a mirror image is never
  // nearer a real particle than the PD particle it mirrors.
  for (Index i = 0; i < n; ++i) {
    if (removed[i] || kind[i] != ParticleKind::pd) continue;
    any_within(map, i, map.bonds(), [&](Index j) {
      if (!removed[j] && kind[j] == ParticleKind::mpm) kind[j] = ParticleKind::transition;
      return false;
    });
  }
  for (Index g = n; g < map.size(); ++g) kind[g] = kind[map.owner(g)];
}

template <int D>
std::vector<Index> onset(const RegionMap<D>& map, std::span<const Index> failed, std::span<ParticleKind> kind,
                         std::span<std::uint8_t> removed) {
  check_shapes<D>(map, kind, removed);
  for (const Index f : failed) {
    check_index(map, f);
    if (removed[f]) throw RunError("hybrid regions: a particle failed after it was removed (or is listed twice)");
    removed[f] = 1;
    kind[f] = ParticleKind::removed;
  }
  return seed<D>(map, failed, kind, removed);
}

template <int D>
std::vector<Index> seed(const RegionMap<D>& map, std::span<const Index> centres, std::span<ParticleKind> kind,
                        std::span<const std::uint8_t> removed) {
  check_shapes<D>(map, kind, removed);
  std::vector<Index> made;
  for (const Index c : centres) {
    check_index(map, c);
    convert_ball(map, c, map.pd_ball(), kind, removed, made);
  }
  std::sort(made.begin(), made.end());
  classify(map, kind, removed);
  return made;
}

template <int D>
std::vector<Index> expand(const RegionMap<D>& map, std::span<const Index> triggers, std::span<ParticleKind> kind,
                          std::span<const std::uint8_t> removed) {
  check_shapes<D>(map, kind, removed);
  std::vector<Index> fired;
  for (const Index t : triggers) {
    check_index(map, t);
    if (removed[t] || kind[t] != ParticleKind::pd) continue;
    if (any_within(map, t, map.trigger_ball(), [&](Index j) { return kind[j] == ParticleKind::transition; }))
      fired.push_back(t);
  }
  std::vector<Index> made;
  for (const Index t : fired) convert_ball(map, t, map.expand_ball(), kind, removed, made);
  std::sort(made.begin(), made.end());
  classify(map, kind, removed);
  return made;
}

template <int D>
std::vector<Index> shrink(const RegionMap<D>& map, const std::vector<Vec<D>>& tips, std::span<const std::uint8_t> keep,
                          std::span<ParticleKind> kind, std::span<const std::uint8_t> removed) {
  check_shapes<D>(map, kind, removed);
  if (keep.size() < static_cast<std::size_t>(map.n_real()))
    throw RunError("hybrid regions: the keep mask must cover every real particle");
  // Tips in lattice units, compared on squared lengths with the stencils' slack
  // (core::Stencil), so a particle exactly at l_con counts as near.
  std::vector<Vec<D>> t;
  for (const auto& tip : tips) t.push_back((tip - map.lattice().origin) / map.lattice().spacing);
  const double limit = map.keep_ratio() * map.keep_ratio() * (1.0 + 1e-10);
  std::vector<Index> reverted;
  for (Index i = 0; i < map.n_real(); ++i) {
    if (removed[i] || keep[i] || kind[i] != ParticleKind::pd) continue;
    const Vec<D> s = map.site(i).template cast<double>();
    const bool near = std::any_of(t.begin(), t.end(), [&](const Vec<D>& x) { return (s - x).squaredNorm() <= limit; });
    if (!near) {
      kind[i] = ParticleKind::mpm;
      reverted.push_back(i);
    }
  }
  classify(map, kind, removed);
  return reverted;
}

template class RegionMap<2>;
template void classify<2>(const RegionMap<2>&, std::span<ParticleKind>, std::span<const std::uint8_t>);
template std::vector<Index> onset<2>(const RegionMap<2>&, std::span<const Index>, std::span<ParticleKind>,
                                     std::span<std::uint8_t>);
template std::vector<Index> seed<2>(const RegionMap<2>&, std::span<const Index>, std::span<ParticleKind>,
                                    std::span<const std::uint8_t>);
template std::vector<Index> expand<2>(const RegionMap<2>&, std::span<const Index>, std::span<ParticleKind>,
                                      std::span<const std::uint8_t>);
template std::vector<Index> shrink<2>(const RegionMap<2>&, const std::vector<Vec<2>>&, std::span<const std::uint8_t>,
                                      std::span<ParticleKind>, std::span<const std::uint8_t>);
template class RegionMap<3>;
template void classify<3>(const RegionMap<3>&, std::span<ParticleKind>, std::span<const std::uint8_t>);
template std::vector<Index> onset<3>(const RegionMap<3>&, std::span<const Index>, std::span<ParticleKind>,
                                     std::span<std::uint8_t>);
template std::vector<Index> seed<3>(const RegionMap<3>&, std::span<const Index>, std::span<ParticleKind>,
                                    std::span<const std::uint8_t>);
template std::vector<Index> expand<3>(const RegionMap<3>&, std::span<const Index>, std::span<ParticleKind>,
                                      std::span<const std::uint8_t>);
template std::vector<Index> shrink<3>(const RegionMap<3>&, const std::vector<Vec<3>>&, std::span<const std::uint8_t>,
                                      std::span<ParticleKind>, std::span<const std::uint8_t>);

}  // namespace pdmpm::hybrid
