#include "solver/pd/lps.hpp"

#include <cmath>

#include "solver/pd/weighted_volume.hpp"

namespace pdmpm::pd {

template <int D>
void Lps<D>::initialise(const System<D>& sys) {
  k_ = lps_coefficients(sys.setting, sys.material);
  if (sys.continuum_weighted_volume)
    m_.assign(sys.particles.size(), lps_weighted_volume(sys.influence, sys.setting, sys.delta, sys.measure));
  else
    m_ = reference_weighted_volumes(sys);
  const auto n = m_.size();
  theta_.assign(n, 0.0);
  inv_m_.resize(n);
  alpha_beta_.assign(2 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) set_weighted_volume(i, m_[i]);
}

template <int D>
void Lps<D>::set_weighted_volume(std::size_t i, double m) {
  m_[i] = m;
  inv_m_[i] = m > 0.0 ? 1.0 / m : 0.0;  // a particle without bonds feels no force
  alpha_beta_[2 * i + 1] = k_.B * inv_m_[i];
}

template <int D>
void Lps<D>::refresh(const System<D>& sys, const std::vector<Index>& changed) {
  // The continuum weighted volume does not depend on which bonds are live.
  if (sys.continuum_weighted_volume) return;
  const auto& p = sys.particles;
  for (Index i : changed) set_weighted_volume(i, pd::weighted_volume(sys, i, BondSet::reference));
  p.fill_ghosts(m_);
  for (Index g = 0; g < p.n_ghost(); ++g) set_weighted_volume(p.n_real + g, m_[p.n_real + g]);
}

template <int D>
std::int64_t Lps<D>::compute_forces(System<D>& sys, const ForceRequest& req) {
  auto& p = sys.particles;
  const Index n = p.n_real;
  if (req.energy) req.energy->resize(n);
  kernels::LpsArgs a;
  a.fam = sys.family_view();
  a.table = sys.table.view();
  a.u = p.u.data()->data();
  a.volume = p.volume.data();
  a.uniform_volume = sys.uniform_volume();
  a.m = m_.data();
  a.theta = theta_.data();
  a.alpha_beta = alpha_beta_.data();
  a.f = p.f.data()->data();
  a.energy = req.energy ? req.energy->data() : nullptr;
  a.A = k_.A;
  a.B = k_.B;
  a.kappa = k_.kappa;
  a.gamma = k_.gamma;
  a.d = k_.d;
  a.breaking = req.break_bonds;
  a.s0 = req.critical_stretch;
  a.after_force = req.break_after_force;
  // Pass 1: break bonds, dilatation over the intact ones; ghosts take their owner's.
  std::int64_t newly = kernels::lps_dilatation<D>(a);
  p.fill_ghosts(theta_);
  for (Index i = 0; i < p.size(); ++i) alpha_beta_[2 * i] = k_.A * theta_[i] * inv_m_[i];
  // Pass 2: pair forces.
  newly += kernels::lps_forces<D>(a);
  return newly;
}

template <int D>
void Lps<D>::dilatation(const System<D>& sys, std::vector<double>& theta) const {
  dilatations(sys, m_, theta);
}

template <int D>
double Lps<D>::stiffness_row_sum(const System<D>& sys, Index i) const {
  // Bond stiffness per unit extension: the direct term B ω β (1/m_i + 1/m_j)
  // plus a bound on the dilatation coupling, d|A| ω β (1/m_i + 1/m_j).
  const double coef = k_.B + k_.d * std::abs(k_.A);
  double sum = 0.0;
  sys.for_each_live_bond(i, [&](BondIndex, Index j, int k) {
    const double inv = (m_[i] > 0 ? 1.0 / m_[i] : 0.0) + (m_[j] > 0 ? 1.0 / m_[j] : 0.0);
    sum += coef * inv * sys.table.weight[k] * sys.particles.volume[j];
  });
  return sum;
}

// m follows the particle kinds in a hybrid run; θ and Aθ/m are the last evaluation's.
template <int D>
void Lps<D>::checkpoint(core::StateArchive& a) {
  a.sync("lps/weighted_volume", m_);
  a.sync("lps/inverse_weighted_volume", inv_m_);
  a.sync("lps/dilatation", theta_);
  a.sync("lps/alpha_beta", alpha_beta_);
}

template class Lps<1>;
template class Lps<2>;
template class Lps<3>;

}  // namespace pdmpm::pd
