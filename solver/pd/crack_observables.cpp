#include "solver/pd/crack_observables.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

namespace pdmpm::pd {
namespace {

// Disjoint sets with path halving and union by size.
class UnionFind {
 public:
  explicit UnionFind(Index n) : parent_(static_cast<std::size_t>(n)), size_(static_cast<std::size_t>(n), 1) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  Index find(Index i) {
    while (parent_[i] != i) {
      parent_[i] = parent_[parent_[i]];
      i = parent_[i];
    }
    return i;
  }
  void unite(Index a, Index b) {
    a = find(a), b = find(b);
    if (a == b) return;
    if (size_[a] < size_[b]) std::swap(a, b);
    parent_[b] = a;
    size_[a] += size_[b];
  }
  Index size_of_root(Index r) const { return size_[r]; }

 private:
  std::vector<Index> parent_, size_;
};

// The real particle a family member stands for (ghosts mirror an owner).
template <int D>
Index real_of(const core::Particles<D>& p, Index j) {
  return j < p.n_real ? j : p.ghost_owner[j - p.n_real];
}

double angle_of(double x, double y) { return std::atan2(y, x) * 180.0 / std::numbers::pi; }

}  // namespace

double rayleigh_speed(const core::Elastic& m, core::Setting s) {
  const double cs2 = m.shear() / m.rho;
  const double k2 = m.shear() / m.wave_modulus(s);  // (c_s / c_p)²
  // R(ξ) = (2 − ξ²)² − 4 √(1 − ξ²) √(1 − k² ξ²) has one root in (0, 1); bisection.
  auto R = [&](double x) {
    const double x2 = x * x;
    return (2.0 - x2) * (2.0 - x2) - 4.0 * std::sqrt(1.0 - x2) * std::sqrt(1.0 - k2 * x2);
  };
  double lo = 1e-6, hi = 1.0 - 1e-15;  // R(0⁺) < 0 ... R(1) = 1 > 0
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (R(mid) > 0.0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi) * std::sqrt(cs2);
}

template <int D>
double CrackPath<D>::max_speed() const {
  double v = 0.0;
  for (double s : speed)
    if (std::isfinite(s)) v = std::max(v, s);
  return v;
}

template <int D>
double CrackPath<D>::angle_deg() const {
  if (tip.empty()) return 0.0;
  const Vec<D> d = tip.back() - origin;
  if constexpr (D == 1) return d[0] >= 0.0 ? 0.0 : 180.0;
  else return angle_of(d[0], d[1]);
}

template <int D>
CrackObservables<D>::CrackObservables(const System<D>& sys, const CrackSettings& settings,
                                      std::vector<NamedLocation<D>> locations, std::vector<std::uint8_t> exclude)
    : settings_(settings), locations_(std::move(locations)), excluded_(std::move(exclude)) {
  const Index n = sys.n_real();
  // Ten lattice spacings at the Rayleigh speed: a one-site error in the tip then
  // changes the speed by at most a tenth of c_R.
  const double c_ref = D == 1 ? std::sqrt(sys.material.E / sys.material.rho) : rayleigh_speed(sys.material, sys.setting);
  default_window_ = 10.0 * sys.spacing() / c_ref;
  excluded_.resize(static_cast<std::size_t>(n), 0);
  crack_time_.assign(static_cast<std::size_t>(n), -1.0);
  first_failure_.assign(locations_.size(), std::nullopt);
  baseline_broken_.assign(locations_.size(), 0);
  broken_at_.assign(locations_.size(), 0);
}

template <int D>
void CrackObservables<D>::sample(const System<D>& sys, const std::vector<double>& phi, double t) {
  const auto& fam = sys.families;
  const auto& p = sys.particles;
  const Index n = p.n_real;
  if (!started_) {
    for (Index i = 0; i < n; ++i)
      if (phi[i] > 0.0) excluded_[i] = 1;
  }

  for (std::size_t k = 0; k < locations_.size(); ++k) {
    std::int64_t broken = 0;
    for (Index i : locations_[k].particles)
      for (BondIndex b = fam.begin(i); b < fam.end(i); ++b) broken += sys.bonds.broken(b);
    if (!started_) baseline_broken_[k] = broken;
    broken_at_[k] = broken - baseline_broken_[k];
    if (broken_at_[k] > 0 && !first_failure_[k]) first_failure_[k] = t;
  }

  cracked_ = 0;
  for (Index i = 0; i < n; ++i) {
    if (excluded_[i]) continue;
    if (phi[i] >= settings_.path_threshold && crack_time_[i] < 0.0) crack_time_[i] = t;
    if (phi[i] < settings_.threshold) continue;
    ++cracked_;
    if (!initiation_) initiation_particles_.push_back(i);
  }
  if (!initiation_ && cracked_ > 0) initiation_ = t;

  count_components(sys, phi);
  track_cracks(sys, t);
  if (!started_) {
    initial_pieces_ = pieces_;
  } else if (pieces_ > initial_pieces_ && !separation_) {
    separation_ = t;
    separation_angle_ = overall_angle_;
  }
  started_ = true;
}

template <int D>
void CrackObservables<D>::count_components(const System<D>& sys, const std::vector<double>& phi) {
  const auto& p = sys.particles;
  const Index n = p.n_real;
  UnionFind all(n), sound(n);
  auto is_sound = [&](Index i) { return phi[i] < settings_.threshold; };
  for (Index i = 0; i < n; ++i)
    sys.for_each_live_bond(i, [&](BondIndex, Index neighbor, int) {
      const Index j = real_of(p, neighbor);
      all.unite(i, j);
      if (is_sound(i) && is_sound(j)) sound.unite(i, j);
    });
  const double min_size = std::max(1.0, settings_.min_piece_fraction * static_cast<double>(n));
  components_ = pieces_ = 0;
  for (Index i = 0; i < n; ++i) {
    if (all.find(i) == i) ++components_;
    if (is_sound(i) && sound.find(i) == i && static_cast<double>(sound.size_of_root(i)) >= min_size) ++pieces_;
  }
}

template <int D>
void CrackObservables<D>::track_cracks(const System<D>& sys, double t) {
  const auto& fam = sys.families;
  const auto& p = sys.particles;
  const Index n = p.n_real;
  std::vector<Index> cracked;
  for (Index i = 0; i < n; ++i)
    if (crack_time_[i] >= 0.0) cracked.push_back(i);

  // Clusters of cracked particles linked through their families.
  UnionFind uf(n);
  for (Index i : cracked)
    for (BondIndex b = fam.begin(i); b < fam.end(i); ++b) {
      const Index j = real_of(p, fam.neighbor[b]);
      if (crack_time_[j] >= 0.0) uf.unite(i, j);
    }
  // Key of each cluster: its earliest-cracked member (ties: lowest index).
  std::vector<Index> key(static_cast<std::size_t>(n), -1);
  auto earlier = [&](Index a, Index b) { return crack_time_[a] < crack_time_[b] || (crack_time_[a] == crack_time_[b] && a < b); };
  for (Index i : cracked) {
    Index& k = key[uf.find(i)];
    if (k < 0 || earlier(i, k)) k = i;
  }

  // Members of each cluster, grouped by root.
  std::vector<Index> root_slot(static_cast<std::size_t>(n), -1);
  std::vector<std::vector<Index>> groups;
  for (Index i : cracked) {
    Index& slot = root_slot[uf.find(i)];
    if (slot < 0) slot = static_cast<Index>(groups.size()), groups.emplace_back();
    groups[slot].push_back(i);
  }
  std::vector<std::uint8_t> alive(paths_.size(), 0);
  for (const auto& members : groups) {
    const Index k = key[uf.find(members.front())];
    auto found = path_of_key_.find(k);
    if (found == path_of_key_.end()) {
      CrackPath<D> c;
      c.key = k;
      Vec<D> sum = Vec<D>::Zero();
      Index count = 0;
      for (Index i : members)
        if (crack_time_[i] == crack_time_[k]) sum += p.x0[i], ++count;
      c.origin = sum / static_cast<double>(count);
      found = path_of_key_.emplace(k, paths_.size()).first;
      paths_.push_back(std::move(c));
      alive.push_back(0);
    }
    CrackPath<D>& c = paths_[found->second];
    Vec<D> tip = c.origin;
    double far = 0.0;
    for (Index i : members) {
      const double d = (p.x0[i] - c.origin).norm();
      if (d > far) far = d, tip = p.x0[i];
    }
    c.time.push_back(t);
    c.tip.push_back(tip);
    c.extent.push_back(far);
    c.reach.push_back(c.reach.empty() ? far : std::max(c.reach.back(), far));
    c.members = members.size();
    update_speed(c);
    alive[found->second] = 1;
  }
  for (std::size_t c = 0; c < paths_.size(); ++c)
    if (!alive[c]) paths_[c].ended = true;

  // Principal axis of all cracked particles (in the x–y plane).
  if constexpr (D >= 2) {
    if (cracked.size() >= 2) {
      Vec<D> mean = Vec<D>::Zero();
      for (Index i : cracked) mean += p.x0[i];
      mean /= static_cast<double>(cracked.size());
      double sxx = 0, syy = 0, sxy = 0;
      for (Index i : cracked) {
        const Vec<D> d = p.x0[i] - mean;
        sxx += d[0] * d[0], syy += d[1] * d[1], sxy += d[0] * d[1];
      }
      double a = 0.5 * angle_of(sxx - syy, 2.0 * sxy);
      if (a < 0.0) a += 180.0;
      overall_angle_ = a;
    }
  }
}

template <int D>
void CrackObservables<D>::update_speed(CrackPath<D>& c) const {
  const std::size_t k = c.time.size() - 1;
  const double window = settings_.speed_window > 0.0 ? settings_.speed_window : default_window_;
  const double t = c.time[k], t0 = t - window;
  if (window <= 0.0 || t0 < c.time.front()) {
    c.speed.push_back(std::numeric_limits<double>::quiet_NaN());
    return;
  }
  // Least-squares slope of the running maximum of the extent over the samples in
  // [t − W, t]: the tip moves in lattice steps, and a fit through every sample in
  // the window is less sensitive to that than a difference of its two ends.
  double st = 0.0, sr = 0.0, stt = 0.0, str = 0.0;
  int count = 0;
  for (std::size_t q = k + 1; q-- > 0 && c.time[q] >= t0 - 1e-12 * window;) {
    const double x = c.time[q] - t, y = c.reach[q];
    st += x, sr += y, stt += x * x, str += x * y;
    ++count;
  }
  const double den = count * stt - st * st;
  c.speed.push_back(count >= 3 && den > 0.0 ? (count * str - st * sr) / den : std::numeric_limits<double>::quiet_NaN());
}

template <int D>
const CrackPath<D>* CrackObservables<D>::leading() const {
  const CrackPath<D>* best = nullptr;
  for (const auto& c : paths_)
    if (!c.ended && (!best || c.extent.back() > best->extent.back())) best = &c;
  return best;
}

template <int D>
double CrackObservables<D>::max_speed() const {
  double v = 0.0;
  for (const auto& c : paths_) v = std::max(v, c.max_speed());
  return v;
}

template class CrackObservables<1>;
template class CrackObservables<2>;
template class CrackObservables<3>;
template struct CrackPath<1>;
template struct CrackPath<2>;
template struct CrackPath<3>;

}  // namespace pdmpm::pd
