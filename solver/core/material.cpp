#include "solver/core/material.hpp"

namespace pdmpm::core {

int dimension(Setting s) {
  switch (s) {
    case Setting::bar1d:
    case Setting::uniaxial_strain: return 1;
    case Setting::plane_stress:
    case Setting::plane_strain: return 2;
    case Setting::solid3d: return 3;
  }
  return 0;
}

double Elastic::isotropic_energy_coefficient(Setting s) const {
  switch (s) {
    case Setting::bar1d: return 0.5 * E;                                    // ½ E s²
    case Setting::uniaxial_strain: return 0.5 * (lame() + 2.0 * shear());   // ½ (λ + 2G) s²
    case Setting::plane_stress: return E / (1.0 - nu);                      // E s² / (1 − ν)
    case Setting::plane_strain: return E / ((1.0 + nu) * (1.0 - 2.0 * nu));  // 2(λ + G) s²
    case Setting::solid3d: return 1.5 * E / (1.0 - 2.0 * nu);               // Deryugin et al. 2023 eq 4.5
  }
  return 0.0;
}

double Elastic::wave_modulus(Setting s) const {
  switch (s) {
    case Setting::bar1d: return E;
    case Setting::plane_stress: return E / (1.0 - nu * nu);
    case Setting::uniaxial_strain:
    case Setting::plane_strain:
    case Setting::solid3d: return lame() + 2.0 * shear();
  }
  return E;
}

}  // namespace pdmpm::core
