#pragma once
// Scene TOML for tests and gates, so each writes only what it varies: one
// rectangular (2D) or box (3D) body of one material under one model, then the
// tables a test adds ([[boundary]], [[precrack]], [output], …) verbatim.
#include <string>
#include <vector>

#include "solver/io/scene.hpp"

namespace pdmpm::test {

struct SceneText {
  std::string id = "test";
  int dimension = 2;
  std::string plane = "stress";  // 2D: "stress" or "strain"
  double spacing = 1e-3;
  double horizon_ratio = 3.015;                         // 0: no horizon (MPM alone needs none)
  double thickness = 1e-3;                              // 2D plate thickness (1D: cross-section area)
  std::vector<double> min{0.0, 0.0}, max{0.03, 0.015};  // the body
  double density = 7850.0, youngs_modulus = 200e9;
  std::string poissons_ratio = "0.3";  // "" leaves it out (the model fixes ν)
  std::string material_keys;           // further [material] lines, e.g. "critical_stretch = 0.01"
  std::string model = "lps";
  std::string model_keys;          // further [model] lines
  std::string time = "steps = 1";  // the [time] table's lines
  std::string tables;              // everything after, verbatim

  std::string toml() const;
  io::Scene parse(const std::string& file = "test.toml") const;
};

// The [material] lines a model needs beyond the elastic constants, so that a loop
// over the model table can give every model the same scene: nothing for an elastic
// model; for a plastic one a yield stress no test in that loop reaches (1e30 Pa),
// so it answers as its elastic part.
std::string elastic_range_keys(const std::string& model);
// For a plastic model a yield stress of 1 MPa (any test strain above 5e-6 flows at
// E = 200 GPa) with E_t = E/100; nothing for an elastic model.
std::string flowing_keys(const std::string& model);
// The horizon ratio m = δ/Δx of the gates that loop over the model table: 3.015, but 2.015 for
// hpd in 3D. hpd's sub-horizon (the overlap of two horizons) holds ~50 points per bond at 3.015
// against ~10 at 2.015, so each 3D force evaluation costs ~15× more, and at 3.015 its 3D runs
// would add minutes to the fast tier; what those gates check (conservation, stability, patch,
// thread invariance) does not depend on m, and hpd's own tests cover m = 3.015.
double gate_horizon_ratio(const std::string& model, int dimension);

}  // namespace pdmpm::test
