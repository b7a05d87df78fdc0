#pragma once
// Velocity Verlet (central difference, seed 004 eq 45) for a PD body:
//   v += ½Δt (f + b)/ρ;  velocity BCs at t + ½Δt;  u += Δt v;  displacement BCs at t + Δt;
//   forces at t + Δt;  v += ½Δt (f + b)/ρ;  velocity BCs at t + Δt.
// Keeps the work done by external forces and supports, so energy balance and
// instability can be judged.
#include "solver/sim/pd_state.hpp"

namespace pdmpm::sim {

template <int D>
class VerletStepper {
 public:
  VerletStepper(PdState<D>& state, double dt);

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

 private:
  PdState<D>& st_;
  double dt_;
  std::int64_t steps_ = 0;
  double e0_ = 0.0, work_ = 0.0, work_abs_ = 0.0;
  std::vector<std::pair<Index, int>> held_;
  std::vector<double> held_f_, held_v_;
  std::vector<Vec<D>> u_old_, b_old_;
};

}  // namespace pdmpm::sim
