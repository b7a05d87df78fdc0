#include "solver/pd/material.hpp"

namespace pdmpm::pd {

std::string_view name(Setting s) {
  switch (s) {
    case Setting::bar1d: return "1d";
    case Setting::plane_stress: return "plane_stress";
    case Setting::plane_strain: return "plane_strain";
    case Setting::solid3d: return "3d";
  }
  return "?";
}

double Elastic::isotropic_energy_coefficient(Setting s) const {
  switch (s) {
    case Setting::bar1d: return 0.5 * E;                                  // ½ E s²
    case Setting::plane_stress: return E / (1.0 - nu);                     // E s² / (1 − ν)
    case Setting::plane_strain: return E / ((1.0 + nu) * (1.0 - 2.0 * nu)); // 2(λ + G) s²
    case Setting::solid3d: return 1.5 * E / (1.0 - 2.0 * nu);              // Deryugin et al. 2023 eq 4.5
  }
  return 0.0;
}

double Elastic::longitudinal_modulus(Setting s) const {
  switch (s) {
    case Setting::bar1d: return E;
    case Setting::plane_stress: return E / (1.0 - nu * nu);
    case Setting::plane_strain:
    case Setting::solid3d: return lame() + 2.0 * shear();
  }
  return 0.0;
}

}  // namespace pdmpm::pd
