// The shared material vocabulary: moduli, wave moduli per setting and the name tables.
#include "solver/core/material.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace pdmpm::core {
namespace {

const Elastic kSteel{200e9, 0.3, 7800.0};

TEST(Elastic, ModuliAgreeWithEachOther) {
  const double G = kSteel.shear(), K = kSteel.bulk(), lambda = kSteel.lame();
  EXPECT_NEAR(K, lambda + 2.0 * G / 3.0, 1e-12 * K);                       // K = λ + 2G/3
  EXPECT_NEAR(kSteel.E, 9.0 * K * G / (3.0 * K + G), 1e-12 * kSteel.E);    // E = 9KG/(3K + G)
  EXPECT_NEAR(kSteel.bulk_2d(Setting::plane_strain), lambda + G, 1e-12 * K);
}

TEST(Elastic, WaveModulusIsThePlaneWaveStiffnessOfEachSetting) {
  const double E = kSteel.E, nu = kSteel.nu;
  const double M = kSteel.lame() + 2.0 * kSteel.shear();
  EXPECT_DOUBLE_EQ(kSteel.wave_modulus(Setting::bar1d), E);
  EXPECT_DOUBLE_EQ(kSteel.wave_modulus(Setting::plane_stress), E / (1.0 - nu * nu));
  for (Setting s : {Setting::uniaxial_strain, Setting::plane_strain, Setting::solid3d})
    EXPECT_DOUBLE_EQ(kSteel.wave_modulus(s), M) << name(s);
  // Uniaxial strain and 3D share the P-wave modulus E(1 − ν)/((1 + ν)(1 − 2ν)).
  EXPECT_NEAR(M, E * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu)), 1e-12 * M);
}

TEST(Elastic, IsotropicEnergyCoefficientIsHalfTheIsotropicStiffness) {
  // W = ½ ε:C:ε with ε = s·I over the setting's dimensions.
  // 1e-14: the formulas differ only in the order of rounding.
  const double lambda = kSteel.lame(), G = kSteel.shear(), tol = 1e-14 * kSteel.E;
  EXPECT_NEAR(kSteel.isotropic_energy_coefficient(Setting::solid3d), 0.5 * (9.0 * lambda + 6.0 * G), tol);
  EXPECT_NEAR(kSteel.isotropic_energy_coefficient(Setting::plane_strain), 0.5 * (4.0 * lambda + 4.0 * G), tol);
  EXPECT_NEAR(kSteel.isotropic_energy_coefficient(Setting::uniaxial_strain), 0.5 * (lambda + 2.0 * G), tol);
}

TEST(J2Hardening, PlasticModulusOfTheBilinearCurve) {
  // Uniaxial: dσ/dε = E_t beyond yield ⇔ 1/E_t = 1/E + 1/H.
  const J2Hardening h{340e6, 1.45e9};
  const double H = h.hardening_modulus(kSteel.E);
  EXPECT_NEAR(1.0 / h.tangent_modulus, 1.0 / kSteel.E + 1.0 / H, 1e-12 / h.tangent_modulus);
  EXPECT_EQ(J2Hardening{}.hardening_modulus(kSteel.E), 0.0);  // perfect plasticity
}

TEST(Setting, DimensionsAndNames) {
  EXPECT_EQ(dimension(Setting::bar1d), 1);
  EXPECT_EQ(dimension(Setting::uniaxial_strain), 1);
  EXPECT_EQ(dimension(Setting::plane_stress), 2);
  EXPECT_EQ(dimension(Setting::plane_strain), 2);
  EXPECT_EQ(dimension(Setting::solid3d), 3);
  EXPECT_EQ(name(Setting::bar1d), "1d");
  EXPECT_EQ(name(Setting::solid3d), "3d");
}

TEST(NamedEnum, EveryNameRoundTripsAndUnknownNamesAreRefusedWithTheList) {
  for (Setting s : enum_values<Setting>()) EXPECT_EQ(find_enum<Setting>(name(s)), s);
  for (FailureRule r : enum_values<FailureRule>()) EXPECT_EQ(parse_enum<FailureRule>(name(r), "f", "k"), r);
  EXPECT_FALSE(find_enum<Setting>("Plane_stress").has_value());  // case matters
  EXPECT_EQ(enum_names<FailureRule>(), "strain, accumulated");
  try {
    (void)parse_enum<FailureRule>("sudden", "scene.toml", "material.failure.rule");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "material.failure.rule");
    EXPECT_NE(std::string(e.what()).find("must be one of strain, accumulated; got \"sudden\""), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace pdmpm::core
