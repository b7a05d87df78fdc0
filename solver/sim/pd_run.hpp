#pragma once
// The PD time loops: velocity Verlet (dynamic) and adaptive dynamic relaxation
// (quasi-static, Kilic & Madenci 2010), with energy bookkeeping, instability
// detection, history, field frames and progress.
#include "solver/sim/pd_setup.hpp"
#include "solver/sim/run.hpp"

namespace pdmpm::sim {

template <int D>
RunResult run_pd(const io::Scene& scene, PdSetup<D>& setup, const RunOptions& options);

}  // namespace pdmpm::sim
