#pragma once
// Boundary conditions on particle regions, applied by the time integrators.
// Kinematic conditions (fixed, displacement, velocity, analytic) set u and v of
// their particles' constrained components (PD particles only: in the hybrid the
// grid constrains the MPM ones); tractions add a force density
// σ / layer to the particles of the loaded layer.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "solver/bc/analytic_field.hpp"
#include "solver/bc/expression.hpp"
#include "solver/core/particles.hpp"

namespace pdmpm::bc {

enum class ConstraintKind { fixed, displacement, velocity, analytic };

template <int D>
struct Constraint {
  std::string name;
  ConstraintKind kind = ConstraintKind::fixed;
  std::vector<Index> particles;
  std::array<bool, D> active{};                   // which components are prescribed
  std::array<Expression, D> value;                // displacement or velocity per component
  std::shared_ptr<const AnalyticField<D>> field;  // analytic
};

template <int D>
struct Traction {
  std::string name;
  std::vector<Index> particles;
  std::array<Expression, D> value;  // Pa, per component
  double layer = 0.0;               // thickness of the loaded layer (m)
};

template <int D>
class Boundaries {
 public:
  std::vector<Constraint<D>> constraints;
  std::vector<Traction<D>> tractions;

  // Per particle and component: 1 if some constraint prescribes it. Build once
  // after the constraints are added.
  void finalise(Index n_real);
  bool constrained(Index i, int a) const { return mask_[static_cast<std::size_t>(i) * D + a] != 0; }
  const std::vector<std::uint8_t>& mask() const { return mask_; }

  // Velocity-prescribed components get v(t); displacement-type ones u(t), v(t).
  void apply_velocity(core::Particles<D>& p, double t) const;
  void apply_displacement(core::Particles<D>& p, double t, double dt) const;
  // Adds the traction force densities at time t to p.b.
  void add_tractions(core::Particles<D>& p, double t) const;

 private:
  std::vector<std::uint8_t> mask_;
};

}  // namespace pdmpm::bc
