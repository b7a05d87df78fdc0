#pragma once
// The bond constants of constants.hpp computed a second, independent way: by
// adaptive quadrature (GSL QAGS) of the integrals they are defined by, written
// over the horizon itself, not through the moments I_n. Used to verify the
// closed forms, and usable for influence functions that have none.
//
//   PMB energy density   W = ½ ∫_H ½ c ω(|ξ|) s² |ξ| dV,  s = n·ε·n (small strain),
//                        c solved from W = W_classical for ε = s·1.
//   LPS weighted volume  m = ∫_H ω |ξ|² dV.
//   Fracture energy      G₀ = energy of every bond crossing a unit crack area when
//                        each is at s₀ (bond energy ½ c ω s₀² |ξ| per unit volume²),
//                        nested over the distance z of a point from the crack plane,
//                        the bond length ξ ≥ z and the bond angle (Silling & Askari
//                        2005 §4, with ω(ξ) kept inside); s₀ solved from G₀.
//
// Horizon measure per setting: 1D A∫_{−δ}^{δ} dx; 2D h∫_0^{2π}∫_0^δ r dr dφ;
// 3D ∫_0^{2π}∫_0^π∫_0^δ r² sinθ dr dθ dφ (A = bar area, h = thickness: `measure`).
//
// Every GSL error (tolerance not reached, roundoff, divergence, …) comes back as
// a QuadratureError instead of GSL's default abort. GSL's error handler is
// process-wide: these functions install their own for the duration of a call,
// so do not call them concurrently with other code that relies on GSL's handler.
#include <Eigen/Core>
#include <cstddef>
#include <functional>

#include "solver/core/error.hpp"
#include "solver/pd/influence.hpp"
#include "solver/core/material.hpp"

namespace pdmpm::pd::quadrature {

class QuadratureError : public RunError {
 public:
  using RunError::RunError;
};

struct Options {
  double epsrel = 1e-12;     // requested relative error at every nesting level
  double epsabs = 0.0;       // requested absolute error (0: relative only)
  std::size_t limit = 1000;  // maximum subintervals per level
};

// A value with GSL's error estimate, propagated through nested integrals and
// through the algebra that solves for a constant (first order).
struct Estimate {
  double value = 0.0;
  double abserr = 0.0;
  double relerr() const;
};

using Strain = Eigen::Matrix3d;  // small strain; 2D settings use the xy block, 1D the xx entry
// f(r, n): r = |ξ| > 0, n = ξ/|ξ| a unit vector in the setting's line/plane/space.
using HorizonIntegrand = std::function<double(double r, const Eigen::Vector3d& n)>;

// ∫_a^b f(x) dx by QAGS (21-point Gauss–Kronrod, adaptive bisection with
// extrapolation; endpoints are never evaluated, so integrable endpoint
// singularities are fine).
Estimate integrate(const std::function<double(double)>& f, double a, double b, const Options& opt = {});

// ∫_H f dV over the horizon of radius δ in setting s.
Estimate integrate_horizon(core::Setting s, double delta, double measure, const HorizonIntegrand& f, const Options& opt = {});

// Isotropic small strain s·1 restricted to the setting's dimensions.
Strain isotropic_strain(core::Setting s, double stretch);

// PMB strain energy density for a small strain ε.
Estimate pmb_energy_density(Influence w, core::Setting s, double c, const Strain& eps, double delta, double measure,
                            const Options& opt = {});
// Micromodulus c from W_PD(c) = W_classical under isotropic expansion.
Estimate pmb_micromodulus(Influence w, core::Setting s, const core::Elastic& m, double delta, double measure,
                          const Options& opt = {});

// Continuum weighted volume m = ∫_H ω |ξ|² dV.
Estimate lps_weighted_volume(Influence w, core::Setting s, double delta, double measure, const Options& opt = {});
// Continuum LPS energy density for a small strain ε with weighted volume m
// (the kernel of lps.hpp with sums replaced by integrals):
//   θ = (d/m) ∫ ω |ξ| e dV,  W = ½ κ θ² + (B/2m) ∫ ω (e − γ θ |ξ|)² dV,  e = |ξ| n·ε·n.
Estimate lps_energy_density(Influence w, core::Setting s, const core::Elastic& mat, double m, const Strain& eps, double delta,
                            double measure, const Options& opt = {});

// Fracture energy of a PMB body with micromodulus c when every bond breaks at s₀.
Estimate fracture_energy(Influence w, core::Setting s, double c, double s0, double delta, double measure,
                         const Options& opt = {});
// s₀ from fracture_energy(c, s₀) = G₀, with c itself from pmb_micromodulus (quadrature).
Estimate critical_stretch(Influence w, core::Setting s, const core::Elastic& m, double G0, double delta, double measure,
                          const Options& opt = {});

}  // namespace pdmpm::pd::quadrature
