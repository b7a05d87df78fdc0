#pragma once
// Everything an MPM run needs, built from a validated scene of model type "mpm":
// the particles (kind mpm, on the scene's lattice) and the mpm::Settings the
// scene's [material], [mpm], [time], boundaries, symmetry planes and body force
// translate into. The translation, key by key, is in the README ("MPM scenes").
#include <string>
#include <vector>

#include "solver/core/particles.hpp"
#include "solver/io/scene.hpp"
#include "solver/mpm/settings.hpp"
#include "solver/sim/probes.hpp"

namespace pdmpm::sim {

template <int D>
struct MpmSetup {
  core::Particles<D> particles;
  mpm::Settings<D> settings;
  // Per settings.boundaries entry: the index of the scene boundary it comes from
  // (fixed/velocity regions), or −1 for a symmetry plane. Reactions are summed per
  // scene boundary.
  std::vector<int> grid_bc_source;
  std::vector<Probe> probes;
};

// Throws InputError for what only the particles reveal (empty body, a symmetry
// plane that cuts the body, traction regions without particles).
template <int D>
MpmSetup<D> build_mpm(const io::Scene& scene);

}  // namespace pdmpm::sim
