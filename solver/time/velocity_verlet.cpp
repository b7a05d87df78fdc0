#include "solver/time/velocity_verlet.hpp"

#include <cmath>

namespace pdmpm::time {

template <int D>
VelocityVerlet<D>::VelocityVerlet(pd::Simulation<D>& sim, double dt) : sim_(sim), dt_(dt) {
  const auto& bcs = sim_.boundaries();
  for (Index i : sim_.movers())
    for (int a = 0; a < D; ++a)
      if (bcs.constrained(i, a)) held_.emplace_back(i, a);
  held_f_.resize(held_.size());
  held_v_.resize(held_.size());
  u_old_.resize(sim_.particles().n_real);
  b_old_.resize(sim_.particles().n_real);
}

template <int D>
void VelocityVerlet<D>::start() {
  auto& p = sim_.particles();
  sim_.boundaries().apply_displacement(p, 0.0, 0.0);
  p.update_ghosts();
  sim_.forces(0.0, true);
  sim_.accept();
  e0_ = sim_.kinetic_energy() + sim_.internal_energy();
}

template <int D>
void VelocityVerlet<D>::step(bool energy) {
  auto& p = sim_.particles();
  const auto& bcs = sim_.boundaries();
  const double dt = dt_, t = time();

  for (std::size_t k = 0; k < held_.size(); ++k) {
    const auto [i, a] = held_[k];
    held_f_[k] = p.f[i][a] + p.b[i][a];
    held_v_[k] = p.v[i][a];
  }
  for (Index i : sim_.movers()) {
    u_old_[i] = p.u[i];
    b_old_[i] = p.b[i];
  }
  sim_.kick(0.5 * dt);
  bcs.apply_velocity(p, t + 0.5 * dt);
  sim_.drift(dt);
  ++steps_;
  const double t1 = time();
  bcs.apply_displacement(p, t1, dt);
  p.update_ghosts();
  sim_.forces(t1, energy);
  sim_.kick(0.5 * dt);
  bcs.apply_velocity(p, t1);
  book_work();
  sim_.accept();
}

// Work of external forces (trapezoidal) and of the supports on held components
// (the change of their kinetic energy minus the work of the forces on them).
template <int D>
void VelocityVerlet<D>::book_work() {
  const auto& p = sim_.particles();
  const double rho = sim_.density();
  // Two sums in the global particle order, the second continuing the first.
  const auto forces = p.template sum_in_order<1>([&](double* dw) {
    for (Index i : sim_.movers()) dw[0] += p.volume[i] * 0.5 * (b_old_[i] + p.b[i]).dot(p.u[i] - u_old_[i]);
  });
  const double dw = p.template sum_in_order<1>(
      [&](double* s) {
        for (std::size_t k = 0; k < held_.size(); ++k) {
          const auto [i, a] = held_[k];
          const double du = p.u[i][a] - u_old_[i][a];
          const double fnew = p.f[i][a] + p.b[i][a];
          s[0] += p.volume[i] *
              (0.5 * rho * (p.v[i][a] * p.v[i][a] - held_v_[k] * held_v_[k]) - 0.5 * (held_f_[k] + fnew) * du);
        }
      },
      forces)[0];
  work_ += dw;
  work_abs_ += std::abs(dw);
}

template <int D>
double VelocityVerlet<D>::pending_work() const {
  const auto& p = sim_.particles();
  const double rho = sim_.density();
  return p.template sum_in_order<1>([&](double* lag) {
    for (Index i : sim_.movers()) {
      const double b = p.b[i].norm();
      if (b > 0.0) lag[0] += p.volume[i] * b * (p.v[i].norm() * dt_ + 0.5 * dt_ * dt_ * b / rho);
    }
  })[0];
}

template <int D>
void VelocityVerlet<D>::checkpoint(core::StateArchive& a) {
  a.sync("verlet/dt", dt_);
  a.sync("verlet/steps", steps_);
  a.sync("verlet/initial_energy", e0_);
  a.sync("verlet/work", work_);
  a.sync("verlet/absolute_work", work_abs_);
}

template class VelocityVerlet<1>;
template class VelocityVerlet<2>;
template class VelocityVerlet<3>;

}  // namespace pdmpm::time
