#pragma once
// The J-integral of a 2D crack tip in its domain form (docs/verification/j_integral.md), over
// particles: Rice's contour integral J = ∫_Γ (W n₁ − t_i ∂u_i/∂x₁) dΓ turned into an area
// integral with a weight q that is 1 at the tip and 0 on an outer contour (the equivalent
// domain integral of Li, Shih & Needleman 1985, "A comparison of methods for calculating
// energy release rates", Eng. Fract. Mech. 21):
//   J = ∫_A (P_ij ∂u_i/∂X_k a_k − W a_j) ∂q/∂X_j dA,
// with a the unit vector of the crack's direction of growth, P the first Piola–Kirchhoff
// stress, W the stress work per reference volume and everything on the reference
// configuration (so it holds for finite strain; for an elastic or monotonically loaded
// elastoplastic body W is the energy density Rice's J uses). q falls linearly in r = |X − tip|
// from 1 at r_inner to 0 at r_outer; only particles in that ring contribute, so J does not
// need the field at the tip. The sum over particles replaces the integral: each particle
// stands for its volume V_p (per unit thickness, J in J/m² = N/m).
#include <vector>

#include "solver/core/types.hpp"

namespace pdmpm::core {

// What the integral needs of one particle.
struct JSample {
  Vec<2> X = Vec<2>::Zero();       // reference position (m)
  double volume = 0.0;             // V_p (m³)
  Mat<2> grad_u = Mat<2>::Zero();  // ∂u_i/∂X_j
  Mat<2> stress = Mat<2>::Zero();  // P_ij (Pa); the Cauchy stress for small strain
  double energy = 0.0;             // W (J/m³ of reference volume)
};

struct JDomain {
  Vec<2> tip = Vec<2>::Zero();
  Vec<2> direction = Vec<2>::UnitX();   // unit, along the crack's growth
  double r_inner = 0.0, r_outer = 0.0;  // 0 ≤ r_inner < r_outer (m)
  double thickness = 1.0;               // the volumes' thickness (m): J per unit length of front
};

struct JResult {
  double J = 0.0;       // J/m²
  Index particles = 0;  // particles in the ring r_inner < r < r_outer
};

// Throws std::invalid_argument for a ring with r_outer ≤ r_inner, a negative r_inner, a
// direction that is not a unit vector or a thickness ≤ 0.
JResult domain_j_integral(const std::vector<JSample>& samples, const JDomain& domain);

}  // namespace pdmpm::core
