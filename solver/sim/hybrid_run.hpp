#pragma once
// The time loop of an adaptive SBPD–MPM scene ([hybrid]): a fixed step (time.dt,
// or time.safety_factor × the smaller of the PD stable step and the grid's CFL
// step at t = 0), instability detection, history, field frames (with the
// per-particle `method`), progress and summary — the outputs of the PD and MPM
// runs, through the same RunRecorder.
#include "solver/sim/hybrid_setup.hpp"
#include "solver/sim/run.hpp"

namespace pdmpm::sim {

// Columns of history.csv besides step/time: the particles of each kind, the
// cumulative region events, the crack tips (count and the first kHybridTipColumns
// positions, NaN where there are fewer), energies, momentum, max damage, probes.
constexpr int kHybridTipColumns = 4;

template <int D>
RunResult run_hybrid(const io::Scene& scene, HybridSetup<D>& setup, const RunOptions& options);

}  // namespace pdmpm::sim
