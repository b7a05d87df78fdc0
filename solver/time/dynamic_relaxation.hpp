#pragma once
// Adaptive dynamic relaxation (Kilic & Madenci 2010) for quasi-static PD:
// pseudo-time Δt = 1, a diagonal fictitious density λ_i from the stiffness
// row sum (large enough for stability), and the damping coefficient
// c = 2 sqrt(uᵀ ¹K u / uᵀu) from the local diagonal stiffness estimate.
// Every iteration's bond state is accepted (bonds broken while relaxing stay broken).
#include "solver/pd/simulation.hpp"

namespace pdmpm::time {

struct RelaxationResult {
  bool converged = false;
  std::int64_t iterations = 0;
  double residual = 0.0;  // ‖f + b‖ over free components / load scale
};

template <int D>
class DynamicRelaxation {
 public:
  explicit DynamicRelaxation(pd::Simulation<D>& sim);
  // Relaxes to equilibrium at load factor t (the `t` of the scene's expressions).
  RelaxationResult solve(double t, double tolerance, std::int64_t max_iterations);

 private:
  pd::Simulation<D>& sim_;
  std::vector<double> lambda_;
  std::vector<Vec<D>> vhalf_, fprev_;
};

}  // namespace pdmpm::time
