#include "solver/pd/simulation.hpp"

#include <omp.h>

namespace pdmpm::pd {

template <int D>
Simulation<D>::Simulation(System<D>& system, Model<D>& model, const Forcing<D>& forcing)
    : sys_(system), model_(model), forcing_(forcing), energy_(system.particles.n_real, 0.0) {
  refresh_kinds();
}

template <int D>
void Simulation<D>::refresh_kinds() {
  after_activity(sys_.refresh_activity());
}

template <int D>
void Simulation<D>::refresh_kinds(const std::vector<Index>& kind_changed) {
  after_activity(sys_.refresh_activity(kind_changed));
}

template <int D>
void Simulation<D>::after_activity(const std::vector<Index>& changed) {
  if (!changed.empty()) model_.refresh(sys_, changed);
  const auto& p = sys_.particles;
  movers_.clear();
  for (Index i = 0; i < p.n_real; ++i)
    if (p.kind[i] == core::ParticleKind::pd) movers_.push_back(i);
}

template <int D>
void Simulation<D>::external_forces(double t) {
  auto& p = particles();
  for (Index i = 0; i < p.n_real; ++i) p.b[i].setZero();
  if (forcing_.body_force) {
    bc::ExpressionVariables vars;
    vars.t = t;
    for (Index i = 0; i < p.n_real; ++i) {
      vars.x = p.x0[i][0];
      if constexpr (D > 1) vars.y = p.x0[i][1];
      if constexpr (D > 2) vars.z = p.x0[i][2];
      for (int a = 0; a < D; ++a) p.b[i][a] = (*forcing_.body_force)[a](vars);
    }
  }
  if (forcing_.boundaries) forcing_.boundaries->add_tractions(p, t);
  if (forcing_.indenter) indenter_force_ = forcing_.indenter->add_forces(p, t);
}

template <int D>
double Simulation<D>::probe_internal_energy(bool allow_breaks) {
  const std::int64_t sides = broken_sides_;
  internal_forces(true, allow_breaks);
  reject();
  broken_sides_ = sides;
  return internal_energy();
}

template <int D>
void Simulation<D>::internal_forces(bool energy, bool allow_breaks) {
  ForceRequest req;
  req.break_bonds = forcing_.breaking.enabled && allow_breaks;
  req.critical_stretch = forcing_.breaking.critical_stretch;
  req.break_after_force = forcing_.breaking.after_force;
  req.energy = energy ? &energy_ : nullptr;
  const double t0 = omp_get_wtime();
  const std::int64_t newly = model_.compute_forces(sys_, req);
  sys_.bonds.pending_breaks += newly;
  broken_sides_ += newly;
  force_seconds_ += omp_get_wtime() - t0;
  bond_evaluations_ += sys_.families.n_bonds();
  if (forcing_.contact) {
    const double t1 = omp_get_wtime();
    contact_pairs_ = forcing_.contact->add_forces(sys_);
    contact_seconds_ += omp_get_wtime() - t1;
  }
}

template <int D>
void Simulation<D>::kick(double h) {
  auto& p = particles();
  const auto& mask = boundaries().mask();
  const double rho = density();
  const auto n = static_cast<Index>(movers_.size());
#pragma omp parallel for schedule(static)
  for (Index k = 0; k < n; ++k) {
    const Index i = movers_[k];
    for (int a = 0; a < D; ++a)
      if (!mask[static_cast<std::size_t>(i) * D + a]) p.v[i][a] += h * (p.f[i][a] + p.b[i][a]) / rho;
  }
}

template <int D>
void Simulation<D>::drift(double dt) {
  auto& p = particles();
  const auto n = static_cast<Index>(movers_.size());
#pragma omp parallel for schedule(static)
  for (Index k = 0; k < n; ++k) {
    const Index i = movers_[k];
    p.u[i] += dt * p.v[i];
  }
}

// Sums over the movers in the global particle order (over every process in a distributed run).
template <int D>
double Simulation<D>::kinetic_energy() const {
  const auto& p = particles();
  const auto [ke] = p.template sum_in_order<1>([&](double* s) {
    for (Index i : movers_) s[0] += p.volume[i] * p.v[i].squaredNorm();
  });
  return 0.5 * density() * ke;
}

template <int D>
double Simulation<D>::internal_energy() const {
  const auto& p = particles();
  return p.template sum_in_order<1>([&](double* s) {
    for (Index i : movers_) s[0] += energy_[i] * p.volume[i];
  })[0];
}

template <int D>
Vec<D> Simulation<D>::momentum() const {
  const auto& p = particles();
  const auto m = p.template sum_in_order<D>([&](double* s) {
    for (Index i : movers_)
      for (int a = 0; a < D; ++a) s[a] += p.volume[i] * p.v[i][a];
  });
  return density() * Eigen::Map<const Vec<D>>(m.data());
}

template <int D>
Eigen::Vector3d Simulation<D>::angular_momentum() const {
  const auto& p = particles();
  const auto L = p.template sum_in_order<3>([&](double* s) {
    for (Index i : movers_) {
      Eigen::Vector3d x = Eigen::Vector3d::Zero(), q = Eigen::Vector3d::Zero();
      const Vec<D> xi = p.position(i);
      for (int a = 0; a < D; ++a) x[a] = xi[a], q[a] = p.volume[i] * p.v[i][a];
      const Eigen::Vector3d c = x.cross(q);
      for (int k = 0; k < 3; ++k) s[k] += c[k];
    }
  });
  return density() * Eigen::Map<const Eigen::Vector3d>(L.data());
}

template <int D>
void Simulation<D>::checkpoint(core::StateArchive& a) {
  a.expect("pd/bond_sides", sys_.families.n_bonds());
  sys_.bonds.checkpoint(a);
  a.sync("pd/owners", sys_.owners);
  model_.checkpoint(a);
  if (forcing_.contact) forcing_.contact->checkpoint(a);
  a.sync("pd/movers", movers_);
  a.sync("pd/energy_density", energy_);
  a.sync("pd/broken_sides", broken_sides_);
  a.sync("pd/contact_pairs", contact_pairs_);
  a.sync("pd/bond_evaluations", bond_evaluations_);
  a.sync("pd/indenter_force", indenter_force_);
  a.sync("pd/force_seconds", force_seconds_);
  a.sync("pd/contact_seconds", contact_seconds_);
}

template class Simulation<1>;
template class Simulation<2>;
template class Simulation<3>;

}  // namespace pdmpm::pd
