#pragma once
// Initial conditions ([[initial]] tables): velocity and/or displacement of a set
// of particles at t = 0, from expressions of the reference position x, y, z.
// Conditions apply in order, so a later one overwrites the components an earlier
// one set on the particles they share; a component without an expression ("free")
// is left as it is. The setups apply them before the first force evaluation, and
// boundary conditions act on top at t = 0 (a constrained component takes the
// boundary's value).
#include <array>
#include <optional>
#include <utility>
#include <vector>

#include "solver/bc/expression.hpp"
#include "solver/core/particles.hpp"

namespace pdmpm::bc {

template <int D>
struct InitialCondition {
  std::vector<Index> particles;                                     // real particles
  std::array<std::optional<Expression>, D> velocity, displacement;  // per component; empty: left alone
};

// Sets v and u of each condition's particles: u moves a particle to x = X + u, its
// reference position X stays.
template <int D>
void apply_initial_conditions(const std::vector<InitialCondition<D>>& conditions, core::Particles<D>& p);

// Central-difference step of initial_displacement_gradients, in lattice spacings.
// Truncation (h k)²/6 is ≲ 1e-8 relative for a wave resolved by four spacings
// (k = 2π/4Δx); rounding (of X ± h and of u) is ≈ ε_mach |X| / h relative,
// ≲ 1e-9 within a thousand spacings of the origin: both far below any strain a
// run resolves.
constexpr double kGradientStep = 1e-4;

// The displacement gradient ∂u_a/∂X_b at each particle an initial displacement
// reaches, ascending by particle: row a from the condition that set u_a last, by
// central differences of its expression with step kGradientStep × Δx (in x, y, z;
// an expression is not differentiated symbolically); rows of components no
// condition set are zero.
template <int D>
std::vector<std::pair<Index, Mat<D>>> initial_displacement_gradients(const std::vector<InitialCondition<D>>& conditions,
                                                                     const core::Particles<D>& p);

}  // namespace pdmpm::bc
