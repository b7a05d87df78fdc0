#pragma once
// Bond constants of docs/models/pmb.md and docs/models/lps.md, derived in closed form.
//   I_n = ∫₀^δ ω(r) rⁿ dr (influence moments)
//   PMB micromodulus c from W_PD = W_classical under isotropic expansion:
//     3D  c = 3E / (2π(1−2ν) I₃)          2D plane stress c = 2E / ((1−ν) π h I₂)
//     1D  c = E / (A I₁)                   2D plane strain c = 2E / ((1+ν)(1−2ν) π h I₂)
//   LPS continuum weighted volume m = ∫_H ω r² dV: 3D 4π I₄, 2D 2π h I₃, 1D 2 A I₂.
//   Critical stretch from fracture energy G₀ (energy of all bonds crossing a unit
//   crack area at s = s₀): 3D G₀ = (π c s₀²/2) I₄, 2D G₀ = c s₀² h I₃, 1D G₀ = (c s₀² A/2) I₂.
#include "solver/pd/influence.hpp"
#include "solver/core/material.hpp"

namespace pdmpm::pd {

double influence_moment(Influence w, int n, double delta);
double pmb_micromodulus(Influence w, core::Setting s, const core::Elastic& m, double delta, double measure);
double lps_weighted_volume(Influence w, core::Setting s, double delta, double measure);
double critical_stretch(Influence w, core::Setting s, const core::Elastic& m, double fracture_energy, double delta, double measure);

// Coefficients of the state-based force scalar t = (A θ ω|ξ| + B ω e) / m and
// energy W = ½ κ θ² + (B / 2m) Σ ω (e − γ θ |ξ|)² V  (docs/models/lps.md; 1D has no volumetric part).
struct LpsCoefficients {
  double A, B, kappa, gamma;
  int d;  // dimension in θ = (d/m) Σ ω |ξ| e V
};
LpsCoefficients lps_coefficients(core::Setting s, const core::Elastic& m);

// Madenci & Oterkus constants (docs/models/lps.md), for cross-checking the same model.
struct MadenciOterkus {
  double a, b, d;
};
MadenciOterkus madenci_oterkus(core::Setting s, const core::Elastic& m, double delta, double measure);

}  // namespace pdmpm::pd
