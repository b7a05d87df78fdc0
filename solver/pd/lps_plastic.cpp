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
  // Remote ghosts (a distributed run's halo) carry their owners' state; mirror ghosts
  // (symmetry planes) would need the reverse bonds of families no process holds.
  const auto& ghosts = sys.particles.ghost_owner;
  if (std::any_of(ghosts.begin(), ghosts.end(), [](Index o) { return o != core::Particles<D>::kRemoteOwner; }))
    throw std::invalid_argument("lps_plastic does not support ghost particles (symmetry planes) yet");
  remote_ = sys.particles.remote;
  setting_ = sys.setting;
  k_ = lps_coefficients(sys.setting, sys.material);
  bulk_ = sys.material.bulk();
  shear_ = sys.material.shear();
  hardening_ = sys.hardening;
  // ζ in ‖t^d‖²_ω = ζ σ̄²/m_d for an in-plane or 3D deviator: 5 in 3D (fourth moment 2/15),
  // 8/3 in 2D (fourth moment 1/8, B = 8G, σ̄² = 6G²·4/m Σ ωβV ε²), 1 in a bar; the return's
  // stiffness is B/ζ = 3G (2D, 3D) or E (bar: B = E).
  zeta_ = D == 1 ? 1.0 : D == 2 ? 8.0 / 3.0 : 5.0;
  three_g_ = k_.B / zeta_;
  plastic_modulus_ = hardening_ ? hardening_->hardening_modulus(sys.material.E) : 0.0;
  const Index n = sys.particles.n_real, all = sys.particles.size();
  shell_ = isotropy_weights(sys);
  shell_.resize(shell_.size() + kernels::lanes, 0.0);  // whole-block loads (kernels::per_offset)
  m_ = reference_weighted_volumes(sys);
  m_.resize(n);
  inv_m_.assign(all, 0.0);
  inv_md_.assign(all, 0.0);
  for (Index i = 0; i < n; ++i) set_weighted_volumes(sys, i);
  sys.particles.fill_ghosts(inv_m_);  // the stable step's row sums read the halo's
  sys.particles.fill_ghosts(inv_md_);
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
      if (j >= n) {  // a remote ghost: its side j→i is another process's (fill_reverse_sides)
        reverse_[b] = kRemoteSide;
        continue;
      }
      const auto first = f.shape.begin() + f.begin(j), last = f.shape.begin() + f.end(j);
      reverse_[b] = static_cast<BondIndex>(std::lower_bound(first, last, opposite[f.shape[b]]) - f.shape.begin());
    }
  plastic_ext_.assign(f.n_bonds() + kernels::lanes, 0.0);  // padded: the first pass loads p_n by blocks
  trial_flowed_.assign(n, 0);
  norm2_.assign(n, 0.0);
  reverse_plastic_.assign(f.n_bonds() + kernels::lanes, 0.0);
  offsets_.assign(f.offsets.begin(), f.offsets.begin() + n + 1);
  scale_.assign(n, 1.0);
  particle_rows_.assign(4 * static_cast<std::size_t>(all), 0.0);
  mean_term_.assign(n, 0.0);
  volumetric_energy_.assign(n, 0.0);
  axial_plastic_.assign(D == 2 ? n : 0, 0.0);
  axial_elastic_.assign(D == 2 ? n : 0, 0.0);
  out_of_plane_.assign(D == 2 ? n : 0, 0.0);
  eq_plastic_.assign(n, 0.0);
  ductile_damage_.assign(sys.ductile_failure.enabled ? n : 0, 0.0);
  failing_.assign(sys.ductile_failure.enabled ? all : 0, 0);
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
  sys.for_each_bond(i, BondSet::reference, [&](BondIndex, Index j, int k) { md += deviatoric_moment(sys, j, k); });
  inv_m_[i] = m_[i] > 0.0 ? 1.0 / m_[i] : 0.0;  // a particle without bonds feels no force
  inv_md_[i] = md > 0.0 ? 1.0 / md : 0.0;
}

// c per stencil offset: 1, or 1 + κ g(n) with κ solving a(κ) = 3 b(κ) for the full
// stencil, a = Σ w r² c n_x⁴ and b = Σ w r² c n_x² n_y² (w = ωβ; isotropy of a cubic or
// square fourth-order tensor: a = 3b). Linear in κ: κ = (3 B_xy − A_x) / (A_xg − 3 B_xyg).
// g = Σ_a n_a⁴ − its mean over directions (3/5 on the sphere, 3/4 on the circle).
template <int D>
std::vector<double> LpsPlastic<D>::isotropy_weights(const System<D>& sys) {
  const auto& t = sys.table;
  const int n_shapes = sys.families.stencil.size();
  std::vector<double> c(n_shapes, 1.0);
  if constexpr (D == 1) return c;
  if (!sys.isotropic_deviatoric) return c;
  std::vector<double> g(n_shapes);
  double ax = 0.0, axg = 0.0, bxy = 0.0, bxyg = 0.0;
  for (int k = 0; k < n_shapes; ++k) {
    const Vec<D> nk = t.xi[k] / t.length[k];
    g[k] = nk.array().pow(4).sum() - (D == 3 ? 0.6 : 0.75);
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
// state, writes the trial one), called by the first pass with eps[b − begin], the trial
// deviatoric extension ε = e − γθ_c|ξ| − p_n of each bond b of i's state, with
// θ_c = (d/m_d) Σ ωβcV|ξ|e the dilatation measured with the deviatoric weights (so
// that Σ ωβcV|ξ| ε = 0 and the force is the gradient of W; with c ≡ 1 it is LPS's θ),
// and norm2_[i] = Σ ωβcV ε².
template <int D>
void LpsPlastic<D>::return_map(const System<D>& sys, Index i, const double* eps) {
  const auto& p = sys.particles;
  const double norm2 = norm2_[i];
  const double ep_n = eq_plastic_.committed[i];
  const double radius =
      hardening_ ? hardening_->yield_stress + plastic_modulus_ * ep_n : std::numeric_limits<double>::infinity();
  const double live = sys.yield_on_live_bonds ? live_bond_ratio(sys, i) : 1.0;
  // sigma: σ̄ after the return as the yield reads it; on_family: the same over the reference
  // family (they differ only for a damaged particle with damaged_yield = "live_bonds").
  double r = 1.0, dep = 0.0, sigma = 0.0, on_family = 0.0;
  if constexpr (D == 2) {
    double x = 0.0;  // the elastic deviator after the return is the trial one over 1 + x
    sigma = planar_return(i, norm2, radius, live, x, on_family);
    r = 1.0 / (1.0 + x);
    dep = x * sigma / three_g_;
  } else {
    // σ̄ = (B/m_d) √(m_d/ζ · Σ ωβcV ε²), read on the live bonds (× √(m_d/m_d,live)) if asked
    const double family_trial = k_.B * std::sqrt(inv_md_[i] / zeta_ * norm2);
    const double trial = std::sqrt(live) * family_trial;
    if (trial > radius) {
      dep = (trial - radius) / (three_g_ + plastic_modulus_);
      r = 1.0 - three_g_ * dep / trial;
    }
    sigma = r * trial;
    on_family = r * family_trial;
    mean_term_[i] = k_.d * k_.kappa * theta_[i];  // 3Kθ (bar: κ = 0)
    volumetric_energy_[i] = 0.5 * k_.kappa * theta_[i] * theta_[i];
  }
  scale_[i] = r;
  // A hybrid's blended coupling weights the particle's force state, energy and dissipation
  // by its β (hybrid/blend_zone.hpp); its plastic state is the unweighted one's.
  const double w = sys.blend_weight.empty() ? 1.0 : sys.blend_weight[i];
  volumetric_energy_[i] *= w;
  particle_rows_[4 * i] = w * mean_term_[i] * inv_m_[i];
  particle_rows_[4 * i + 1] = w * r * k_.B * inv_md_[i];
  particle_rows_[4 * i + 2] = k_.gamma * theta_c_[i];
  sigma_eq_[i] = sigma;
  eq_plastic_.trial[i] = ep_n + dep;
  // The work the return dissipates, Σ t Δp βV: σ̄ Δε̄_p, or σ̄_family² Δε̄_p/σ̄ when the yield
  // reads the live bonds (the forces stay the reference family's).
  dissipation_[i] =
      w * p.volume[i] * (live == 1.0 ? sigma_eq_[i] * dep : (sigma > 0.0 ? on_family * on_family * dep / sigma : 0.0));
  // p ← p + (1 − r) ε on every bond of the state; broken and inactive bonds keep theirs. A particle
  // that does not flow keeps p_n, copied back only if an earlier trial changed it.
  if (r == 1.0 && !trial_flowed_[i]) return;
  trial_flowed_[i] = r != 1.0;
  const double flow = 1.0 - r;
  const BondIndex begin = sys.families.begin(i);
  for (BondIndex b = begin; b < sys.families.end(i); ++b)
    plastic_ext_.trial[b] = flow != 0.0 && sys.bonds.in_state(b) ? plastic_ext_.committed[b] + flow * eps[b - begin]
                                                                 : plastic_ext_.committed[b];
}

// m_d/m_d,live of particle i: the reference family's deviatoric weighted volume over its
// state bonds' (1 for a particle with every bond; 1 when none is left, no force either).
template <int D>
double LpsPlastic<D>::live_bond_ratio(const System<D>& sys, Index i) const {
  // Most particles have every bond: look at the flags first (summing the moments of every
  // particle's family made pure SBPD's run 23 % dearer).
  bool intact = true;
  for (BondIndex b = sys.families.begin(i); b < sys.families.end(i) && intact; ++b)
    intact = !sys.bonds.in_reference_family(b) || sys.bonds.in_state(b);
  if (intact) return 1.0;
  double live = 0.0;
  sys.for_each_bond(i, BondSet::reference, [&](BondIndex b, Index j, int k) {
    if (sys.bonds.in_state(b)) live += deviatoric_moment(sys, j, k);
  });
  if (!(live > 0.0) || !(inv_md_[i] > 0.0)) return 1.0;
  return 1.0 / (inv_md_[i] * live);
}

// The 2D return (see the header): the in-plane deviator of the bonds, Σ ωβcV ε² = norm2,
// and the particle's axial deviator q_e = Q/(1 + x + a) return together; plane strain
// (a = 0) is radial, plane stress (a = 4G/3K, from σ_zz = 0) solves
// F(x) = σ̄(x)(1 − Hx/3G) − Y = 0 by Newton from x = 0 (F convex and decreasing, so the
// iterates rise monotonically to the root). Writes q_p, q_e, ε_zz and the mean term;
// returns σ̄ after the return. `live` (live_bond_ratio) scales the bonds' term as the yield
// reads it; on_family is σ̄ after the return read over the reference family.
template <int D>
double LpsPlastic<D>::planar_return(Index i, double norm2, double radius, double live, double& x, double& on_family) {
  const double G = shear_, K = bulk_, theta = theta_[i];
  const bool plane_stress = setting_ == core::Setting::plane_stress;
  const double family_dev2 = 4.0 * norm2 * inv_md_[i];  // ε₂ᵈ : ε₂ᵈ of the bonds
  const double dev2 = live * family_dev2;               // as the yield reads it (live_bond_ratio)
  const double a = plane_stress ? 4.0 * G / (3.0 * K) : 0.0;
  const double Q = (plane_stress ? 0.5 : 1.0 / 6.0) * theta - axial_plastic_.committed[i];
  const double six_g2 = 6.0 * G * G;
  auto equivalent = [&](double y) {
    return std::sqrt(six_g2 * (dev2 / ((1.0 + y) * (1.0 + y)) + 6.0 * Q * Q / ((1.0 + y + a) * (1.0 + y + a))));
  };
  x = 0.0;
  double sigma = equivalent(0.0);
  if (sigma > radius) {
    const double h = plastic_modulus_ / three_g_;
    if (a == 0.0) {  // radial: the 3D formula
      const double dep = (sigma - radius) / (three_g_ + plastic_modulus_);
      const double after = sigma - three_g_ * dep;
      x = sigma / after - 1.0;
      sigma = after;
    } else {
      for (int it = 0; it < 100; ++it) {
        const double F = sigma * (1.0 - h * x) - radius;
        const double b1 = 1.0 + x, b2 = 1.0 + x + a;
        const double slope = -six_g2 / sigma * (dev2 / (b1 * b1 * b1) + 6.0 * Q * Q / (b2 * b2 * b2));
        const double step = -F / (slope * (1.0 - h * x) - h * sigma);
        x += step;
        sigma = equivalent(x);
        if (std::abs(step) <= 1e-15 * (1.0 + x)) break;
      }
    }
  }
  on_family = live == 1.0
      ? sigma
      : std::sqrt(six_g2 * (family_dev2 / ((1.0 + x) * (1.0 + x)) + 6.0 * Q * Q / ((1.0 + x + a) * (1.0 + x + a))));
  const double qe = Q / (1.0 + x + a);
  axial_elastic_[i] = qe;
  axial_plastic_.trial[i] = axial_plastic_.committed[i] + x * qe;
  out_of_plane_[i] = plane_stress ? 4.0 * G * qe / K - theta : 0.0;  // σ_zz = K tr ε − 4G q_e = 0
  const double trace = theta + out_of_plane_[i];
  mean_term_[i] = 2.0 * (K * trace + 2.0 * G * qe);  // 2P, P = (σ_xx + σ_yy)/2
  volumetric_energy_[i] = 0.5 * K * trace * trace + 6.0 * G * qe * qe;
  return sigma;
}

template <int D>
std::int64_t LpsPlastic<D>::compute_forces(System<D>& sys, const ForceRequest& req) {
  auto& p = sys.particles;
  const Index n = p.n_real;
  const auto& t = sys.table;
  if (req.energy) req.energy->resize(n);
  // Pass 1: break bonds (before-force rule), θ and θ_c over the intact ones, then ε and
  // Σ ωβcV ε² per particle, and the particle's return mapping (r, μ, s and the trial
  // plastic state).
  kernels::LpsPlasticArgs a;  // (no ghosts: p.size() = n)
  a.lps.fam = sys.family_view();
  a.lps.table = t.view();
  a.lps.u = p.u.data()->data();
  a.lps.volume = p.volume.data();
  a.lps.uniform_volume = sys.uniform_volume();
  a.lps.m = m_.data();
  a.lps.theta = theta_.data();
  a.lps.d = k_.d;
  a.lps.breaking = req.break_bonds;
  a.lps.s0 = req.critical_stretch;
  a.lps.after_force = req.break_after_force;
  a.lps.f = p.f.data()->data();
  a.lps.energy = req.energy ? req.energy->data() : nullptr;
  a.shell = shell_.data();
  a.inv_md = inv_md_.data();
  a.theta_c = theta_c_.data();
  struct Context {
    LpsPlastic* model;
    const System<D>* sys;
  } context{this, &sys};
  a.model = &context;
  a.return_map = [](void* c, Index i, const double* eps) {
    const auto* ctx = static_cast<const Context*>(c);
    ctx->model->return_map(*ctx->sys, i, eps);
  };
  a.reverse_plastic = reverse_plastic_.data();
  a.plastic_extension = plastic_ext_.committed.data();
  a.norm2 = norm2_.data();
  a.lps.gamma = k_.gamma;
  a.particle_rows = particle_rows_.data();
  a.volumetric_energy = volumetric_energy_.data();
  a.scale = scale_.data();
  a.B = k_.B;
  std::int64_t newly = kernels::lps_plastic_extension<D>(a);
  if (remote_) remote_->fill(particle_rows_.data(), 4);  // the force pass reads the halo's rows

  // Pass 2: pair forces (t_ij + t_ji) β V_j y/|y|; the break-after-force rule.
  newly += kernels::lps_plastic_forces<D>(a);
  if (req.break_bonds && sys.ductile_failure.enabled) newly += fail_particles(sys);
  const auto [work] = p.template sum_in_order<1>([&](double* sum) {
    for (Index i = 0; i < n; ++i) sum[0] += dissipation_[i];
  });
  plastic_work_trial_ = plastic_work_ + work;
  return newly;
}

// The ductile criterion on every owner that has flowed (the state of this evaluation);
// the bonds of the particles that fail break on both sides, in index order.
template <int D>
std::int64_t LpsPlastic<D>::fail_particles(System<D>& sys) {
  const auto& rule = sys.ductile_failure;
  const auto fam = sys.family_view();
  const Index n_owners = fam.n_owners;
  std::int64_t any = 0;
#pragma omp parallel for schedule(static) reduction(+ : any)
  for (Index k = 0; k < n_owners; ++k) {
    const Index i = fam.particle(k);
    failing_[i] = 0;
    const double ep = eq_plastic_.trial[i];
    if (ep == 0.0) continue;
    const double eps_f = rule.d0 * std::exp(rule.c * triaxiality(own_stress(sys, i)));
    if (rule.rule == core::FailureRule::strain) {
      failing_[i] = ep >= eps_f;
    } else {
      ductile_damage_.trial[i] = ductile_damage_.committed[i] + (ep - eq_plastic_.committed[i]) / eps_f;
      failing_[i] = ductile_damage_.trial[i] >= 1.0;
    }
    any += failing_[i];
  }
  // A distributed run: which halo particles fail (their owners found it); a bond to one
  // breaks on this side here, on the other side there.
  const Index n = sys.particles.n_real;
  std::int64_t halo_failing = 0;
  if (remote_) {
    std::vector<double> fails(failing_.begin(), failing_.end());
    remote_->fill(fails.data(), 1);
    for (Index h = n; h < sys.particles.size(); ++h) {
      failing_[h] = fails[h] != 0.0;
      halo_failing += failing_[h];
    }
    any += halo_failing;
  }
  if (any == 0) return 0;
  std::int64_t broken = 0;
  auto& flags = sys.bonds.flags.trial;
  const auto cut = [&](BondIndex side) {
    if (!(flags[side] & kBondBroken)) {
      flags[side] |= kBondBroken;
      ++broken;
    }
  };
  for (Index k = 0; k < n_owners; ++k) {
    const Index i = fam.particle(k);
    if (!failing_[i] && halo_failing == 0) continue;
    for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b) {
      const Index j = sys.families.neighbor[b];
      if (failing_[i]) {
        cut(b);
        if (reverse_[b] != kRemoteSide) cut(reverse_[b]);
      } else if (j >= n && failing_[j]) {
        cut(b);
      }
    }
  }
  return broken;
}

// The trial p differs from the committed one only on the bonds of the particles whose
// trial flowed (return_map restores the others), so accept and reject copy those alone.
template <int D>
void LpsPlastic<D>::accept() {
  // The force pass's copy of each reverse bond's p follows the particles that flowed.
  const auto n = static_cast<Index>(trial_flowed_.size());
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i)
    if (trial_flowed_[i])
      for (BondIndex b = offsets_[i]; b < offsets_[i + 1]; ++b) {
        plastic_ext_.committed[b] = plastic_ext_.trial[b];
        if (reverse_[b] != kRemoteSide) reverse_plastic_[reverse_[b]] = plastic_ext_.committed[b];
      }
  std::fill(trial_flowed_.begin(), trial_flowed_.end(), 0);
  if (remote_) remote_->fill_reverse_sides(plastic_ext_.committed.data(), reverse_plastic_.data());
  eq_plastic_.accept();
  axial_plastic_.accept();
  ductile_damage_.accept();
  plastic_work_ = plastic_work_trial_;
}

template <int D>
void LpsPlastic<D>::reject() {
  const auto n = static_cast<Index>(trial_flowed_.size());
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i)
    if (trial_flowed_[i])
      std::copy(plastic_ext_.committed.begin() + offsets_[i], plastic_ext_.committed.begin() + offsets_[i + 1],
                plastic_ext_.trial.begin() + offsets_[i]);
  std::fill(trial_flowed_.begin(), trial_flowed_.end(), 0);
  eq_plastic_.reject();
  axial_plastic_.reject();
  ductile_damage_.reject();
  plastic_work_trial_ = plastic_work_;
}

template <int D>
void LpsPlastic<D>::dilatation(const System<D>& sys, std::vector<double>& theta) const {
  dilatations(sys, m_, theta);
}

template <int D>
std::pair<double, double> LpsPlastic<D>::current_dilatations(const System<D>& sys, Index i) const {
  const double md = inv_md_[i] > 0.0 ? 1.0 / inv_md_[i] : 0.0;
  return {dilatation_of(sys, i, m_[i]), dilatation_of(sys, i, md, shell_.data())};
}

template <int D>
double LpsPlastic<D>::axial_plastic_for(double theta, double q_e) const {
  if constexpr (D != 2) return 0.0;
  const bool plane_stress = setting_ == core::Setting::plane_stress;
  const double a = plane_stress ? 4.0 * shear_ / (3.0 * bulk_) : 0.0;
  return (plane_stress ? 0.5 : 1.0 / 6.0) * theta - q_e * (1.0 + a);
}

template <int D>
double LpsPlastic<D>::axial_elastic_for(double theta, double q_p) const {
  if constexpr (D != 2) return 0.0;
  const bool plane_stress = setting_ == core::Setting::plane_stress;
  const double a = plane_stress ? 4.0 * shear_ / (3.0 * bulk_) : 0.0;
  return ((plane_stress ? 0.5 : 1.0 / 6.0) * theta - q_p) / (1.0 + a);
}

template <int D>
double LpsPlastic<D>::volumetric_elastic_for(double theta, double q_e) const {
  return D == 2 && setting_ == core::Setting::plane_stress ? 4.0 * shear_ * q_e / bulk_ : theta;
}

template <int D>
double LpsPlastic<D>::stiffness_row_sum(const System<D>& sys, Index i) const {
  // The elastic bound (plastic flow only softens the bonds): the direct term B c ω β (1/m_d,i + 1/m_d,j),
  // the coupling through θ_c, d γ B c ω β (1/m_d,i + 1/m_d,j), and through θ, d·dκ ω β (1/m_i + 1/m_j)
  // (the mean term is dκθ elastically: 3Kθ in 3D, 2κ₂θ in 2D).
  const double threeK = k_.d * k_.kappa;
  double sum = 0.0;
  sys.for_each_live_bond(i, [&](BondIndex, Index j, int k) {
    const double c = shell_[k];
    sum += (k_.B * c * (1.0 + k_.d * k_.gamma) * (inv_md_[i] + inv_md_[j]) + k_.d * threeK * (inv_m_[i] + inv_m_[j])) *
        sys.table.weight[k] * sys.particles.volume[j];
  });
  return sum;
}

// t_ij / (ωβ): (mean term) |ξ| / m_i + c B (e − γθ_c,i|ξ| − p_ij) / m_d,i, with p from the trial state.
template <int D>
double LpsPlastic<D>::scalar_force_state(Index i, BondIndex b, int k, double e, double L) const {
  return mean_term_[i] * L * inv_m_[i] +
      shell_[k] * k_.B * (e - k_.gamma * theta_c_[i] * L - plastic_ext_.trial[b]) * inv_md_[i];
}

template <int D>
Mat<D> LpsPlastic<D>::force_state_stress(const System<D>& sys, Index i) const {
  const auto& p = sys.particles;
  const auto& t = sys.table;
  Mat<D> s = Mat<D>::Zero();
  sys.for_each_bond(i, BondSet::state, [&](BondIndex b, Index j, int k) {
    const auto g = deform<D>(t.xi[k], t.length[k], p.u[j] - p.u[i]);
    const double tij = scalar_force_state(i, b, k, g.e, t.length[k]);
    s += t.weight[k] * p.volume[j] * tij / g.l * (g.y * t.xi[k].transpose());
  });
  return s;
}

template <int D>
double LpsPlastic<D>::out_of_plane_stress(Index i) const {
  if (D != 2 || setting_ == core::Setting::plane_stress) return 0.0;
  return bulk_ * theta_[i] - 4.0 * shear_ * axial_elastic_[i];  // plane strain: K θ + 2G·(−2 q_e)
}

template <int D>
Tensor6 LpsPlastic<D>::own_stress(const System<D>& sys, Index i) const {
  const Mat<D> s = force_state_stress(sys, i);
  constexpr int row[6] = {0, 1, 2, 0, 1, 0}, col[6] = {0, 1, 2, 1, 2, 2};  // xx yy zz xy yz xz
  Tensor6 out{};
  for (int c = 0; c < 6; ++c)
    if (row[c] < D && col[c] < D) out[c] = 0.5 * (s(row[c], col[c]) + s(col[c], row[c]));
  if constexpr (D == 2) out[2] = out_of_plane_stress(i);
  return out;
}

// The committed plastic state, and the weighted volumes (they follow the particle kinds in a
// hybrid run); the last evaluation's values too, since fields written before the next
// evaluation read them.
template <int D>
void LpsPlastic<D>::checkpoint(core::StateArchive& a) {
  a.sync("lps_plastic/weighted_volume", m_);
  a.sync("lps_plastic/inverse_weighted_volume", inv_m_);
  a.sync("lps_plastic/dilatation", theta_);
  a.sync("lps_plastic/deviatoric_dilatation", theta_c_);
  a.sync("lps_plastic/inverse_deviatoric_weighted_volume", inv_md_);
  plastic_ext_.checkpoint(a, "lps_plastic/plastic_extension");
  eq_plastic_.checkpoint(a, "lps_plastic/eq_plastic_strain");
  a.sync("lps_plastic/dissipation", dissipation_);
  a.sync("lps_plastic/plastic_work", plastic_work_);
  a.sync("lps_plastic/plastic_work_trial", plastic_work_trial_);
  a.sync("lps_plastic/sigma_eq", sigma_eq_);
  a.sync("lps_plastic/trial_flowed", trial_flowed_);
  a.sync("lps_plastic/reverse_plastic_extension", reverse_plastic_);
  a.sync("lps_plastic/scale", scale_);
  a.sync("lps_plastic/mean_term", mean_term_);
  a.sync("lps_plastic/volumetric_energy", volumetric_energy_);
  axial_plastic_.checkpoint(a, "lps_plastic/axial_plastic");
  ductile_damage_.checkpoint(a, "lps_plastic/ductile_damage");
  a.sync("lps_plastic/failing", failing_);
  a.sync("lps_plastic/axial_elastic", axial_elastic_);
  a.sync("lps_plastic/out_of_plane_strain", out_of_plane_);
}

template class LpsPlastic<1>;
template class LpsPlastic<2>;
template class LpsPlastic<3>;

}  // namespace pdmpm::pd
