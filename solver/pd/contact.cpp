#include "solver/pd/contact.hpp"

#include <cmath>

namespace pdmpm::pd {
namespace {

// True if j is an intact bond partner of i.
template <int D>
bool bonded(const System<D>& sys, Index i, Index j) {
  const auto& fam = sys.families;
  for (BondIndex b = fam.begin(i); b < fam.end(i); ++b)
    if (fam.neighbor[b] == j) return !sys.broken[b];
  return false;
}

}  // namespace

template <int D>
std::int64_t ShortRangeContact<D>::add_forces(System<D>& sys) {
  auto& p = sys.particles;
  const double dx = sys.spacing();
  const double reach = prm_.max_distance * dx;
  const double k = prm_.stiffness_factor * c_ / sys.delta;
  y_.resize(p.size());
  for (Index i = 0; i < p.size(); ++i) y_[i] = p.position(i);
  cells_.build(y_, reach);
  std::int64_t pairs = 0;
#pragma omp parallel for schedule(static) reduction(+ : pairs)
  for (Index i = 0; i < p.n_real; ++i) {
    Vec<D> fi = Vec<D>::Zero();
    cells_.for_each_near(y_[i], [&](Index j) {
      if (j == i) return;
      const Vec<D> d = y_[j] - y_[i];
      const double l = d.norm();
      if (l >= reach || l == 0.0) return;
      const double dij = std::min(prm_.distance_factor * (p.x0[j] - p.x0[i]).norm(), reach);
      if (l >= dij || (!prm_.bonded_pairs && bonded(sys, i, j))) return;
      fi += (k * (l - dij) * p.volume[j] / l) * d;
      ++pairs;
    });
    p.f[i] += fi;
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
  return neighbours * vmax * prm_.stiffness_factor * c_ / sys.delta;
}

template class ShortRangeContact<1>;
template class ShortRangeContact<2>;
template class ShortRangeContact<3>;

}  // namespace pdmpm::pd
