#pragma once
// Everything an MPM run needs, built from a validated scene of model type "mpm":
// the particles (kind mpm, on the scene's lattice) and the mpm::Settings the
// scene's [material], [mpm], [time], boundaries, symmetry planes and body force
// translate into. The translation, key by key, is in the README ("MPM scenes").
#include <memory>
#include <string>
#include <vector>

#include "solver/bc/initial_condition.hpp"
#include "solver/dist/communicator.hpp"
#include "solver/core/particles.hpp"
#include "solver/io/scene.hpp"
#include "solver/mpm/settings.hpp"
#include "solver/mpm/simulation.hpp"
#include "solver/sim/j_integral_outputs.hpp"
#include "solver/sim/probes.hpp"

namespace pdmpm::sim {

// The mpm::Settings a scene's [material], [mpm], [time], boundaries, symmetry
// planes and body force translate into (model type "mpm", and the grid of a
// hybrid scene), with the grid origin on the body's lower faces.
template <int D>
struct MpmGridSettings {
  mpm::Settings<D> settings;
  // Per settings.boundaries entry: the index of the scene boundary it comes from
  // (fixed/velocity regions), or −1 for a symmetry plane.
  std::vector<int> grid_bc_source;
};

// Throws InputError for a symmetry plane that cuts the body or a "free" traction component.
template <int D>
MpmGridSettings<D> translate_mpm(const io::Scene& scene);

// Each fixed/velocity region must hold a grid node, or the condition does nothing:
// InputError naming the boundary's region otherwise.
template <int D>
void check_boundary_nodes(const io::Scene& scene, const std::vector<int>& grid_bc_source,
                          const mpm::Simulation<D>& sim);

// An initial displacement strains the material: F = I + ∇u at each particle it
// reaches (∇u by central differences of the expressions,
// bc::initial_displacement_gradients) and the stress of that F. Call once the
// simulation exists, before its first step.
template <int D>
void set_initial_deformation(const std::vector<bc::InitialCondition<D>>& initial, mpm::Simulation<D>& sim);

template <int D>
struct MpmSetup {
  core::Particles<D> particles;
  mpm::Settings<D> settings;
  // Per settings.boundaries entry: the index of the scene boundary it comes from
  // (fixed/velocity regions), or −1 for a symmetry plane. Reactions are summed per
  // scene boundary.
  std::vector<int> grid_bc_source;
  std::vector<Probe> probes;
  std::vector<JIntegralOutput> j_integrals;  // [[j_integral]] (2D)
  // [[initial]], already applied to u and v; set_initial_deformation gives the
  // simulation the matching deformation gradients.
  std::vector<bc::InitialCondition<D>> initial;
  // A distributed run (docs/models/distributed.md): `particles` holds this process's own
  // points; `others` are the other processes as the step sees them.
  std::shared_ptr<mpm::OtherProcesses> others;
  Index global_count = 0;  // the whole body's points
};

// Throws InputError for what only the particles reveal (empty body, a symmetry
// plane that cuts the body, traction regions without particles).
// With `comm` of more than one process, each process keeps its share of the points.
template <int D>
MpmSetup<D> build_mpm(const io::Scene& scene, const dist::Communicator* comm = nullptr);

}  // namespace pdmpm::sim
