#pragma once
// Outgoing spherical elastic wave from a cavity of radius r₀ whose wall moves
// radially as g(t) = w₀ sin(2πt/T) for t ≥ 0 (docs/verification/analytic_solutions.md, Deryugin et al. 2023 §9). The source
// runs on for all t > 0: Deryugin et al. 2023 gives an oscillation period and amplitude and
// no duration, and its end time is 7 periods.
// Potential φ = F(τ)/r, τ = t − (r − r₀)/c_p, u_r = −F'(τ)/(c_p r) − F(τ)/r²,
// with F' + (c_p/r₀) F = −c_p r₀ g(t), F(t ≤ 0) = 0, integrated in closed form:
//   F(t) = −c_p r₀ w₀ [a sin ωt − ω cos ωt + ω e^{−at}] / (a² + ω²),  a = c_p/r₀, ω = 2π/T.
// Inside the cavity (r < r₀) the solution is not defined; there the field is
// continued by the homogeneous radial expansion u_r = g(t) r / r₀, which meets
// the wall motion at r = r₀ and is zero at t = 0. (Lattice points inside the
// source that carry a prescribed displacement use it.)
namespace pdmpm::analytic {

struct SphericalWave {
  double r0 = 0.01;         // cavity radius (m)
  double period = 1e-5;     // T (s)
  double amplitude = 1e-4;  // w₀ (m)
  double cp = 0.0;          // P-wave speed √((λ + 2G)/ρ) (m/s)

  // Wall motion g(t) and its rate (zero for t ≤ 0).
  double source(double t) const;
  double source_rate(double t) const;
  // F, F', F'' at retarded time τ (zero for τ ≤ 0).
  double F(double tau) const;
  double dF(double tau) const;
  double d2F(double tau) const;
  double radial_displacement(double r, double t) const;
  double radial_velocity(double r, double t) const;
  // Radius the wave front has reached at time t.
  double front(double t) const { return r0 + cp * t; }
};

}  // namespace pdmpm::analytic
