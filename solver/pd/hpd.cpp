#include "solver/pd/hpd.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>

#include "solver/core/error.hpp"
#include "solver/pd/bond_kinematics.hpp"
#include "solver/pd/constants.hpp"

namespace pdmpm::pd {

template <int D>
void Hpd<D>::initialise(const System<D>& sys) {
  law_ = sys.hpd.law;
  setting_ = sys.setting;
  min_points_ = sys.hpd.min_points(D);
  end_weight_ = sys.hpd.end_weight;
  const auto& m = sys.material;
  young_ = m.E;
  shear_ = m.shear();
  // Plane stress: σ_zz = 0 eliminates ε_zz, λ* = 2λG/(λ + 2G) = Eν/(1 − ν²).
  lambda_ = sys.setting == core::Setting::plane_stress ? m.E * m.nu / (1.0 - m.nu * m.nu) : m.lame();
  axial_modulus_ = sys.setting == core::Setting::plane_strain ? m.E / (1.0 - m.nu * m.nu) : m.E;
  if (law_ == HpdLaw::axial_1d) {
    c_ = pmb_micromodulus(sys.influence, sys.setting, sys.material, sys.delta, sys.measure);
    return;
  }
  if (const auto why = sub_horizon_shortfall(sys.families.stencil, min_points_); !why.empty())
    throw std::invalid_argument("hpd: " + why);
  if (law_ == HpdLaw::j2) {
    if (!sys.hardening)
      throw std::invalid_argument("hpd: constitutive = \"j2\" needs yield_stress and tangent_modulus");
    mpm::Material material;
    material.model = mpm::MaterialModel::j2;
    material.elastic = sys.material;
    material.j2 = *sys.hardening;
    j2_ = std::make_unique<mpm::Constitutive<D>>(material, sys.setting);
    history_.assign(sys.families.n_bonds(), mpm::PointHistory{});
    dissipation_.assign(sys.families.n_bonds(), 0.0);
    eq_plastic_.assign(sys.particles.n_real, 0.0);
    bond_cauchy_.assign(sys.families.n_bonds(), Mat<3>::Zero());
  }
  inv_m_.assign(sys.particles.n_real, 0.0);
  bond_weight_.assign(sys.families.n_bonds(), 0.0);
  for (Index i = 0; i < sys.particles.n_real; ++i) set_weighted_volume(sys, i);
  bond_p_.assign(sys.families.n_bonds(), Mat<D>::Zero());
  stabilization_ = sys.hpd.stabilization;
  residual_modulus_ = 2.0 * stabilization_ * shear_;
  remote_ = sys.particles.remote;
  sub_ = SubHorizon<D>::build(sys, min_points_, end_weight_, halo_bonds(sys));
  residual_force_.assign(stabilization_ > 0.0 ? sub_.at_bond.size() : 0, Vec<D>::Zero());
  if (remote_) {
    index_remote_slots(sys);
    exchange_stiffness_rows(sys);
  }
}

template <int D>
void Hpd<D>::refresh(const System<D>& sys, const std::vector<Index>& changed) {
  if (law_ == HpdLaw::axial_1d) return;
  for (Index i : changed) set_weighted_volume(sys, i);
  sub_ = SubHorizon<D>::build(sys, min_points_, end_weight_);  // the reference family changed
  residual_force_.assign(stabilization_ > 0.0 ? sub_.at_bond.size() : 0, Vec<D>::Zero());
}

template <int D>
void Hpd<D>::set_weighted_volume(const System<D>& sys, Index i) {
  double m = 0.0;  // Σ ω β |ξ| V_j over the reference family
  sys.for_each_bond(i, BondSet::reference, [&](BondIndex, Index j, int k) {
    m += sys.table.weight[k] * sys.table.length[k] * sys.particles.volume[j];
  });
  inv_m_[i] = m > 0.0 ? 1.0 / m : 0.0;  // a particle without bonds stores no energy
  const auto& t = sys.table;
  for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b) {
    const int k = sys.families.shape[b];
    bond_weight_[b] = sys.particles.volume[i] * t.weight[k] * t.length[k] *
        sys.particles.volume[sys.families.neighbor[b]] * inv_m_[i];
  }
}

template <int D>
double Hpd<D>::stiffness_row_sum(const System<D>& sys, Index i) const {
  const auto& t = sys.table;
  double sum = 0.0;
  if (law_ == HpdLaw::axial_1d) {
    sys.for_each_live_bond(
        i, [&](BondIndex, Index j, int k) { sum += c_ * t.weight[k] / t.length[k] * sys.particles.volume[j]; });
    return sum;
  }
  // Largest eigenvalue of C on symmetric tensors: dλ + 2G (volumetric) or 2G (deviatoric); a bar: E.
  const double hooke = D == 1 ? young_ : std::max(std::abs(D * lambda_ + 2.0 * shear_), 2.0 * shear_);
  const double modulus = std::max(hooke, axial_modulus_);
  double residual = 0.0;
  auto add = [&](double bond, double stabilising) { sum += bond, residual += stabilising; };
  for_each_remote_record(i, true, remote_rows_, 2, [&](const double* r) { add(r[0], r[1]); });
  for (BondIndex q = sub_.at_begin[i]; q < sub_.at_begin[i + 1]; ++q) {
    const auto [bond, stabilising] = slot_stiffness(sys, i, q);
    add(bond, stabilising);
  }
  for_each_remote_record(i, false, remote_rows_, 2, [&](const double* r) { add(r[0], r[1]); });
  return 0.5 * (modulus * sum + residual) / sys.particles.volume[i];
}

template <int D>
std::pair<double, double> Hpd<D>::slot_stiffness(const System<D>& sys, Index i, BondIndex q) const {
  const BondIndex b = sub_.at_bond[q];
  double row = 0.0;
  for (BondIndex l = sub_.begin[b]; l < sub_.begin[b + 1]; ++l) row += sub_.coef[l].norm();
  const double bond = bond_weight_[b] * sub_.at_coef[q].norm() * row;
  if (!(stabilization_ > 0.0)) return {bond, 0.0};
  // The stabilisation: ∂(G V_i r_i)/∂u_l = G V_i (δ_il − V_l/ΣV − V_l (x_l − x̄)·K̃⁻¹(x_i − x̄)) (times the
  // unit tensor; positions relative to the bond's owner).
  const Index owner = sub_.point[sub_.begin[b]];  // a side's first slot is its owner
  auto from_centroid = [&](Index k) -> Vec<D> {
    return sys.particles.x0[k] - sys.particles.x0[owner] - sub_.centroid[b];
  };
  const Vec<D> gi = sub_.volume_inverse[b] * from_centroid(i);
  double residual_row = 0.0, vi = 0.0;  // V_i: the volume in i's own slot (0 outside the residual)
  for (BondIndex l = sub_.begin[b]; l < sub_.begin[b + 1]; ++l) {
    const bool own = sub_.point[l] == i;
    if (own) vi = sub_.volume[l];
    residual_row +=
        std::abs((own ? 1.0 : 0.0) - sub_.volume[l] * (sub_.inv_volume[b] + from_centroid(sub_.point[l]).dot(gi)));
  }
  return {bond, residual_modulus_ * bond_weight_[b] * sub_.inv_second_moment[b] * vi * residual_row};
}

template <int D>
std::int64_t Hpd<D>::compute_forces(System<D>& sys, const ForceRequest& req) {
  if (req.energy) req.energy->assign(sys.particles.n_real, 0.0);
  std::int64_t newly = 0;
  if (req.break_bonds && !req.break_after_force) newly += break_bonds(sys, req.critical_stretch, false);
  if (law_ == HpdLaw::axial_1d)
    axial_forces(sys, req);
  else
    midpoint_forces(sys, req);
  if (req.break_bonds && req.break_after_force) newly += break_bonds(sys, req.critical_stretch, true);
  return newly;
}

// The critical-stretch rule on each owner's own bond sides (s is symmetric, so both sides of
// a bond break in the same evaluation): s ≥ s₀ before the force, s > s₀ after it.
template <int D>
std::int64_t Hpd<D>::break_bonds(System<D>& sys, double s0, bool after_force) const {
  const auto& p = sys.particles;
  const auto& t = sys.table;
  const auto fam = sys.family_view();
  std::int64_t broken = 0;
#pragma omp parallel for schedule(static) reduction(+ : broken)
  for (Index k = 0; k < fam.n_owners; ++k) {
    const Index i = fam.particle(k);
    for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b) {
      if (!sys.bonds.live(b)) continue;
      const int s = sys.families.shape[b];
      const double e = deform<D>(t.xi[s], t.length[s], p.u[sys.families.neighbor[b]] - p.u[i]).e;
      const double limit = s0 * t.length[s];
      if (after_force ? e > limit : e >= limit) {
        sys.bonds.flags.trial[b] |= kBondBroken;
        ++broken;
      }
    }
  }
  return broken;
}

// axial_1d: f_i = Σ_j c ω β s V_j y/|y|, W_i = ¼ Σ_j c ω β s² |ξ| V_j (the 1D law's energy ½E_b s²
// over the bond areas).
template <int D>
void Hpd<D>::axial_forces(System<D>& sys, const ForceRequest& req) const {
  auto& p = sys.particles;
  const auto& t = sys.table;
  const auto fam = sys.family_view();
#pragma omp parallel for schedule(static)
  for (Index k = 0; k < fam.n_owners; ++k) {
    const Index i = fam.particle(k);
    Vec<D> f = Vec<D>::Zero();
    double w = 0.0;
    sys.for_each_live_bond(i, [&](BondIndex, Index j, int s) {
      const auto g = deform<D>(t.xi[s], t.length[s], p.u[j] - p.u[i]);
      const double stretch = g.e / t.length[s], cw = c_ * t.weight[s] * p.volume[j];
      f += cw * stretch / g.l * g.y;
      w += 0.25 * cw * stretch * stretch * t.length[s];
    });
    p.f[i] = f;
    if (req.energy) (*req.energy)[i] = w;
  }
}

template <int D>
Mat<D> Hpd<D>::second_piola(const System<D>& sys, BondIndex b, const Mat<D>& H, double& psi) const {
  // Ẽ = ½(FᵀF − I) = ½(H + Hᵀ + HᵀH), without the cancellation of I at small strain.
  // Entry by entry: as an expression GCC stored the product in halves and reloaded it whole, a
  // store-forwarding stall that made this the dearest line of a 3D step at δ = 2Δx.
  Mat<D> strain;
  for (int a = 0; a < D; ++a)
    for (int c = 0; c < D; ++c) strain(a, c) = 0.5 * (H(a, c) + H(c, a) + H.col(a).dot(H.col(c)));
  if (sub_.axial[b]) {  // fallback: the bond's own Green strain along it, uniaxial stress
    const Vec<D> n = sys.table.xi[sys.families.shape[b]] / sys.table.length[sys.families.shape[b]];
    const double enn = n.dot(strain * n);
    psi = 0.5 * axial_modulus_ * enn * enn;
    return axial_modulus_ * enn * n * n.transpose();
  }
  Mat<D> S;
  if constexpr (D == 1)
    S = young_ * strain;  // a bar: uniaxial stress
  else
    S = lambda_ * strain.trace() * Mat<D>::Identity() + 2.0 * shear_ * strain;
  psi = 0.5 * (S.array() * strain.array()).sum();
  return S;
}

// Pass 1: every live bond side's P = F S, weighted by V_i a_ij; pass 2: each owner gathers
// −P c_k over the sub-horizon entries that name it.
template <int D>
void Hpd<D>::midpoint_forces(System<D>& sys, const ForceRequest& req) {
  if (remote_) {  // every process fits again when one's sub-horizons changed (its rows go to the others)
    sub_.halo = halo_bonds(sys);
    if (remote_->max(sub_.stale(sys) ? 1.0 : 0.0) > 0.0) {
      sub_.update(sys, min_points_, end_weight_);
      exchange_stiffness_rows(sys);
    }
  } else if (sub_.stale(sys)) {
    sub_.update(sys, min_points_, end_weight_);
  }
  auto& p = sys.particles;
  const auto fam = sys.family_view();
  Index inverted = std::numeric_limits<Index>::max();  // j2: the lowest particle with an inverted bond
  // Each own bond side's P (and residual forces), from its sub-horizon.
  auto bond_stresses = [&](Index i) {
    double w = 0.0, eq = 0.0;
    for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b) {
      if (!sys.bonds.live(b)) {  // its slots hold zeros; a zero P keeps an old inf out of 0 · P
        bond_p_[b] = Mat<D>::Zero();
        if (law_ == HpdLaw::j2) bond_cauchy_[b] = Mat<3>::Zero();
        if (stabilization_ > 0.0) clear_residual(b);
        continue;
      }
      Mat<D> H = Mat<D>::Zero();
      // Column by column: the outer-product expression made GCC spill the product to the stack and
      // reload it across two stores, a store-forwarding stall per entry (3× slower).
      if (stabilization_ > 0.0) {
        w += fit_and_residual(sys, i, b, H) / p.volume[i];
      } else {
        for (BondIndex e = sub_.begin[b]; e < sub_.begin[b + 1]; ++e) {
          const Vec<D>& u = p.u[sub_.point[e]];
          for (int a = 0; a < D; ++a) H.col(a) += sub_.coef[e][a] * u;
        }
      }
      double psi = 0.0;
      if (law_ == HpdLaw::j2 && !sub_.axial[b]) {
        try {
          bond_p_[b] = bond_weight_[b] * j2_stress(b, H, psi);
        } catch (const RunError&) {  // det F ≤ 0 at the midpoint: reported after the region
          bond_p_[b] = Mat<D>::Zero();
#pragma omp critical(hpd_inverted)
          inverted = std::min(inverted, i);
        }
        eq += bond_weight_[b] / p.volume[i] * history_.trial[b].eq_plastic_strain;
      } else {
        const Mat<D> S = second_piola(sys, b, H, psi);
        bond_p_[b] = bond_weight_[b] * (S + H * S);                           // V_i a_ij F S
        if (law_ == HpdLaw::j2) bond_cauchy_[b] = mpm::embed<D>(bond_p_[b]);  // an elastic axial-fallback bond: P ≈ σ
      }
      w += bond_weight_[b] / p.volume[i] * psi;
    }
    if (req.energy) (*req.energy)[i] = w;
    if (law_ == HpdLaw::j2) eq_plastic_[i] = eq;
  };
  // The forces on point i: every slot of a sub-horizon that holds it, in one process's order
  // (distributed: the records of lower processes' bonds, its own slots, the higher ones').
  const int width = stabilization_ > 0.0 ? 2 * D : D;
  auto gather = [&](Index i) {
    Vec<D> f = Vec<D>::Zero();
    auto minus = [&](const double* r) { f -= Eigen::Map<const Vec<D>>(r); };
    for_each_remote_record(i, true, remote_forces_, width, minus);
    for (BondIndex q = sub_.at_begin[i]; q < sub_.at_begin[i + 1]; ++q) f -= bond_p_[sub_.at_bond[q]] * sub_.at_coef[q];
    for_each_remote_record(i, false, remote_forces_, width, minus);
    if (stabilization_ > 0.0) {  // −∂/∂u_i of ½ G Σ_l V_l |r_l|² is −G V_i r_i (the fit is a V-orthogonal projection)
      auto plus = [&](const double* r) { f += Eigen::Map<const Vec<D>>(r + D); };
      for_each_remote_record(i, true, remote_forces_, width, plus);
      for (BondIndex q = sub_.at_begin[i]; q < sub_.at_begin[i + 1]; ++q) f += residual_force_[q];
      for_each_remote_record(i, false, remote_forces_, width, plus);
    }
    p.f[i] = f / p.volume[i];
  };
  if (!remote_) {
    // One parallel region, two loops (the barrier between them is the for's): a fork less per
    // evaluation, which counts in the many small steps of the conservation gates.
#pragma omp parallel
    {
#pragma omp for schedule(static)
      for (Index k = 0; k < fam.n_owners; ++k) bond_stresses(fam.particle(k));
#pragma omp for schedule(static)
      for (Index k = 0; k < fam.n_owners; ++k) gather(fam.particle(k));
    }
  } else {
#pragma omp parallel for schedule(static)
    for (Index k = 0; k < fam.n_owners; ++k) bond_stresses(fam.particle(k));
    remote_forces_ = send_halo_slots(sys, width, [&](Index, BondIndex q, double* out) {
      const Vec<D> v = bond_p_[sub_.at_bond[q]] * sub_.at_coef[q];
      for (int a = 0; a < D; ++a) out[a] = v[a];
      if (stabilization_ > 0.0)
        for (int a = 0; a < D; ++a) out[D + a] = residual_force_[q][a];
    });
#pragma omp parallel for schedule(static)
    for (Index k = 0; k < fam.n_owners; ++k) gather(fam.particle(k));
  }
  if (inverted != std::numeric_limits<Index>::max())
    throw RunError("hpd (constitutive = \"j2\"): a bond of particle " + std::to_string(inverted) +
                   " has an inverted midpoint deformation (det F ≤ 0); the step may be too large or the body crushed");
}

// The halo's bond flags (a distributed run; none in one process): each own particle's flags by
// stencil index, filled into the halo by their owners.
template <int D>
HaloBonds Hpd<D>::halo_bonds(const System<D>& sys) const {
  HaloBonds h;
  if (!remote_) return h;
  const auto& f = sys.families;
  const int width = f.stencil.size();
  const Index n = sys.particles.n_real, size = sys.particles.size();
  std::vector<double> table(static_cast<std::size_t>(size) * width, HaloBonds::kNoBond);
  for (Index i = 0; i < n; ++i)
    for (BondIndex b = f.begin(i); b < f.end(i); ++b)
      table[static_cast<std::size_t>(i) * width + f.shape[b]] = sys.bonds.flags.trial[b];
  remote_->fill(table.data(), width);
  h.stencil = width;
  h.flags.resize(static_cast<std::size_t>(size - n) * width);
  for (std::size_t e = 0; e < h.flags.size(); ++e)
    h.flags[e] = static_cast<std::uint8_t>(table[static_cast<std::size_t>(n) * width + e]);
  return h;
}

// Which records of the others' bond sides arrive for which own point: each process sends, per
// halo point it holds with slots, the point's global index and its number of slots.
template <int D>
void Hpd<D>::index_remote_slots(const System<D>& sys) {
  const Index n = sys.particles.n_real, size = sys.particles.size();
  std::vector<std::vector<double>> to(static_cast<std::size_t>(remote_->processes()));
  for (Index k = n; k < size; ++k) {
    const BondIndex count = sub_.at_begin[k + 1] - sub_.at_begin[k];
    if (count > 0)
      to[remote_->ghost_owner_rank(k - n)].insert(
          to[remote_->ghost_owner_rank(k - n)].end(),
          {static_cast<double>(remote_->ghost_global(k - n)), static_cast<double>(count)});
  }
  const auto from = remote_->send_to(to);
  std::vector<std::vector<RemoteSpan>> per(static_cast<std::size_t>(n));
  const Index first = sys.particles.global_index(0);
  for (int q = 0; q < static_cast<int>(from.size()); ++q) {
    BondIndex record = 0;
    for (std::size_t r = 0; r + 1 < from[q].size(); r += 2) {
      const auto count = static_cast<BondIndex>(from[q][r + 1]);
      per[static_cast<Index>(from[q][r]) - first].push_back({q, record, count});
      record += count;
    }
  }
  span_begin_.assign(static_cast<std::size_t>(n) + 1, 0);
  spans_.clear();
  for (Index i = 0; i < n; ++i) {
    spans_.insert(spans_.end(), per[i].begin(), per[i].end());
    span_begin_[i + 1] = static_cast<BondIndex>(spans_.size());
  }
}

template <int D>
template <class Fn>
std::vector<std::vector<double>> Hpd<D>::send_halo_slots(const System<D>& sys, int width, Fn&& fn) const {
  const Index n = sys.particles.n_real, size = sys.particles.size();
  std::vector<std::vector<double>> to(static_cast<std::size_t>(remote_->processes()));
  for (Index k = n; k < size; ++k) {
    auto& out = to[remote_->ghost_owner_rank(k - n)];
    for (BondIndex q = sub_.at_begin[k]; q < sub_.at_begin[k + 1]; ++q) {
      out.resize(out.size() + width);
      fn(k, q, out.data() + out.size() - width);
    }
  }
  return remote_->send_to(to);
}

template <int D>
void Hpd<D>::exchange_stiffness_rows(const System<D>& sys) {
  remote_rows_ = send_halo_slots(
      sys, 2, [&](Index k, BondIndex q, double* out) { std::tie(out[0], out[1]) = slot_stiffness(sys, k, q); });
}

template <int D>
template <class Fn>
void Hpd<D>::for_each_remote_record(Index i, bool lower, const std::vector<std::vector<double>>& records, int width,
                                    Fn&& fn) const {
  if (!remote_) return;
  const int me = remote_->rank();
  for (BondIndex s = span_begin_[i]; s < span_begin_[i + 1]; ++s) {
    const RemoteSpan& span = spans_[s];
    if ((span.process < me) != lower) continue;
    for (BondIndex r = span.first; r < span.first + span.count; ++r) fn(&records[span.process][r * width]);
  }
}

// Bond side b = i→j with the stabilisation (HpdOptions::stabilization): H (the weighted fit's
// gradient, as the loop in midpoint_forces) and, in the same pass over the sub-horizon, the plain
// fit (ū, H̃), relative to x_i and u_i so that a large rigid motion does not round the residual;
// then the forces −G V_l r_l, G = 2gμ V_i a_ij / tr K̃, written to the slots' places by point for
// the gather. Returns the energy ½ G Σ_l V_l |r_l|² (0 for an axial side: it has no residual).
template <int D>
double Hpd<D>::fit_and_residual(const System<D>& sys, Index i, BondIndex b, Mat<D>& H) {
  // Local pointers: the stores to the residual forces would otherwise make the compiler reload
  // every array's address in every iteration.
  const Index* point = sub_.point.data();
  const Vec<D>* coef = sub_.coef.data();
  const double* volume = sub_.volume.data();
  const BondIndex* place = sub_.entry_at.data();
  const Vec<D>* u = sys.particles.u.data();
  const Vec<D>* x0 = sys.particles.x0.data();
  Vec<D>* force = residual_force_.data();
  const BondIndex first = sub_.begin[b], last = sub_.begin[b + 1];
  const Vec<D> ui = u[i], xi = x0[i], centroid = sub_.centroid[b];
  Vec<D> mean = Vec<D>::Zero();
  Mat<D> moment = Mat<D>::Zero();
  for (BondIndex e = first; e < last; ++e) {
    const Index l = point[e];
    const Vec<D> ul = u[l];
    for (int a = 0; a < D; ++a) H.col(a) += coef[e][a] * ul;
    const Vec<D> du = ul - ui, x = volume[e] * (x0[l] - xi - centroid);
    mean += volume[e] * du;
    for (int a = 0; a < D; ++a) moment.col(a) += x[a] * du;
  }
  if (sub_.axial[b]) {
    clear_residual(b);
    return 0.0;
  }
  mean *= sub_.inv_volume[b];
  const Mat<D> Hp = moment * sub_.volume_inverse[b];
  const double G = residual_modulus_ * bond_weight_[b] * sub_.inv_second_moment[b];
  double sum = 0.0;
  for (BondIndex e = first; e < last; ++e) {
    const Index l = point[e];
    const Vec<D> r = u[l] - ui - mean - Hp * (x0[l] - xi - centroid);
    sum += volume[e] * r.squaredNorm();
    force[place[e]] = -(G * volume[e]) * r;
  }
  return 0.5 * G * sum;
}

template <int D>
void Hpd<D>::clear_residual(BondIndex b) {
  for (BondIndex e = sub_.begin[b]; e < sub_.begin[b + 1]; ++e) residual_force_[sub_.entry_at[e]] = Vec<D>::Zero();
}

// j2: the law from bond b's committed state at F = I + H; its trial state and plastic work
// are written, P = τ F⁻ᵀ returned, psi = the elastic energy density.
template <int D>
Mat<D> Hpd<D>::j2_stress(BondIndex b, const Mat<D>& H, double& psi) {
  const Mat<D> F = Mat<D>::Identity() + H;
  mpm::PointHistory h = history_.committed[b];
  const mpm::StressResult r = j2_->update(F, h);
  history_.trial[b] = h;
  dissipation_.trial[b] = dissipation_.committed[b] + bond_weight_[b] * r.dissipation;
  psi = r.energy;
  bond_cauchy_[b] = bond_weight_[b] / r.J * r.kirchhoff;
  return r.kirchhoff.template topLeftCorner<D, D>() * F.inverse().transpose();
}

template <int D>
void Hpd<D>::accept() {
  if (law_ != HpdLaw::j2) return;
  history_.accept();
  dissipation_.accept();
}

template <int D>
void Hpd<D>::reject() {
  if (law_ != HpdLaw::j2) return;
  history_.reject();
  dissipation_.reject();
}

template <int D>
void Hpd<D>::checkpoint(core::StateArchive& a) {
  if (law_ != HpdLaw::j2) return;
  history_.checkpoint(a, "hpd/history");
  dissipation_.checkpoint(a, "hpd/dissipation");
  a.sync("hpd/eq_plastic_strain", eq_plastic_);
}

template <int D>
double Hpd<D>::plastic_work() const {
  // Bond side by bond side in the global order (distributed: the processes' sums in a chain).
  auto add_own = [&](double* sum) {
    for (double d : dissipation_.trial) *sum += d;
  };
  double sum = 0.0;
  if (remote_)
    remote_->ordered_sum(&sum, 1, add_own);
  else
    add_own(&sum);
  return sum;
}

template <int D>
Tensor6 Hpd<D>::own_stress(const System<D>& sys, Index i) const {
  Mat<3> sigma = Mat<3>::Zero();
  for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b)
    if (sys.bonds.live(b)) sigma += bond_cauchy_[b];
  sigma /= sys.particles.volume[i];
  // xx, yy, zz, xy, yz, xz; σ is symmetric (τ is)
  return {sigma(0, 0), sigma(1, 1), sigma(2, 2), sigma(0, 1), sigma(1, 2), sigma(0, 2)};
}

template <int D>
Mat<D> Hpd<D>::bond_averaged_stress(const System<D>& sys, Index i) const {
  Mat<D> s = Mat<D>::Zero();
  for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b)
    if (sys.bonds.live(b)) s += bond_p_[b];
  return s / sys.particles.volume[i];
}

template class Hpd<1>;
template class Hpd<2>;
template class Hpd<3>;

}  // namespace pdmpm::pd
