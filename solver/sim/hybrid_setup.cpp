#include "solver/sim/hybrid_setup.hpp"

#include "solver/core/error.hpp"
#include "solver/sim/geometry_from_scene.hpp"

namespace pdmpm::sim {
namespace {

const io::Scene& checked(const io::Scene& scene) {
  if (scene.method != io::Method::hybrid || !scene.hybrid || !scene.mpm)
    throw InputError(scene.file, "hybrid", "a hybrid run needs a hybrid scene ([hybrid] and [mpm] tables)");
  return scene;
}

}  // namespace

template <int D>
HybridSetup<D>::HybridSetup(const io::Scene& scene) : pd(build_pd<D>(checked(scene))) {
  auto grid = translate_mpm<D>(scene);
  grid_bc_source = std::move(grid.grid_bc_source);
  pd_simulation = std::make_unique<pd::Simulation<D>>(pd.system, *pd.model, pd.forcing());
  mpm_simulation =
      std::make_unique<mpm::Simulation<D>>(std::move(grid.settings), pd.system.particles, scene.file, "mpm");
  check_boundary_nodes<D>(scene, grid_bc_source, *mpm_simulation);
  // build_pd moved and sped up the particles; the grid's state needs the strain too
  // (every real particle's, since any may be carried by the grid).
  set_initial_deformation<D>(pd.initial, *mpm_simulation);
  hybrid_simulation = std::make_unique<hybrid::Simulation<D>>(*pd_simulation, *mpm_simulation, *scene.hybrid);
  if (!scene.initial_pd.empty()) {
    const auto& p = pd.system.particles;
    initial_pd = select_particles<D>(p.x0, p.n_real, make_geometry<D>(scene.initial_pd), scene.spacing);
    if (initial_pd.empty())
      throw InputError(scene.file, "hybrid.initial_pd",
                       "selects no particle (particles sit on lattice sites; check the region against the body)");
  }
}

template <int D>
std::unique_ptr<HybridSetup<D>> build_hybrid(const io::Scene& scene) {
  return std::make_unique<HybridSetup<D>>(scene);
}

template struct HybridSetup<2>;
template struct HybridSetup<3>;
template std::unique_ptr<HybridSetup<2>> build_hybrid<2>(const io::Scene&);
template std::unique_ptr<HybridSetup<3>> build_hybrid<3>(const io::Scene&);

}  // namespace pdmpm::sim
