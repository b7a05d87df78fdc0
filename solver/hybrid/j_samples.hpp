#pragma once
// The particles of a hybrid body (MPM, transition and PD alike) as samples of the
// J-integral's domain form (solver/core/j_integral.hpp; docs/verification/j_integral.md).
// Every particle is read through MPM's material law, so the three modes of a run measure J
// the same way whichever method carries the ring:
//   MPM, transition  F and τ of the material point;
//   PD               F from the live bonds and the plastic state fitted from the bond plastic
//                    extensions — what a conversion to MPM would give it (conversion.hpp) —
//                    then τ from the law (the point's own state is left untouched);
// P = τ F⁻ᵀ, ∂u/∂X = F − I. W is the elastic energy of the law plus the plastic work of a
// monotonic path to the particle's ε̄_p under linear hardening, σ_y ε̄_p + ½ H ε̄_p²: the
// deformation-theory energy for which J of an elastoplastic body is defined (Rice 1968),
// and the same for both methods (PD keeps no per-particle plastic work). Skipped: removed
// and failed particles, and PD particles whose live bonds no longer determine F (the crack) or
// give an inverted one.
#include <vector>

#include "solver/core/j_integral.hpp"
#include "solver/hybrid/simulation.hpp"

namespace pdmpm::hybrid {

// Samples of the real particles within `radius` of `centre` (reference positions).
std::vector<core::JSample> j_samples(const Simulation<2>& h, const Vec<2>& centre, double radius);

}  // namespace pdmpm::hybrid
