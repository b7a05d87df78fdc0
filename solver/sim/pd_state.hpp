#pragma once
// A PD body in motion: its setup plus what the integrators share — force
// evaluation (internal, contact, external), energies and bookkeeping counters.
#include <vector>

#include "solver/sim/pd_setup.hpp"

namespace pdmpm::sim {

template <int D>
class PdState {
 public:
  explicit PdState(PdSetup<D>& setup);

  PdSetup<D>& setup() { return s_; }
  const PdSetup<D>& setup() const { return s_; }
  core::Particles<D>& particles() { return s_.system.particles; }
  const core::Particles<D>& particles() const { return s_.system.particles; }
  double density() const { return s_.system.material.rho; }

  // External force density b at time (or load factor) t: body force, tractions, indenter.
  void external_forces(double t);
  // Internal force density f (model + contact), breaking bonds if damage is on.
  // With `energy`, also the strain energy density of every particle.
  void internal_forces(bool energy);

  double kinetic_energy() const;
  double internal_energy() const;  // from the last internal_forces(true)
  Vec<D> momentum() const;
  Eigen::Vector3d angular_momentum() const;

  std::int64_t broken_bonds() const { return broken_sides_ / 2; }
  std::int64_t contact_pairs() const { return contact_pairs_; }
  const Vec<D>& indenter_force() const { return indenter_force_; }
  double force_seconds() const { return force_seconds_; }  // the model's bond loops
  double contact_seconds() const { return contact_seconds_; }  // short-range contact (LAMMPS times it in "Pair" too)
  std::int64_t bond_evaluations() const { return bond_evaluations_; }

 private:
  PdSetup<D>& s_;
  std::vector<double> energy_;
  std::int64_t broken_sides_ = 0, contact_pairs_ = 0, bond_evaluations_ = 0;
  Vec<D> indenter_force_ = Vec<D>::Zero();
  double force_seconds_ = 0.0, contact_seconds_ = 0.0;
};

}  // namespace pdmpm::sim
