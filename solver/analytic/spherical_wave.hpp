#pragma once
// Outgoing spherical elastic wave from a cavity of radius r₀ whose wall moves
// radially as g(t) = w₀ sin(2πt/T) for t ≥ 0 (SPEC §9, seed 001 §9).
// Potential φ = F(τ)/r, τ = t − (r − r₀)/c_p, u_r = −F'(τ)/(c_p r) − F(τ)/r²,
// with F' + (c_p/r₀) F = −c_p r₀ g(t), F(t ≤ 0) = 0, integrated in closed form:
//   F(t) = −c_p r₀ w₀ [a sin ωt − ω cos ωt + ω e^{−at}] / (a² + ω²),  a = c_p/r₀, ω = 2π/T.
namespace pdmpm::analytic {

struct SphericalWave {
  double r0 = 0.01;         // cavity radius (m)
  double period = 1e-5;     // T (s)
  double amplitude = 1e-4;  // w₀ (m)
  double cp = 0.0;          // P-wave speed √((λ + 2G)/ρ) (m/s)

  // F, F', F'' at retarded time τ (zero for τ ≤ 0).
  double F(double tau) const;
  double dF(double tau) const;
  double d2F(double tau) const;
  double radial_displacement(double r, double t) const;
  double radial_velocity(double r, double t) const;
};

}  // namespace pdmpm::analytic
