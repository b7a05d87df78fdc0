#pragma once
// Everything an adaptive SBPD–MPM run needs, built from a validated hybrid scene:
// the PD body (build_pd: particles, families, model, boundaries, pre-cracks), the
// mpm::Settings the same scene translates into (translate_mpm), the MPM simulation
// on the PD body's particle store, and the hybrid::Simulation that borrows both.
// Built once, in place: hybrid::Simulation holds references into the others, so
// the setup is neither copied nor moved (build_hybrid returns it by unique_ptr).
#include <memory>
#include <vector>

#include "solver/hybrid/simulation.hpp"
#include "solver/io/scene.hpp"
#include "solver/mpm/simulation.hpp"
#include "solver/pd/simulation.hpp"
#include "solver/sim/mpm_setup.hpp"
#include "solver/sim/pd_setup.hpp"

namespace pdmpm::sim {

template <int D>
struct HybridSetup {
  // Throws InputError for what only the particles or the grid reveal (empty body,
  // empty regions, a boundary box without grid nodes, an initial PD region without particles).
  explicit HybridSetup(const io::Scene& scene);
  HybridSetup(const HybridSetup&) = delete;
  HybridSetup& operator=(const HybridSetup&) = delete;

  PdSetup<D> pd;                    // the body and its PD parts (built in place: the model may point into it)
  std::vector<int> grid_bc_source;  // per grid condition: the scene boundary (translate_mpm)
  std::unique_ptr<pd::Simulation<D>> pd_simulation;
  std::unique_ptr<mpm::Simulation<D>> mpm_simulation;  // on pd.system.particles
  std::unique_ptr<hybrid::Simulation<D>> hybrid_simulation;
  std::vector<Index> initial_pd;  // the particles of [hybrid] initial_pd's regions: they start PD
};

template <int D>
std::unique_ptr<HybridSetup<D>> build_hybrid(const io::Scene& scene);

}  // namespace pdmpm::sim
