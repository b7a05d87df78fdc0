#pragma once
// Critical time step of explicit central differences for a PD body.
//  silling_askari  Δt = min_i sqrt(2ρ / Σ_j V_j C_ij) over the PD particles (Silling & Askari 2005):
//                  a Gershgorin-type bound, so never above the true limit.
//  lanczos         Δt = 2 / sqrt(λ_max(M⁻¹K)), λ_max by the Lanczos method on the
//                  force operator linearised about the current state: the
//                  actual limit of the linear(ised) problem.
#include <cstdint>

#include "solver/pd/model.hpp"

namespace pdmpm::time {

template <int D>
double silling_askari_step(const pd::System<D>& sys, const pd::Model<D>& model, double extra_row_sum = 0.0);

struct LanczosResult {
  double dt = 0.0;
  double lambda_max = 0.0;
  int iterations = 0;
  double relative_change = 0.0;  // of λ_max over the last 10 iterations
};

// Leaves the system's displacements, forces and broken flags as it found them.
template <int D>
LanczosResult lanczos_step(pd::System<D>& sys, pd::Model<D>& model, int max_iterations = 300, double tolerance = 1e-7);

}  // namespace pdmpm::time
