#pragma once
// The fixed, non-affine configurations whose forces are kept as regression gold
// (reference_data/regression_forces.h5): for every model × setting × influence
// function, a small lattice block with a partial edge crack (bonds cut) and a
// smooth non-affine displacement of strain ~1e-3. The regold tool writes what
// compute() returns; the regression gate recomputes and compares.
#include <string>
#include <vector>

#include "solver/pd/influence.hpp"
#include "solver/core/material.hpp"

namespace pdmpm::test::regression {

struct Case {
  std::string model;
  core::Setting setting = core::Setting::solid3d;
  pd::Influence influence = pd::Influence::constant;
  std::string group() const;  // "/pmb/3d/constant"
  int dimension() const { return core::dimension(setting); }
};

// Every registered model × 4 settings × 7 influence functions.
std::vector<Case> cases();

struct Result {
  int particles = 0, dimension = 0;
  std::vector<double> force;       // particles × dimension, N/m³
  std::vector<double> energy;      // strain energy density, J/m³
  std::vector<double> dilatation;  // θ
  long broken_bond_sides = 0;
};

Result compute(const Case& c);

// One-line description stored with the gold file.
std::string describe();

}  // namespace pdmpm::test::regression
