#pragma once
// Stress around a circular hole of radius a in a plate under remote uniaxial
// tension σ along y (docs/verification/analytic_solutions.md: the δ-convergence reference for peak stress).
//  Kirsch (1898), infinite plate, polar (r, θ) with θ measured from the load axis:
//   σ_rr = σ/2 (1 − a²/r²) + σ/2 (1 − 4a²/r² + 3a⁴/r⁴) cos 2θ
//   σ_θθ = σ/2 (1 + a²/r²) − σ/2 (1 + 3a⁴/r⁴) cos 2θ
//   σ_rθ = −σ/2 (1 + 2a²/r² − 3a⁴/r⁴) sin 2θ
//  so σ_θθ = 3σ at the hole's edge across the load (K_t = 3), for any ν.
//  Finite width W (hole diameter d = 2a on the centre line, long plate), two
//  standard fits of Howland's (1930) series solution, both as net-section factors
//  K_tn = σ_max / σ_net, σ_net = σ W / (W − d):
//   Heywood (1952):             K_tn = 2 + (1 − d/W)³
//   Roark table 17.1 / Peterson: K_tn = 3 − 3.13 (d/W) + 3.66 (d/W)² − 1.53 (d/W)³
//  The gross-section factor (what a plate pulled by σ sees) is K_tn / (1 − d/W).
#include <array>

namespace pdmpm::analytic {

struct Kirsch {
  double radius = 1.0;  // a
  double stress = 1.0;  // remote σ (along y)

  // Polar components (σ_rr, σ_θθ, σ_rθ) at r ≥ a, θ from the y axis.
  std::array<double, 3> polar(double r, double theta) const;
  // Cartesian (σ_xx, σ_yy, σ_xy) at the point (x, y), hole centred at the origin.
  std::array<double, 3> cartesian(double x, double y) const;
};

enum class WidthCorrection { heywood, roark };

// Gross-section stress concentration factor σ_max / σ of a long plate of width W
// with a central hole of diameter d (0 ≤ d/W < 1).
double finite_width_kt(double d_over_w, WidthCorrection fit);

}  // namespace pdmpm::analytic
