// Von Mises stress, triaxiality and the ductile fracture strain of docs/models/planned.md.
#include "solver/mpm/stress_measures.hpp"

#include <gtest/gtest.h>

namespace pdmpm::mpm {
namespace {

TEST(StressMeasures, TriaxialityOfStandardStates) {
  Mat<3> s = Mat<3>::Zero();
  s(0, 0) = 100.0;  // uniaxial tension
  EXPECT_NEAR(von_mises(s), 100.0, 1e-12);
  EXPECT_NEAR(triaxiality(s), 1.0 / 3.0, 1e-15);
  s(1, 1) = 100.0;  // equibiaxial plane stress
  EXPECT_NEAR(triaxiality(s), 2.0 / 3.0, 1e-15);
  s.setZero();
  s(0, 1) = s(1, 0) = 50.0;  // pure shear
  EXPECT_NEAR(von_mises(s), 50.0 * std::sqrt(3.0), 1e-12);
  EXPECT_EQ(triaxiality(s), 0.0);
  s.setZero();
  s(0, 0) = -100.0;  // uniaxial compression
  EXPECT_NEAR(triaxiality(s), -1.0 / 3.0, 1e-15);
  EXPECT_EQ(triaxiality(Mat<3>::Zero()), 0.0);
  EXPECT_EQ(triaxiality(-5.0 * Mat<3>::Identity()), -1e12);  // hydrostatic: no finite η
}

TEST(StressMeasures, FractureStrain) {
  EXPECT_NEAR(fracture_strain(0.8, -1.5, 1.0 / 3.0), 0.8 * std::exp(-0.5), 1e-15);
}

}  // namespace
}  // namespace pdmpm::mpm
