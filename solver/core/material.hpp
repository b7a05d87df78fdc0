#pragma once
// The material vocabulary both methods read: the kinematic setting, isotropic
// linear elasticity, J2 hardening and the ductile failure criterion. PD models and
// MPM constitutive laws take these; a scene fills them once for either method.
#include <array>

#include "solver/core/named_enum.hpp"

namespace pdmpm::core {

// 1D: a bar under uniaxial stress (lateral faces free) or uniaxial strain (laterally
// confined; MPM only); 2D: plane stress (thin plate, thickness in the particle volume)
// or plane strain; 3D solid.
enum class Setting { bar1d, uniaxial_strain, plane_stress, plane_strain, solid3d };

constexpr std::array<EnumName<Setting>, 5> names(Setting) {
  return {{{Setting::bar1d, "1d"},
           {Setting::uniaxial_strain, "uniaxial_strain"},
           {Setting::plane_stress, "plane_stress"},
           {Setting::plane_strain, "plane_strain"},
           {Setting::solid3d, "3d"}}};
}

int dimension(Setting s);

struct Elastic {
  double E = 0.0;    // Young's modulus (Pa)
  double nu = 0.0;   // Poisson's ratio
  double rho = 0.0;  // density (kg/m³)

  double shear() const { return E / (2.0 * (1.0 + nu)); }
  double bulk() const { return E / (3.0 * (1.0 - 2.0 * nu)); }
  double lame() const { return E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)); }
  // In-plane bulk modulus κ₂ of the 2D models (Le, Chan & Schwartz 2014):
  // λ + G in plane strain, E / (2(1 − ν)) in plane stress.
  double bulk_2d(Setting s) const { return s == Setting::plane_stress ? E / (2.0 * (1.0 - nu)) : lame() + shear(); }
  // Energy density per s² under isotropic expansion ε = s·I of the setting's
  // dimensions (classical).
  double isotropic_energy_coefficient(Setting s) const;
  // P-wave modulus of the setting: ρ c_p² of the fastest plane elastic wave (the
  // stable step of either method, the wave speeds of the analytic solutions).
  double wave_modulus(Setting s) const;
};

// Von Mises plasticity with linear isotropic hardening: the uniaxial curve is
// bilinear, slope E to σ_y and E_t beyond.
struct J2Hardening {
  double yield_stress = 0.0;     // σ_y (Pa), > 0
  double tangent_modulus = 0.0;  // E_t (Pa), 0 ≤ E_t < E

  // Plastic (hardening) modulus in equivalent plastic strain: H = E·E_t / (E − E_t).
  double hardening_modulus(double E) const { return E * tangent_modulus / (E - tangent_modulus); }
};

// Failure rule of the ductile criterion ε_f = d₀ exp(c η) (Noorian et al. eqs 8–9).
// strain: fail when ε̄_p ≥ ε_f(η) at the current η (the reading docs/choices.md takes);
// accumulated: fail when ∫ dε̄_p / ε_f(η) ≥ 1 (path-dependent variant).
enum class FailureRule { strain, accumulated };

constexpr std::array<EnumName<FailureRule>, 2> names(FailureRule) {
  return {{{FailureRule::strain, "strain"}, {FailureRule::accumulated, "accumulated"}}};
}

struct DuctileFailure {
  bool enabled = false;
  double d0 = 0.0;  // > 0
  double c = 0.0;   // finite; usually < 0
  FailureRule rule = FailureRule::strain;
};

}  // namespace pdmpm::core
