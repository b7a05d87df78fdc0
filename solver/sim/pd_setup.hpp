#pragma once
// Everything a PD run needs, built from a validated scene: particles (with
// symmetry ghosts), families, pre-cracks, the force model, boundary conditions,
// initial conditions (applied to u and v), loads, contact and probes. All
// user-facing checks that need the particles (empty body, empty regions, probes
// outside the body) happen here, before any output is written.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "solver/bc/boundary.hpp"
#include "solver/bc/initial_condition.hpp"
#include "solver/bc/indenter.hpp"
#include "solver/dist/distribute.hpp"
#include "solver/io/scene.hpp"
#include "solver/pd/contact.hpp"
#include "solver/pd/crack_observables.hpp"
#include "solver/pd/model.hpp"
#include "solver/pd/simulation.hpp"
#include "solver/sim/j_integral_outputs.hpp"
#include "solver/sim/probes.hpp"

namespace pdmpm::sim {

template <int D>
struct PdSetup {
  pd::System<D> system;
  std::unique_ptr<pd::Model<D>> model;
  bc::Boundaries<D> boundaries;
  std::vector<bc::InitialCondition<D>> initial;  // [[initial]], already applied to the particles
  std::array<bc::Expression, D> body_force;
  bool has_body_force = false;
  std::optional<bc::Indenter<D>> indenter;
  std::optional<pd::ShortRangeContact<D>> contact;
  std::vector<Probe> probes;
  std::vector<JIntegralOutput> j_integrals;  // [[j_integral]] (2D)
  double critical_stretch = 0.0;             // 0 when damage is off
  bool damage = false;
  bool break_after_force = false;  // LAMMPS' bond-break timing (scene model.break_timing)
  std::int64_t precrack_cut = 0;   // bond sides cut by pre-cracks
  Index symmetry_ghosts = 0;       // mirror particles of the whole body (as one process makes them)
  // Crack observables, when the scene asks for them.
  std::optional<pd::CrackSettings> crack;
  std::vector<pd::NamedLocation<D>> locations;
  std::vector<std::uint8_t> crack_exclude;  // per real particle: in a region excluded from crack detection
  // A distributed run with crack observables: the whole body, its families' flags filled
  // from every process's at each history sample (docs/models/distributed.md).
  std::optional<pd::System<D>> crack_body;
  pd::System<D>& crack_system() { return crack_body ? *crack_body : system; }
  // A distributed run: this process's particles in the whole body (its store holds
  // its own particles and their halo, solver/dist/).
  std::optional<dist::Ownership> ownership;

  // What acts on the body besides its bonds, for a pd::Simulation.
  pd::Forcing<D> forcing() {
    pd::Forcing<D> f;
    f.boundaries = &boundaries;
    f.body_force = has_body_force ? &body_force : nullptr;
    f.indenter = indenter ? &*indenter : nullptr;
    f.contact = contact ? &*contact : nullptr;
    f.breaking = {damage, critical_stretch, break_after_force};
    return f;
  }
};

// The body of a setup in motion.
template <int D>
pd::Simulation<D> make_simulation(PdSetup<D>& s) {
  return pd::Simulation<D>(s.system, *s.model, s.forcing());
}

// With a communicator of more than one process, each builds its share of the body
// (solver/dist/distribute.hpp); the scene's checks (a region selecting nothing, a
// pre-crack cutting nothing) then look at the whole body.
template <int D>
PdSetup<D> build_pd(const io::Scene& scene, const dist::Communicator* comm = nullptr);

}  // namespace pdmpm::sim
