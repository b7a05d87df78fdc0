#pragma once
// Isotropic linear elastic constants and the kinematic setting they act in.
#include <string_view>

namespace pdmpm::pd {

// 1D bar, 2D plane stress / plane strain, or 3D. `measure` is the bar's
// cross-section area (1D, m²), the plate thickness (2D, m) or 1 (3D).
enum class Setting { bar1d, plane_stress, plane_strain, solid3d };

inline int dimension(Setting s) { return s == Setting::bar1d ? 1 : s == Setting::solid3d ? 3 : 2; }
std::string_view name(Setting s);

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
  // Energy density per s² under isotropic expansion ε = s·I (classical).
  double isotropic_energy_coefficient(Setting s) const;
  // P-wave (longitudinal) modulus of the setting: ρ c_p² for a plane wave.
  double longitudinal_modulus(Setting s) const;
};

}  // namespace pdmpm::pd
