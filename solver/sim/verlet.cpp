#include "solver/sim/verlet.hpp"

#include <cmath>

namespace pdmpm::sim {

template <int D>
VerletStepper<D>::VerletStepper(PdState<D>& state, double dt) : st_(state), dt_(dt) {
  const auto& p = st_.particles();
  const auto& bcs = st_.setup().boundaries;
  for (Index i = 0; i < p.n_real; ++i)
    for (int a = 0; a < D; ++a)
      if (bcs.constrained(i, a)) held_.emplace_back(i, a);
  held_f_.resize(held_.size());
  held_v_.resize(held_.size());
  u_old_.resize(p.n_real);
  b_old_.resize(p.n_real);
}

template <int D>
void VerletStepper<D>::start() {
  auto& p = st_.particles();
  st_.setup().boundaries.apply_displacement(p, 0.0, 0.0);
  p.update_ghosts();
  st_.external_forces(0.0);
  st_.internal_forces(true);
  e0_ = st_.kinetic_energy() + st_.internal_energy();
}

template <int D>
void VerletStepper<D>::step(bool energy) {
  auto& p = st_.particles();
  const auto& bcs = st_.setup().boundaries;
  const auto& mask = bcs.mask();
  const double rho = st_.density(), dt = dt_;
  const Index n = p.n_real;
  const double t = time();

  for (std::size_t k = 0; k < held_.size(); ++k) {
    const auto [i, a] = held_[k];
    held_f_[k] = p.f[i][a] + p.b[i][a];
    held_v_[k] = p.v[i][a];
  }
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i) {
    for (int a = 0; a < D; ++a)
      if (!mask[static_cast<std::size_t>(i) * D + a]) p.v[i][a] += 0.5 * dt * (p.f[i][a] + p.b[i][a]) / rho;
    u_old_[i] = p.u[i];
    b_old_[i] = p.b[i];
  }
  bcs.apply_velocity(p, t + 0.5 * dt);
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i) p.u[i] += dt * p.v[i];
  ++steps_;
  const double t1 = time();
  bcs.apply_displacement(p, t1, dt);
  p.update_ghosts();
  st_.external_forces(t1);
  st_.internal_forces(energy);
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i)
    for (int a = 0; a < D; ++a)
      if (!mask[static_cast<std::size_t>(i) * D + a]) p.v[i][a] += 0.5 * dt * (p.f[i][a] + p.b[i][a]) / rho;
  bcs.apply_velocity(p, t1);

  // Work of external forces (trapezoidal) and of the supports on held components
  // (the change of their kinetic energy minus the work of the forces on them).
  double dw = 0.0;
  for (Index i = 0; i < n; ++i) dw += p.volume[i] * 0.5 * (b_old_[i] + p.b[i]).dot(p.u[i] - u_old_[i]);
  for (std::size_t k = 0; k < held_.size(); ++k) {
    const auto [i, a] = held_[k];
    const double du = p.u[i][a] - u_old_[i][a];
    const double fnew = p.f[i][a] + p.b[i][a];
    dw += p.volume[i] * (0.5 * rho * (p.v[i][a] * p.v[i][a] - held_v_[k] * held_v_[k]) - 0.5 * (held_f_[k] + fnew) * du);
  }
  work_ += dw;
  work_abs_ += std::abs(dw);
}

template <int D>
double VerletStepper<D>::pending_work() const {
  const auto& p = st_.particles();
  const double rho = st_.density();
  double lag = 0.0;
  for (Index i = 0; i < p.n_real; ++i) {
    const double b = p.b[i].norm();
    if (b > 0.0) lag += p.volume[i] * b * (p.v[i].norm() * dt_ + 0.5 * dt_ * dt_ * b / rho);
  }
  return lag;
}

template class VerletStepper<1>;
template class VerletStepper<2>;
template class VerletStepper<3>;

}  // namespace pdmpm::sim
