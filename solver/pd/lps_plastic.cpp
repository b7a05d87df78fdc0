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
  if (sys.setting != core::Setting::solid3d && sys.setting != core::Setting::bar1d)
    throw std::invalid_argument("lps_plastic is implemented for 3d and 1d only (got '" +
                                std::string(pdmpm::name(sys.setting)) + "')");
  if (sys.particles.n_ghost() > 0)
    throw std::invalid_argument("lps_plastic does not support ghost particles (symmetry planes) yet");
  k_ = lps_coefficients(sys.setting, sys.material);
  hardening_ = sys.hardening;
  // ζ in ‖t^d‖²_ω = ζ σ̄²/m_d: 5 in 3D (fourth moment 2/15), 1 in a bar; the return's
  // stiffness is B/ζ = 3G (3D: B = 15G) or E (bar: B = E).
  zeta_ = sys.setting == core::Setting::bar1d ? 1.0 : 5.0;
  three_g_ = k_.B / zeta_;
  plastic_modulus_ = hardening_ ? hardening_->hardening_modulus(sys.material.E) : 0.0;
  const Index n = sys.particles.n_real;
  shell_ = isotropy_weights(sys);
  m_ = reference_weighted_volumes(sys);
  m_.resize(n);
  inv_m_.resize(n);
  inv_md_.resize(n);
  for (Index i = 0; i < n; ++i) set_weighted_volumes(sys, i);
  theta_.assign(n, 0.0);
  theta_c_.assign(n, 0.0);
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
  trial_eps_.assign(f.n_bonds(), 0.0);
  scale_.assign(n, 1.0);
  eq_plastic_.assign(n, 0.0);
  plastic_work_ = plastic_work_trial_ = 0.0;
}

template <int D>
void LpsPlastic<D>::refresh(const System<D>& sys, const std::vector<Index>& changed) {
  for (Index i : changed) {
    m_[i] = pd::weighted_volume(sys, i, BondSet::reference);
    set_weighted_volumes(sys, i);
  }
}

template <int D>
void LpsPlastic<D>::set_weighted_volumes(const System<D>& sys, Index i) {
  double md = 0.0;
  sys.for_each_bond(i, BondSet::reference, [&](BondIndex, Index j, int k) {
    md += sys.table.weight[k] * shell_[k] * sys.table.length[k] * sys.table.length[k] * sys.particles.volume[j];
  });
  inv_m_[i] = m_[i] > 0.0 ? 1.0 / m_[i] : 0.0;  // a particle without bonds feels no force
  inv_md_[i] = md > 0.0 ? 1.0 / md : 0.0;
}

// c per stencil offset: 1, or 1 + κ g(n) with κ solving a(κ) = 3 b(κ) for the full
// stencil, a = Σ w r² c n_x⁴ and b = Σ w r² c n_x² n_y² (w = ωβ; isotropy of a cubic
// fourth-order tensor: a = 3b). Linear in κ: κ = (3 B_xy − A_x) / (A_xg − 3 B_xyg).
template <int D>
std::vector<double> LpsPlastic<D>::isotropy_weights(const System<D>& sys) {
  const auto& t = sys.table;
  const int n_shapes = sys.families.stencil.size();
  std::vector<double> c(n_shapes, 1.0);
  if constexpr (D != 3) return c;  // 3D only (initialise refuses the others)
  if (!sys.isotropic_deviatoric) return c;
  std::vector<double> g(n_shapes);
  double ax = 0.0, axg = 0.0, bxy = 0.0, bxyg = 0.0;
  for (int k = 0; k < n_shapes; ++k) {
    const Vec<D> nk = t.xi[k] / t.length[k];
    g[k] = nk.array().pow(4).sum() - 0.6;
    const double w = t.weight[k] * t.length[k] * t.length[k];
    const double x4 = std::pow(nk[0], 4), x2y2 = nk[0] * nk[0] * nk[1] * nk[1];
    ax += w * x4, axg += w * x4 * g[k], bxy += w * x2y2, bxyg += w * x2y2 * g[k];
  }
  const double kappa = (3.0 * bxy - ax) / (axg - 3.0 * bxyg);
  for (int k = 0; k < n_shapes; ++k) c[k] = 1.0 + kappa * g[k];
  if (*std::min_element(c.begin(), c.end()) <= 0.0)
    throw std::invalid_argument("lps_plastic: the isotropy correction would make a bond weight ≤ 0 for this stencil");
  return c;
}

// Radial return of particle i's deviatoric force state (reads the committed
// state, writes the trial one).
template <int D>
void LpsPlastic<D>::return_map(const System<D>& sys, Index i) {
  const auto& p = sys.particles;
  const auto& t = sys.table;
  // θ_c = (d/m_d) Σ ωβcV|ξ|e: the dilatation measured with the deviatoric weights, so that
  // Σ ωβcV|ξ| ε = 0 and the force is the gradient of W (with c ≡ 1 it is LPS's θ).
  double moment = 0.0;
  sys.for_each_live_bond(i, [&](BondIndex b, Index j, int k) {
    const double e = deform<D>(t.xi[k], t.length[k], p.u[j] - p.u[i]).e;
    trial_eps_[b] = e;
    moment += t.weight[k] * shell_[k] * p.volume[j] * t.length[k] * e;
  });
  theta_c_[i] = k_.d * moment * inv_md_[i];
  const double gamma_theta = k_.gamma * theta_c_[i];
  double norm2 = 0.0;  // Σ ω β c V ε²
  sys.for_each_live_bond(i, [&](BondIndex b, Index j, int k) {
    const double eps = trial_eps_[b] - gamma_theta * t.length[k] - plastic_ext_.committed[b];
    trial_eps_[b] = eps;
    norm2 += t.weight[k] * shell_[k] * p.volume[j] * eps * eps;
  });
  const double trial = k_.B * std::sqrt(inv_md_[i] / zeta_ * norm2);  // σ̄ = (B/m_d) √(m_d/ζ · Σ ωβcV ε²)
  const double ep_n = eq_plastic_.committed[i];
  const double radius =
      hardening_ ? hardening_->yield_stress + plastic_modulus_ * ep_n : std::numeric_limits<double>::infinity();
  double r = 1.0, dep = 0.0;
  if (trial > radius) {
    dep = (trial - radius) / (three_g_ + plastic_modulus_);
    r = 1.0 - three_g_ * dep / trial;
  }
  scale_[i] = r;
  sigma_eq_[i] = r * trial;
  eq_plastic_.trial[i] = ep_n + dep;
  dissipation_[i] = p.volume[i] * sigma_eq_[i] * dep;
  // p ← p + (1 − r) ε on every live bond; broken and inactive bonds keep theirs.
  for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b)
    plastic_ext_.trial[b] = plastic_ext_.committed[b];
  if (r == 1.0) return;
  sys.for_each_live_bond(i, [&](BondIndex b, Index, int) {
    plastic_ext_.trial[b] = plastic_ext_.committed[b] + (1.0 - r) * trial_eps_[b];
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
  const double B = k_.B, kappa = k_.kappa, three_k = 3.0 * k_.kappa;
  std::int64_t broken_after = 0;
#pragma omp parallel for schedule(static) reduction(+ : broken_after)
  for (Index k = 0; k < n_owners; ++k) {
    const Index i = a.fam.particle(k);
    Vec<D> f = Vec<D>::Zero();
    double dev = 0.0;
    sys.for_each_live_bond(i, [&](BondIndex b, Index j, int s) {
      const auto g = deform<D>(t.xi[s], t.length[s], p.u[j] - p.u[i]);
      const double L = t.length[s];
      // The elastic deviatoric part after the return is r ε_trial (both sides live together).
      const double eps_i = scale_[i] * trial_eps_[b], eps_j = scale_[j] * trial_eps_[reverse_[b]];
      const double tij = three_k * theta_[i] * L * inv_m_[i] + shell_[s] * B * eps_i * inv_md_[i];
      const double tji = three_k * theta_[j] * L * inv_m_[j] + shell_[s] * B * eps_j * inv_md_[j];
      f += t.weight[s] * p.volume[j] * (tij + tji) / g.l * g.y;
      if (req.energy) dev += t.weight[s] * shell_[s] * p.volume[j] * eps_i * eps_i;
    });
    p.f[i] = f;
    if (req.energy) (*req.energy)[i] = 0.5 * kappa * theta_[i] * theta_[i] + 0.5 * B * inv_md_[i] * dev;
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
  dilatations(sys, m_, theta);
}

template <int D>
double LpsPlastic<D>::stiffness_row_sum(const System<D>& sys, Index i) const {
  // The elastic bound (plastic flow only softens the bonds): the direct term B c ω β (1/m_d,i + 1/m_d,j),
  // the coupling through θ_c, d γ B c ω β (1/m_d,i + 1/m_d,j), and through θ, d 3K ω β (1/m_i + 1/m_j).
  const double threeK = 3.0 * k_.kappa;
  double sum = 0.0;
  sys.for_each_live_bond(i, [&](BondIndex, Index j, int k) {
    const double c = shell_[k];
    sum += (k_.B * c * (1.0 + k_.d * k_.gamma) * (inv_md_[i] + inv_md_[j]) + k_.d * threeK * (inv_m_[i] + inv_m_[j])) *
        sys.table.weight[k] * sys.particles.volume[j];
  });
  return sum;
}

// t_ij / (ωβ): 3K θ_i |ξ| / m_i + c B (e − θ_c,i|ξ|/3 − p_ij) / m_d,i, with p from the trial state.
template <int D>
double LpsPlastic<D>::scalar_force_state(Index i, BondIndex b, int k, double e, double L) const {
  return 3.0 * k_.kappa * theta_[i] * L * inv_m_[i] +
      shell_[k] * k_.B * (e - k_.gamma * theta_c_[i] * L - plastic_ext_.trial[b]) * inv_md_[i];
}

template <int D>
Mat<D> LpsPlastic<D>::force_state_stress(const System<D>& sys, Index i) const {
  const auto& p = sys.particles;
  const auto& t = sys.table;
  Mat<D> s = Mat<D>::Zero();
  sys.for_each_live_bond(i, [&](BondIndex b, Index j, int k) {
    const auto g = deform<D>(t.xi[k], t.length[k], p.u[j] - p.u[i]);
    const double tij = scalar_force_state(i, b, k, g.e, t.length[k]);
    s += t.weight[k] * p.volume[j] * tij / g.l * (g.y * t.xi[k].transpose());
  });
  return s;
}

template class LpsPlastic<1>;
template class LpsPlastic<2>;
template class LpsPlastic<3>;

}  // namespace pdmpm::pd
