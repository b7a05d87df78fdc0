#include "solver/pd/contact.hpp"

#include <cmath>

namespace pdmpm::pd {
namespace {

// True if the particle of global index gj is a live bond partner of i.
template <int D>
bool bonded(const System<D>& sys, Index i, Index gj) {
  const auto& fam = sys.families;
  for (BondIndex b = fam.begin(i); b < fam.end(i); ++b)
    if (sys.particles.global_index(fam.neighbor[b]) == gj) return sys.bonds.live(b);
  return false;
}

}  // namespace

template <int D>
Index ShortRangeContact<D>::global_of_entry(const core::Particles<D>& p, Index k) const {
  if (!p.remote) return k;
  return k < p.n_real ? p.global_index(k) : ghosts_.global()[k - p.n_real];
}

// Whether a particle of the list's first `local` ones moved more than skin/2 since the
// last build (the others are some other process's first ones).
template <int D>
bool ShortRangeContact<D>::list_is_stale(Index local, double skin) const {
  if (y_at_build_.size() < static_cast<std::size_t>(local)) return true;
  const double limit2 = 0.25 * skin * skin;
  bool stale = false;
#pragma omp parallel for schedule(static) reduction(|| : stale)
  for (Index i = 0; i < local; ++i) stale = stale || (y_[i] - y_at_build_[i]).squaredNorm() > limit2;
  return stale;
}

// Candidates j ≠ i within `radius` of each real particle, in the cell list's
// fixed order (two passes: count, then fill), so the list is the same for any
// number of threads — and of processes: distributed, the cells cover the whole body's
// box and hold their particles in the global order.
template <int D>
void ShortRangeContact<D>::build_list(const core::Particles<D>& p, Index local, double radius) {
  x0_.assign(p.x0.begin(), p.x0.begin() + local);
  volume_.assign(p.volume.begin(), p.volume.begin() + local);
  if (p.remote) {
    const auto& gx0 = ghosts_.reference_position();
    x0_.insert(x0_.end(), gx0.begin(), gx0.end());
    volume_.insert(volume_.end(), ghosts_.volume().begin(), ghosts_.volume().end());
    // Global order: the lower processes' ghosts, own particles, the higher processes' ghosts.
    const Index lower = ghosts_.from_lower_processes(), n = static_cast<Index>(y_.size());
    std::vector<Index> order;
    order.reserve(y_.size());
    for (Index k = local; k < local + lower; ++k) order.push_back(k);
    for (Index k = 0; k < local; ++k) order.push_back(k);
    for (Index k = local + lower; k < n; ++k) order.push_back(k);
    cells_.build(y_, radius, ghosts_.body_lo(), ghosts_.body_hi(), order);
  } else {
    cells_.build(y_, radius);
  }
  const double r2 = radius * radius;
  std::vector<std::int64_t> count(static_cast<std::size_t>(real_) + 1, 0);
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < real_; ++i) {
    std::int64_t c = 0;
    cells_.for_each_near(y_[i], [&](Index j) { c += j != i && (y_[j] - y_[i]).squaredNorm() < r2; });
    count[static_cast<std::size_t>(i) + 1] = c;
  }
  for (Index i = 0; i < real_; ++i) count[i + 1] += count[i];
  start_ = std::move(count);
  partner_.resize(static_cast<std::size_t>(start_.back()));
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < real_; ++i) {
    std::int64_t k = start_[i];
    cells_.for_each_near(y_[i], [&](Index j) {
      if (j != i && (y_[j] - y_[i]).squaredNorm() < r2) partner_[static_cast<std::size_t>(k++)] = j;
    });
  }
  y_at_build_ = y_;
}

template <int D>
std::int64_t ShortRangeContact<D>::add_forces(System<D>& sys) {
  auto& p = sys.particles;
  const double dx = sys.spacing();
  const double reach = prm_.max_distance * dx;
  const double skin = 0.3 * dx;  // a list of ~18 partners in 3D, rebuilt rarely in small-strain runs
  const double k = prm_.stiffness_factor * c_ / sys.delta;
  // One process lists its real particles and symmetry ghosts; a distributed process its
  // own particles (its halo's are other processes' own, and come as contact ghosts).
  const Index local = p.remote ? p.n_real : p.size();
  y_.resize(local);
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < local; ++i) y_[i] = p.position(i);
  real_ = p.n_real;
  bool stale = list_is_stale(local, skin) || static_cast<Index>(start_.size()) != real_ + 1;
  if (p.remote) {
    stale = p.remote->max(stale ? 1.0 : 0.0) > 0.0;  // every process rebuilds with the others
    if (stale)
      ghosts_.find(p, y_, reach + skin);
    else
      ghosts_.refresh(p, y_);
    y_.insert(y_.end(), ghosts_.position().begin(), ghosts_.position().end());
  }
  if (stale) build_list(p, local, reach + skin);
  const double reach2 = reach * reach, f2 = prm_.distance_factor * prm_.distance_factor;
  std::int64_t pairs = 0, across = 0;
#pragma omp parallel for schedule(static) reduction(+ : pairs, across)
  for (Index i = 0; i < p.n_real; ++i) {
    Vec<D> fi = Vec<D>::Zero();
    for (std::int64_t q = start_[i]; q < start_[i + 1]; ++q) {
      const Index j = partner_[static_cast<std::size_t>(q)];
      // Squared distances reject partners out of reach without a square root (as
      // LAMMPS' peri/pmb compares r² with d²).
      const Vec<D> d = y_[j] - y_[i];
      const double l2 = d.squaredNorm();
      if (l2 >= reach2 || l2 == 0.0) continue;
      // Most candidates are lattice neighbours at rest, out of their own reach d_ij:
      // rejected on squares too; the square roots only for pairs that press.
      const double r02 = (x0_[j] - x0_[i]).squaredNorm();
      if (l2 >= std::min(f2 * r02, reach2) || (!prm_.bonded_pairs && bonded(sys, i, global_of_entry(p, j)))) continue;
      const double dij = std::min(prm_.distance_factor * std::sqrt(r02), reach);
      const double l = std::sqrt(l2);
      fi += (k * (l - dij) * volume_[j] / l) * d;
      ++pairs;
      across += j >= local;  // another process's particle (none in one process: local is everyone)
    }
    p.f[i] += fi;
  }
  if (p.remote) {
    const auto total = p.template sum_in_order<2>([&](double* s) {
      s[0] += static_cast<double>(pairs);
      s[1] += static_cast<double>(across);
    });
    pairs = static_cast<std::int64_t>(total[0]);
    most_across_ = std::max(most_across_, static_cast<std::int64_t>(total[1]));
  }
  return pairs;
}

template <int D>
double ShortRangeContact<D>::stiffness_row_sum(const System<D>& sys) const {
  // Every lattice neighbour within the contact reach could press at once.
  const double dx = sys.spacing();
  const double reach = prm_.max_distance * dx;
  int neighbours = 0;
  const int r = static_cast<int>(std::ceil(prm_.max_distance));
  IVec<D> o = IVec<D>::Constant(-r);
  while (true) {
    const double l = dx * std::sqrt(static_cast<double>(o.squaredNorm()));
    if (o.squaredNorm() > 0 && l < reach) ++neighbours;
    int a = 0;
    for (; a < D; ++a) {
      if (++o[a] <= r) break;
      o[a] = -r;
    }
    if (a == D) break;
  }
  double vmax = 0.0;
  for (double v : sys.particles.volume) vmax = std::max(vmax, v);
  vmax = sys.particles.max_everywhere(vmax);
  return neighbours * vmax * prm_.stiffness_factor * c_ / sys.delta;
}

template <int D>
void ShortRangeContact<D>::checkpoint(core::StateArchive& a) {
  a.sync("contact/positions", y_);
  a.sync("contact/positions_at_build", y_at_build_);
  a.sync("contact/reference_positions", x0_);
  a.sync("contact/volume", volume_);
  ghosts_.checkpoint(a);
  a.sync("contact/real", real_);
  a.sync("contact/most_pairs_across_processes", most_across_);
  a.sync("contact/start", start_);
  a.sync("contact/partner", partner_);
}

template class ShortRangeContact<1>;
template class ShortRangeContact<2>;
template class ShortRangeContact<3>;

}  // namespace pdmpm::pd
