#include "solver/hybrid/crack_tips.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <utility>

#include "solver/core/error.hpp"
#include "solver/core/site_map.hpp"

namespace pdmpm::hybrid {
namespace {

// Calls f(o) for every integer offset o in [−r, r]^D, in a fixed order.
template <int D, class F>
void for_each_offset(int r, F&& f) {
  IVec<D> o = IVec<D>::Constant(-r);
  while (true) {
    f(o);
    int a = 0;
    for (; a < D; ++a) {
      if (++o[a] <= r) break;
      o[a] = -r;
    }
    if (a == D) return;
  }
}

// The particle at s + o, or if that site is missing, at its mirror image
// through s: the first present of the reflections of o in its axes (fixed
// order, single axes first); -1 if none is present.
template <int D>
Index mirrored(const core::SiteMap<D>& map, const IVec<D>& s, const IVec<D>& o) {
  for (int mask = 0; mask < (1 << D); ++mask) {
    IVec<D> r = o;
    for (int a = 0; a < D; ++a)
      if (mask >> a & 1) r[a] = -r[a];
    if (const Index j = map.find(s + r); j >= 0) return j;
  }
  return -1;
}

// Whether the site s (damage phi_s; `around`: the window's offsets and damage,
// missing sites mirrored) lies on the ridge of its crack's damage band: along the
// band's normal — the axis of least covariance about the damage's centroid — no
// present site within `reach` is more than 1 / fraction times as damaged. (The
// moment test's axis, the least second moment about s, is the band's direction
// for a flank site, which sees the band to one side: the flanks vary along the
// crack, a bond more or less broken per particle, and look one-sided.)
template <int D>
bool on_ridge(const core::SiteMap<D>& map, const IVec<D>& s, double phi_s, const std::vector<double>& phi,
              const std::vector<std::pair<IVec<D>, double>>& around, int reach, double fraction) {
  double total = phi_s;
  Vec<D> centroid = Vec<D>::Zero();
  for (const auto& [o, p] : around) total += p, centroid += p * o.template cast<double>();
  centroid /= total;
  Mat<D> covariance = phi_s * centroid * centroid.transpose();
  for (const auto& [o, p] : around) {
    const Vec<D> d = o.template cast<double>() - centroid;
    covariance += p * d * d.transpose();
  }
  const Vec<D> normal = Eigen::SelfAdjointEigenSolver<Mat<D>>(covariance).eigenvectors().col(0);
  double ridge = phi_s;
  for (int t = -reach; t <= reach; ++t) {
    const IVec<D> o = (static_cast<double>(t) * normal).array().round().template cast<int>();
    if (const Index j = map.find(s + o); j >= 0) ridge = std::max(ridge, phi[j]);
  }
  return phi_s >= fraction * ridge;
}

template <int D>
bool site_less(const IVec<D>& a, const IVec<D>& b) {
  return std::lexicographical_compare(a.data(), a.data() + D, b.data(), b.data() + D);
}

void check(const CrackTipSettings& s) {
  auto require = [](bool ok, const char* key, const char* what) {
    if (!ok) throw InputError("", key, what);
  };
  require(s.damage_threshold > 0.0, "damage_threshold", "must be positive");
  require(s.laplacian_threshold < 0.0, "laplacian_threshold", "must be negative (a tip is a minimum of the Laplacian)");
  require(s.end_radius >= 1.0, "end_radius", "must be at least one lattice spacing");
  require(s.end_asymmetry >= 0.0 && s.end_asymmetry <= 1.0, "end_asymmetry", "must lie in [0, 1]");
  require(s.ridge_fraction >= 0.0 && s.ridge_fraction <= 1.0, "ridge_fraction", "must lie in [0, 1]");
  require(s.tip_offset >= 0.0, "tip_offset", "must not be negative");
  require(s.merge_radius >= 0.0, "merge_radius", "must not be negative");
  require(s.match_radius >= 0.0, "match_radius", "must not be negative");
}

}  // namespace

template <int D>
std::vector<CrackTip<D>> find_crack_tips(const core::Lattice<D>& lattice, const std::vector<IVec<D>>& sites,
                                         const std::vector<double>& phi, const CrackTipSettings& s) {
  check(s);
  if (sites.size() != phi.size()) throw RunError("crack tips: one damage value per site expected");
  const core::SiteMap<D> map(sites, 0);
  const auto n = static_cast<Index>(sites.size());

  // ∇²φ Δx², missing neighbours mirrored through the site (zero normal derivative).
  std::vector<double> lap(sites.size(), 0.0);
  for (Index i = 0; i < n; ++i) {
    for (int a = 0; a < D; ++a) {
      const Index p = mirrored<D>(map, sites[i], IVec<D>::Unit(a)), m = mirrored<D>(map, sites[i], -IVec<D>::Unit(a));
      if (p >= 0) lap[i] += phi[p] + phi[m] - 2.0 * phi[i];
    }
  }

  struct Candidate {
    Index i;
    Vec<D> ahead;  // unit vector from the damage towards the intact side
  };
  const int reach = static_cast<int>(std::floor(s.end_radius));
  const double r2 = s.end_radius * s.end_radius;
  // Crack ends: sites below the ∇²φ threshold, near damage, whose damage is one-sided.
  std::vector<std::uint8_t> is_end(sites.size(), 0);
  std::vector<Vec<D>> ahead(sites.size(), Vec<D>::Zero());
  for (Index i = 0; i < n; ++i) {
    if (lap[i] >= s.laplacian_threshold) continue;
    double damage = phi[i];
    for_each_offset<D>(1, [&](const IVec<D>& o) {
      const Index j = map.find(sites[i] + o);
      if (j >= 0) damage = std::max(damage, phi[j]);
    });
    if (damage < s.damage_threshold) continue;

    // One-sidedness of the damage within the crack's line (plane), whose normal
    // is the axis of least spread of the damage around the site.
    std::vector<std::pair<IVec<D>, double>> around;
    Mat<D> spread = Mat<D>::Zero();
    for_each_offset<D>(reach, [&](const IVec<D>& o) {
      const double o2 = o.squaredNorm();
      if (o2 == 0 || o2 > r2) return;
      const Index j = mirrored(map, sites[i], o);
      if (j < 0) return;
      around.emplace_back(o, phi[j]);
      spread += phi[j] * o.template cast<double>() * o.template cast<double>().transpose();
    });
    const Vec<D> normal = Eigen::SelfAdjointEigenSolver<Mat<D>>(spread).eigenvectors().col(0);
    const Mat<D> in_plane = Mat<D>::Identity() - normal * normal.transpose();
    Vec<D> moment = Vec<D>::Zero();
    double weight = 0.0;
    for (const auto& [o, p] : around) {
      const Vec<D> t = in_plane * o.template cast<double>();
      moment += p * t;
      weight += p * t.norm();
    }
    if (weight > 0.0 && moment.norm() >= s.end_asymmetry * weight &&
        on_ridge<D>(map, sites[i], phi[i], phi, around, reach, s.ridge_fraction)) {
      is_end[i] = 1;
      ahead[i] = -moment.normalized();
    }
  }
  // Candidates: crack-end sites that are minima of ∇²φ among all their neighbours.
  // Behind a running crack the damage keeps growing, so the deepest ∇²φ can lie on
  // the ridge behind the end and no end site is such a minimum: a connected group of
  // end sites without a candidate contributes its deepest site instead.
  std::vector<Candidate> candidates;
  std::vector<std::uint8_t> in_group(sites.size(), 0);
  for (Index i = 0; i < n; ++i) {
    if (!is_end[i]) continue;
    bool minimum = true;
    for_each_offset<D>(1, [&](const IVec<D>& o) {
      const Index j = map.find(sites[i] + o);
      if (j >= 0) minimum = minimum && lap[i] <= lap[j];
    });
    if (minimum) candidates.push_back({i, ahead[i]});
  }
  std::vector<std::uint8_t> has_candidate(sites.size(), 0);
  for (const auto& c : candidates) has_candidate[c.i] = 1;
  for (Index seed = 0; seed < n; ++seed) {
    if (!is_end[seed] || in_group[seed]) continue;
    std::vector<Index> group{seed};
    in_group[seed] = 1;
    for (std::size_t k = 0; k < group.size(); ++k)
      for_each_offset<D>(1, [&](const IVec<D>& o) {
        const Index j = map.find(sites[group[k]] + o);
        if (j >= 0 && is_end[j] && !in_group[j]) {
          in_group[j] = 1;
          group.push_back(j);
        }
      });
    if (std::any_of(group.begin(), group.end(), [&](Index i) { return has_candidate[i] != 0; })) continue;
    const Index deepest = *std::min_element(group.begin(), group.end(), [&](Index a, Index b) {
      return lap[a] != lap[b] ? lap[a] < lap[b] : site_less<D>(sites[a], sites[b]);
    });
    candidates.push_back({deepest, ahead[deepest]});
  }

  std::sort(candidates.begin(), candidates.end(), [&](const Candidate& a, const Candidate& b) {
    return lap[a.i] != lap[b.i] ? lap[a.i] < lap[b.i] : site_less<D>(sites[a.i], sites[b.i]);
  });
  const double merge2 = s.merge_radius * s.merge_radius;
  std::vector<CrackTip<D>> tips;
  for (const auto& [i, toward_intact] : candidates) {
    const bool near = std::any_of(tips.begin(), tips.end(), [&](const CrackTip<D>& t) {
      return static_cast<double>((t.site - sites[i]).squaredNorm()) <= merge2;
    });
    if (near) continue;
    // Vertex of the parabola through ∇²φ at the site and its two neighbours per
    // axis (within ±½: the site is a minimum), then tip_offset towards the intact side.
    Vec<D> x = sites[i].template cast<double>() + s.tip_offset * toward_intact;
    for (int a = 0; a < D; ++a) {
      const Index p = mirrored<D>(map, sites[i], IVec<D>::Unit(a)), m = mirrored<D>(map, sites[i], -IVec<D>::Unit(a));
      if (p < 0) continue;
      const double curvature = lap[p] - 2.0 * lap[i] + lap[m];
      if (curvature > 0.0) x[a] -= std::clamp(0.5 * (lap[p] - lap[m]) / curvature, -0.5, 0.5);
    }
    tips.push_back({-1, sites[i], lattice.origin + lattice.spacing * x, lap[i] / (lattice.spacing * lattice.spacing)});
  }
  std::sort(tips.begin(), tips.end(),
            [](const CrackTip<D>& a, const CrackTip<D>& b) { return site_less<D>(a.site, b.site); });
  return tips;
}

template <int D>
std::vector<CrackTip<D>> match_crack_tips(const std::vector<CrackTip<D>>& previous, std::vector<CrackTip<D>> found,
                                          const CrackTipSettings& s, int& next_id) {
  check(s);
  // All pairs within the matching radius, closest first (ties by index: deterministic).
  std::vector<std::tuple<double, std::size_t, std::size_t>> pairs;
  for (std::size_t a = 0; a < previous.size(); ++a)
    for (std::size_t b = 0; b < found.size(); ++b) {
      const double d = (previous[a].site - found[b].site).template cast<double>().norm();
      if (d <= s.match_radius) pairs.emplace_back(d, a, b);
    }
  std::sort(pairs.begin(), pairs.end());
  std::vector<bool> taken(previous.size(), false);
  for (auto& t : found) t.id = -1;
  for (const auto& [d, a, b] : pairs) {
    if (taken[a] || found[b].id >= 0) continue;
    taken[a] = true;
    found[b].id = previous[a].id;
  }
  for (auto& t : found)
    if (t.id < 0) t.id = next_id++;
  std::sort(found.begin(), found.end(), [](const CrackTip<D>& a, const CrackTip<D>& b) { return a.id < b.id; });
  return found;
}

template std::vector<CrackTip<2>> find_crack_tips(const core::Lattice<2>&, const std::vector<IVec<2>>&,
                                                  const std::vector<double>&, const CrackTipSettings&);
template std::vector<CrackTip<3>> find_crack_tips(const core::Lattice<3>&, const std::vector<IVec<3>>&,
                                                  const std::vector<double>&, const CrackTipSettings&);
template std::vector<CrackTip<2>> match_crack_tips(const std::vector<CrackTip<2>>&, std::vector<CrackTip<2>>,
                                                   const CrackTipSettings&, int&);
template std::vector<CrackTip<3>> match_crack_tips(const std::vector<CrackTip<3>>&, std::vector<CrackTip<3>>,
                                                   const CrackTipSettings&, int&);

}  // namespace pdmpm::hybrid
