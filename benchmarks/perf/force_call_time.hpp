#pragma once
// Seconds per force evaluation of a PD model, averaged over `calls` after one warm-up
// call. A plastic model is never accepted: every call starts from the same committed
// state, as the first trial of a time step does.
#include <omp.h>

#include "solver/pd/model.hpp"

namespace pdmpm::perf {

inline double seconds_per_force_call(pd::Model<3>& model, pd::System<3>& sys, int calls) {
  model.compute_forces(sys, {});
  const double t0 = omp_get_wtime();
  for (int k = 0; k < calls; ++k) model.compute_forces(sys, {});
  return (omp_get_wtime() - t0) / calls;
}

}  // namespace pdmpm::perf
