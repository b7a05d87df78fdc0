#pragma once
// A 2D steel plate for hybrid tests and gates: one scene text read as a PD body
// (lps_plastic) and as MPM settings (j2), the MPM simulation built on the PD body's
// particle store, and the hybrid over both.
#include <memory>
#include <string>
#include <vector>

#include "solver/hybrid/simulation.hpp"
#include "solver/sim/pd_setup.hpp"
#include "verification/support/scene_text.hpp"

namespace pdmpm::test {

// E = 200 GPa, ν = 0.3, ρ = 7850 kg/m³, σ_y = 250 MPa, E_t = 2 GPa, plane stress,
// Δx = 1 mm, δ = 3.015Δx.
struct HybridPlate {
  std::vector<double> size{0.03, 0.015};
  std::string tables;            // both methods: boundaries, …
  std::string pd_tables;         // PD only: pre-cracks
  std::string material_keys;     // both methods
  std::string pd_material_keys;  // PD only: critical_stretch
  std::string hardening = "yield_stress = 250e6\ntangent_modulus = 2e9";

  // The scene as the PD body ("pd") or the MPM settings ("mpm") read it.
  io::Scene scene(const std::string& method) const;
};

struct HybridBody {
  sim::PdSetup<2> pd_setup;
  std::unique_ptr<pd::Simulation<2>> pd;
  std::unique_ptr<mpm::Simulation<2>> mpm;
  std::unique_ptr<hybrid::Simulation<2>> hybrid;

  explicit HybridBody(const hybrid::Settings& settings, const HybridPlate& plate = {});
  core::Particles<2>& particles() { return pd_setup.system.particles; }
};

// A hybrid scene as text: a 30 × 20 mm plate (Δx = 1 mm, δ = 3Δx) of lps_plastic + J2
// with an edge pre-crack, pulled apart at its top and bottom edges; `hybrid_keys` are the
// [hybrid] table's lines.
SceneText hybrid_plate_scene(const std::string& hybrid_keys, const std::string& time = "steps = 200");

}  // namespace pdmpm::test
