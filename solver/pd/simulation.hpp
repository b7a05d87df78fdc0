#pragma once
// A PD body in motion, as mpm::Simulation is for MPM: it borrows the particle
// store (through pd::System) and acts only on its own particles —
//   owners (PD and transition kinds): their bond loops run, so PD forces on a
//           transition particle are there for the grid to take;
//   movers (PD kind): the particles it integrates, and whose energy and
//           momentum it counts; MPM and transition particles belong to the grid.
// It exposes the verbs a time integrator needs — forces(t), kick, drift,
// energies, momentum, accept/reject of the bond state — and owns no loop in
// time: velocity Verlet and dynamic relaxation live in solver/time/.
#include <array>
#include <cstdint>
#include <vector>

#include "solver/bc/boundary.hpp"
#include "solver/bc/expression.hpp"
#include "solver/bc/indenter.hpp"
#include "solver/pd/contact.hpp"
#include "solver/pd/model.hpp"

namespace pdmpm::pd {

// The critical-stretch rule as a run applies it.
struct BondBreaking {
  bool enabled = false;
  double critical_stretch = 0.0;  // s₀
  bool after_force = false;       // LAMMPS' timing (see ForceRequest)
};

// What acts on a PD body besides its bonds; null pointers for what a scene lacks.
template <int D>
struct Forcing {
  const bc::Boundaries<D>* boundaries = nullptr;  // supports, prescribed motion, tractions
  const std::array<bc::Expression, D>* body_force = nullptr;
  const bc::Indenter<D>* indenter = nullptr;
  ShortRangeContact<D>* contact = nullptr;
  BondBreaking breaking;
};

template <int D>
class Simulation {
 public:
  Simulation(System<D>& system, Model<D>& model, const Forcing<D>& forcing);

  System<D>& system() { return sys_; }
  const System<D>& system() const { return sys_; }
  Model<D>& model() { return model_; }
  const Model<D>& model() const { return model_; }
  core::Particles<D>& particles() { return sys_.particles; }
  const core::Particles<D>& particles() const { return sys_.particles; }
  const bc::Boundaries<D>& boundaries() const { return *forcing_.boundaries; }
  const Forcing<D>& forcing() const { return forcing_; }
  double density() const { return sys_.material.rho; }
  const std::vector<Index>& movers() const { return movers_; }

  // After particle kinds changed: which bonds are live, the owner and mover
  // lists, and the model's per-particle constants of the particles concerned.
  // Broken bonds stay broken. With `kind_changed` (the real particles whose kind
  // changed, when that is all that did) only their bonds and their neighbours' are
  // re-derived; the result is the same.
  void refresh_kinds();
  void refresh_kinds(const std::vector<Index>& kind_changed);

  // External force density b at time (or load factor) t: body force, tractions, indenter.
  void external_forces(double t);
  // Internal force density f (model + contact) of the owners, breaking bonds if
  // the run asks and `allow_breaks`; with `energy`, also the strain energy density of each owner.
  void internal_forces(bool energy, bool allow_breaks = true);
  void forces(double t, bool energy) {
    external_forces(t);
    internal_forces(energy);
  }

  // v += h (f + b)/ρ on the movers' free components (h = Δt/2 in velocity Verlet).
  void kick(double h);
  // u += Δt v on the movers.
  void drift(double dt);

  // The bond state the last evaluations wrote becomes committed / is dropped.
  void accept() {
    sys_.bonds.accept();
    model_.accept();
  }
  void reject() {
    sys_.bonds.reject();
    model_.reject();
  }

  // Strain energy of the current displacements, committing nothing: an evaluation
  // whose breaks and plastic flow are dropped (the next evaluation makes them again).
  // Without `allow_breaks` no bond breaks in it: the energy of the bonds as they are.
  double probe_internal_energy(bool allow_breaks = true);

  // Its state for a checkpoint (core/state_archive.hpp): bond flags, the model's and
  // contact's state, the counters; not the particle store, which it borrows.
  void checkpoint(core::StateArchive& a);

  double kinetic_energy() const;
  double internal_energy() const;  // from the last internal_forces(true)
  // Strain energy density of owner i (a mover or, in a hybrid, a transition particle)
  // from the last internal_forces(true).
  double energy_density(Index i) const { return energy_[i]; }
  Vec<D> momentum() const;
  Eigen::Vector3d angular_momentum() const;

  std::int64_t broken_bonds() const { return broken_sides_ / 2; }
  // Broken bond sides of the real particles (a distributed run sums them over its processes).
  std::int64_t broken_sides() const { return broken_sides_; }
  std::int64_t contact_pairs() const { return contact_pairs_; }
  const Vec<D>& indenter_force() const { return indenter_force_; }
  double force_seconds() const { return force_seconds_; }      // the model's bond loops
  double contact_seconds() const { return contact_seconds_; }  // short-range contact (LAMMPS times it in "Pair" too)
  std::int64_t bond_evaluations() const { return bond_evaluations_; }

 private:
  void after_activity(const std::vector<Index>& changed);  // the model's constants, the mover list

  System<D>& sys_;
  Model<D>& model_;
  Forcing<D> forcing_;
  std::vector<Index> movers_;
  std::vector<double> energy_;
  std::int64_t broken_sides_ = 0, contact_pairs_ = 0, bond_evaluations_ = 0;
  Vec<D> indenter_force_ = Vec<D>::Zero();
  double force_seconds_ = 0.0, contact_seconds_ = 0.0;
};

}  // namespace pdmpm::pd
