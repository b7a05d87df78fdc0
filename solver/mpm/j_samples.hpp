#pragma once
// Material points as samples of the J-integral's domain form (solver/core/j_integral.hpp;
// docs/verification/j_integral.md): ∂u/∂X = F − I, P = τ F⁻ᵀ, and W the law's elastic energy plus
// the plastic work of a monotonic path to ε̄_p under linear hardening, σ_y ε̄_p + ½ H ε̄_p² — the
// deformation-theory energy for which J of an elastoplastic body is defined (Rice 1968).
#include <optional>
#include <vector>

#include "solver/core/j_integral.hpp"
#include "solver/mpm/simulation.hpp"

namespace pdmpm::mpm {

// σ_y ε̄ + ½ H ε̄² of the J2 law (0 for the elastic laws).
double monotonic_plastic_work(const Material& m, double eq_plastic_strain);

// The sample of particle i; none if it has failed (it carries no stress).
std::optional<core::JSample> j_sample(const Simulation<2>& sim, Index i);

// Samples of the particles the step integrates within `radius` of `centre` (reference positions).
std::vector<core::JSample> j_samples(const Simulation<2>& sim, const Vec<2>& centre, double radius);

}  // namespace pdmpm::mpm
