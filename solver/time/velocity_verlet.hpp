#pragma once
// Velocity Verlet (central difference; Gu & Zhou 2017 eq 45) for a PD body:
//   kick ½Δt;  velocity BCs at t + ½Δt;  drift Δt;  displacement BCs at t + Δt;
//   forces at t + Δt;  kick ½Δt;  velocity BCs at t + Δt;  accept the bond state.
// Keeps the work done by external forces and supports, so energy balance and
// instability can be judged.
#include <utility>
#include <vector>

#include "solver/pd/simulation.hpp"

namespace pdmpm::time {

template <int D>
class VelocityVerlet {
 public:
  VelocityVerlet(pd::Simulation<D>& sim, double dt);

  // Applies the t = 0 boundary conditions and evaluates the first forces.
  void start();
  // One step; `energy` also evaluates the strain energy at the new state.
  void step(bool energy);

  double time() const { return dt_ * static_cast<double>(steps_); }
  std::int64_t steps() const { return steps_; }
  double dt() const { return dt_; }
  double initial_energy() const { return e0_; }
  double external_work() const { return work_; }
  double absolute_work() const { return work_abs_; }
  // Work the current external forces can do within one step (what the booked
  // work lags behind the kinetic energy by).
  double pending_work() const;

  // Resume: the integrator's own state (steps, work books); the body's is the Simulation's.
  void checkpoint(core::StateArchive& a);

 private:
  void book_work();

  pd::Simulation<D>& sim_;
  double dt_;
  std::int64_t steps_ = 0;
  double e0_ = 0.0, work_ = 0.0, work_abs_ = 0.0;
  std::vector<std::pair<Index, int>> held_;  // supported (particle, component) pairs
  std::vector<double> held_f_, held_v_;
  std::vector<Vec<D>> u_old_, b_old_;
};

}  // namespace pdmpm::time
