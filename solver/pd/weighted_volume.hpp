#pragma once
// Discrete weighted volume m_i = Σ_j ω β |ξ|² V_j (docs/models/lps.md)
// and the dilatation θ_i = (d/m_i) Σ_j ω β |ξ| e V_j (over the bonds of i's state).
#include <vector>

#include "solver/pd/bond_kinematics.hpp"
#include "solver/pd/system.hpp"

namespace pdmpm::pd {

// Over the live bonds (the current family), or over the reference family, in
// which bonds broken during the run still count: LPS's m stays what it was at
// the start however particle kinds change.
template <int D>
double weighted_volume(const System<D>& sys, Index i, BondSet set = BondSet::live) {
  const auto& t = sys.table;
  double m = 0.0;
  sys.for_each_bond(i, set, [&](BondIndex, Index j, int k) {
    m += t.weight[k] * t.length[k] * t.length[k] * sys.particles.volume[j];
  });
  return m;
}

// Reference weighted volume of every particle, ghosts copying their owner's.
template <int D>
std::vector<double> reference_weighted_volumes(const System<D>& sys) {
  const auto& p = sys.particles;
  std::vector<double> m(p.size(), 0.0);
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < p.n_real; ++i) m[i] = weighted_volume(sys, i, BondSet::reference);
  p.fill_ghosts(m);
  return m;
}

// With `shape_weight` (a factor per stencil offset, lps_plastic's isotropy weights c) the
// dilatation in those weights, m_i then being theirs too (θ_c of docs/models/lps_plastic.md).
template <int D>
double dilatation_of(const System<D>& sys, Index i, double m_i, const double* shape_weight = nullptr) {
  if (m_i <= 0.0) return 0.0;
  const auto& t = sys.table;
  const auto& p = sys.particles;
  double sum = 0.0;
  sys.for_each_bond(i, BondSet::state, [&](BondIndex, Index j, int k) {
    const auto bond = deform<D>(t.xi[k], t.length[k], p.u[j] - p.u[i]);
    const double w = shape_weight ? shape_weight[k] * t.weight[k] : t.weight[k];
    sum += w * t.length[k] * bond.e * p.volume[j];
  });
  return D * sum / m_i;
}

// θ of every real particle given its weighted volume m (indexed like the particles).
template <int D>
void dilatations(const System<D>& sys, const std::vector<double>& m, std::vector<double>& theta) {
  theta.assign(sys.particles.n_real, 0.0);
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < sys.particles.n_real; ++i) theta[i] = dilatation_of(sys, i, m[i]);
}

}  // namespace pdmpm::pd
