#include "solver/pd/lps_plastic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "solver/pd/bond_kinematics.hpp"
#include "solver/pd/weighted_volume.hpp"

namespace pdmpm::pd {

template <int D>
void LpsPlastic<D>::initialise(const System<D>& sys) {
  if (sys.setting != core::Setting::solid3d)
    throw std::invalid_argument("lps_plastic is implemented in 3d only (got '" + std::string(pdmpm::name(sys.setting)) + "')");
  if (sys.particles.n_ghost() > 0)
    throw std::invalid_argument("lps_plastic does not support ghost particles (symmetry planes) yet");
  k_ = lps_coefficients(sys.setting, sys.material);
  hardening_ = sys.hardening;
  three_g_ = k_.B / 5.0;  // 3D: B = 15G
  plastic_modulus_ = hardening_ ? hardening_->hardening_modulus(sys.material.E) : 0.0;
  const Index n = sys.particles.n_real;
  m_ = reference_weighted_volumes(sys);
  m_.resize(n);
  inv_m_.resize(n);
  for (Index i = 0; i < n; ++i) inv_m_[i] = m_[i] > 0.0 ? 1.0 / m_[i] : 0.0;
  theta_.assign(n, 0.0);
  sigma_eq_.assign(n, 0.0);
  dissipation_.assign(n, 0.0);
  // Families are in stencil order, so the reverse bond (offset −ξ) is found by bisection.
  const auto& f = sys.families;
  const auto& st = f.stencil;
  std::vector<std::uint16_t> opposite(st.size());
  for (int k = 0; k < st.size(); ++k)
    for (int q = 0; q < st.size(); ++q)
      if (st.offset[q] == -st.offset[k]) opposite[k] = static_cast<std::uint16_t>(q);
  reverse_.assign(f.n_bonds(), 0);
  for (Index i = 0; i < n; ++i)
    for (BondIndex b = f.begin(i); b < f.end(i); ++b) {
      const Index j = f.neighbor[b];
      const auto first = f.shape.begin() + f.begin(j), last = f.shape.begin() + f.end(j);
      reverse_[b] = static_cast<BondIndex>(std::lower_bound(first, last, opposite[f.shape[b]]) - f.shape.begin());
    }
  plastic_ext_.assign(f.n_bonds(), 0.0);
  eq_plastic_.assign(n, 0.0);
  plastic_work_ = plastic_work_trial_ = 0.0;
}

template <int D>
void LpsPlastic<D>::refresh(const System<D>& sys, const std::vector<Index>& changed) {
  for (Index i : changed) {
    m_[i] = pd::weighted_volume(sys, i, BondSet::reference);
    inv_m_[i] = m_[i] > 0.0 ? 1.0 / m_[i] : 0.0;
  }
}

// Radial return of particle i's deviatoric force state (reads the committed
// state, writes the trial one).
template <int D>
void LpsPlastic<D>::return_map(const System<D>& sys, Index i) {
  const auto& p = sys.particles;
  const auto& t = sys.table;
  const double gamma = k_.gamma, theta = theta_[i];
  double norm2 = 0.0;  // Σ ω β V ε²
  sys.for_each_live_bond(i, [&](BondIndex b, Index j, int k) {
    const double e = deform<D>(t.xi[k], t.length[k], p.u[j] - p.u[i]).e;
    const double eps = e - gamma * theta * t.length[k] - plastic_ext_.committed[b];
    norm2 += t.weight[k] * p.volume[j] * eps * eps;
  });
  const double q = k_.B * inv_m_[i];
  const double trial = q * std::sqrt(m_[i] / 5.0 * norm2);  // σ̄ of the trial state
  const double ep_n = eq_plastic_.committed[i];
  const double radius = hardening_ ? hardening_->yield_stress + plastic_modulus_ * ep_n
                                   : std::numeric_limits<double>::infinity();
  double r = 1.0, dep = 0.0;
  if (trial > radius) {
    dep = (trial - radius) / (three_g_ + plastic_modulus_);
    r = 1.0 - three_g_ * dep / trial;
  }
  sigma_eq_[i] = r * trial;
  eq_plastic_.trial[i] = ep_n + dep;
  dissipation_[i] = p.volume[i] * sigma_eq_[i] * dep;
  // p ← p + (1 − r) ε on every live bond; broken and inactive bonds keep theirs.
  for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b) plastic_ext_.trial[b] = plastic_ext_.committed[b];
  if (r == 1.0) return;
  sys.for_each_live_bond(i, [&](BondIndex b, Index j, int k) {
    const double e = deform<D>(t.xi[k], t.length[k], p.u[j] - p.u[i]).e;
    const double eps = e - gamma * theta * t.length[k] - plastic_ext_.committed[b];
    plastic_ext_.trial[b] = plastic_ext_.committed[b] + (1.0 - r) * eps;
  });
}

template <int D>
std::int64_t LpsPlastic<D>::compute_forces(System<D>& sys, const ForceRequest& req) {
  auto& p = sys.particles;
  const Index n = p.n_real;
  const auto& t = sys.table;
  if (req.energy) req.energy->resize(n);
  // Pass 1: break bonds (before-force rule), dilatation over the intact ones — LPS's kernel.
  std::vector<double> theta_all(p.size(), 0.0);
  kernels::LpsArgs a;
  a.fam = sys.family_view();
  a.table = t.view();
  a.u = p.u.data()->data();
  a.volume = p.volume.data();
  a.uniform_volume = sys.uniform_volume();
  a.m = m_.data();
  a.theta = theta_all.data();
  a.d = k_.d;
  a.breaking = req.break_bonds;
  a.s0 = req.critical_stretch;
  a.after_force = req.break_after_force;
  std::int64_t newly = kernels::lps_dilatation<D>(a);
  std::copy(theta_all.begin(), theta_all.begin() + n, theta_.begin());

  // Pass 2: the return mapping of every owner.
  const Index n_owners = a.fam.n_owners;
#pragma omp parallel for schedule(static)
  for (Index k = 0; k < n_owners; ++k) return_map(sys, a.fam.particle(k));

  // Pass 3: pair forces (t_ij + t_ji) β V_j y/|y|.
  const double A = k_.A, B = k_.B, gamma = k_.gamma, kappa = k_.kappa;
  std::int64_t broken_after = 0;
#pragma omp parallel for schedule(static) reduction(+ : broken_after)
  for (Index k = 0; k < n_owners; ++k) {
    const Index i = a.fam.particle(k);
    Vec<D> f = Vec<D>::Zero();
    double dev = 0.0;
    sys.for_each_live_bond(i, [&](BondIndex b, Index j, int s) {
      const auto g = deform<D>(t.xi[s], t.length[s], p.u[j] - p.u[i]);
      const double L = t.length[s];
      const double tij = (A * theta_[i] * L + B * (g.e - plastic_ext_.trial[b])) * inv_m_[i];
      const double tji = (A * theta_[j] * L + B * (g.e - plastic_ext_.trial[reverse_[b]])) * inv_m_[j];
      f += t.weight[s] * p.volume[j] * (tij + tji) / g.l * g.y;
      if (req.energy) {
        const double eps = g.e - gamma * theta_[i] * L - plastic_ext_.trial[b];
        dev += t.weight[s] * p.volume[j] * eps * eps;
      }
    });
    p.f[i] = f;
    if (req.energy) (*req.energy)[i] = 0.5 * kappa * theta_[i] * theta_[i] + 0.5 * B * inv_m_[i] * dev;
    // Break-after-force rule (LAMMPS): i's side only, whose flags nobody else reads in this pass.
    if (req.break_bonds && req.break_after_force)
      for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b) {
        if (!sys.bonds.live(b)) continue;
        const int s = sys.families.shape[b];
        const auto g = deform<D>(t.xi[s], t.length[s], p.u[sys.families.neighbor[b]] - p.u[i]);
        if (g.e > req.critical_stretch * t.length[s]) {
          sys.bonds.flags.trial[b] |= kBondBroken;
          ++broken_after;
        }
      }
  }
  newly += broken_after;
  double work = 0.0;
  for (Index i = 0; i < n; ++i) work += dissipation_[i];
  plastic_work_trial_ = plastic_work_ + work;
  return newly;
}

template <int D>
void LpsPlastic<D>::accept() {
  plastic_ext_.accept();
  eq_plastic_.accept();
  plastic_work_ = plastic_work_trial_;
}

template <int D>
void LpsPlastic<D>::reject() {
  plastic_ext_.reject();
  eq_plastic_.reject();
  plastic_work_trial_ = plastic_work_;
}

template <int D>
void LpsPlastic<D>::dilatation(const System<D>& sys, std::vector<double>& theta) const {
  theta.assign(sys.particles.n_real, 0.0);
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < sys.particles.n_real; ++i) theta[i] = dilatation_of(sys, i, m_[i]);
}

template <int D>
double LpsPlastic<D>::stiffness_row_sum(const System<D>& sys, Index i) const {
  // The elastic LPS bound (plastic flow only softens the bonds).
  const double coef = k_.B + k_.d * std::abs(k_.A);
  double sum = 0.0;
  sys.for_each_live_bond(i, [&](BondIndex, Index j, int k) {
    sum += coef * (inv_m_[i] + inv_m_[j]) * sys.table.weight[k] * sys.particles.volume[j];
  });
  return sum;
}

template <int D>
Mat<D> LpsPlastic<D>::force_state_stress(const System<D>& sys, Index i) const {
  const auto& p = sys.particles;
  const auto& t = sys.table;
  Mat<D> s = Mat<D>::Zero();
  sys.for_each_live_bond(i, [&](BondIndex b, Index j, int k) {
    const auto g = deform<D>(t.xi[k], t.length[k], p.u[j] - p.u[i]);
    const double tij = (k_.A * theta_[i] * t.length[k] + k_.B * (g.e - plastic_ext_.trial[b])) * inv_m_[i];
    s += t.weight[k] * p.volume[j] * tij / g.l * (g.y * t.xi[k].transpose());
  });
  return s;
}

template class LpsPlastic<1>;
template class LpsPlastic<2>;
template class LpsPlastic<3>;

}  // namespace pdmpm::pd
