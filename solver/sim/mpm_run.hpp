#pragma once
// The MPM time loop for a scene of model type "mpm": a fixed step (time.dt, or
// time.safety_factor × the grid CFL step at t = 0), energy bookkeeping and
// instability detection, history, field frames, progress and summary — the same
// outputs as a PD run (solver/sim/pd_run.hpp) with MPM's own fields.
#include "solver/sim/mpm_setup.hpp"
#include "solver/sim/run.hpp"

namespace pdmpm::sim {

template <int D>
RunResult run_mpm(const io::Scene& scene, MpmSetup<D>& setup, const RunOptions& options);

}  // namespace pdmpm::sim
