#pragma once
// Linear elastic fracture mechanics references for the J-integral (docs/verification/j_integral.md).
//
// Centre crack of length 2a in a strip of width W under remote tension σ normal to the
// crack (Tada, Paris & Irwin, The Stress Analysis of Cracks Handbook, 3rd ed., 2000, §2.1;
// docs/references.md tada2000):
//   K_I = σ √(πa) F(α),  α = 2a/W,  F(α) = (1 − 0.025 α² + 0.06 α⁴) √(sec(πα/2)),
// Tada's fit of Isida's series, quoted there as accurate to 0.1 % for any α < 1 (an
// infinitely long strip). J = K_I² / E' with E' = E (plane stress), E / (1 − ν²) (plane strain).
//
// Williams' mode-I near-tip field (the leading term; tip at the origin, crack along −x):
//   u_x = K/(2G) √(r/2π) cos(θ/2) (κ − 1 + 2 sin²(θ/2)),
//   u_y = K/(2G) √(r/2π) sin(θ/2) (κ + 1 − 2 cos²(θ/2)),
//   σ_xx = K/√(2πr) cos(θ/2)(1 − sin(θ/2) sin(3θ/2)),
//   σ_yy = K/√(2πr) cos(θ/2)(1 + sin(θ/2) sin(3θ/2)),
//   σ_xy = K/√(2πr) cos(θ/2) sin(θ/2) cos(3θ/2),
// κ = (3 − ν)/(1 + ν) in plane stress, 3 − 4ν in plane strain (Anderson, Fracture
// Mechanics, 3rd ed., table 2.1 and 2.2). It is an exact elastic field, so the
// J-integral of any contour around the tip is K²/E'.
#include <array>

#include "solver/core/material.hpp"

namespace pdmpm::analytic {

// F(α) of the centre-cracked strip, 0 ≤ α = 2a/W < 1.
double centre_crack_factor(double alpha);
// K_I of a centre crack 2a in a strip of width W under remote σ (Pa √m).
double centre_crack_k1(double stress, double half_length, double width);
// E' of the setting: J = K_I² / E'.
double fracture_modulus(const core::Elastic& m, core::Setting s);

struct WilliamsModeOne {
  double k1 = 1.0;  // K_I (Pa √m)
  core::Elastic material;
  core::Setting setting = core::Setting::plane_stress;

  // Displacement (u_x, u_y) at (x, y), tip at the origin, crack faces along the negative x axis.
  std::array<double, 2> displacement(double x, double y) const;
  // Its gradient ∂u_i/∂x_j as (xx, xy, yx, yy), by differentiating the displacement.
  std::array<double, 4> displacement_gradient(double x, double y) const;
  // In-plane stress (σ_xx, σ_yy, σ_xy).
  std::array<double, 3> stress(double x, double y) const;
};

}  // namespace pdmpm::analytic
