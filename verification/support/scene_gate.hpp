#pragma once
// Helpers for gates that run a scene file the way users do (sim::run_scene:
// history.csv, summary.json, fields.h5) and show its fields in the report.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "solver/io/scene.hpp"
#include "verification/support/fields_reader.hpp"
#include "verification/support/raster_image.hpp"

namespace pdmpm::test {

// <source>/verification/scenes/<name>
std::string scene_file(const std::string& name);

struct GateRun {
  nlohmann::json summary;
  std::filesystem::path dir;  // results/work/<problem>/<tag>
  FieldsReader fields() const { return FieldsReader((dir / "fields.h5").string()); }
  // One column of history.csv by its header name (throws if there is none).
  std::vector<double> history(const std::string& column) const;
};

// Runs the scene quietly into results/work/<problem>/<tag>; fails the test (and
// throws) if the run does not complete.
GateRun run_for_gate(const io::Scene& scene, const std::string& problem, const std::string& tag);

// Writes the raster to results/data/<problem>/<name>.png and records it as an image item.
void record_image(const std::string& problem, const std::string& name, const Raster& img, const std::string& title,
                  const std::string& caption);

// Reference positions (x, y) and damage of a 2D frame.
struct Frame2d {
  std::vector<std::array<double, 2>> x0;
  std::vector<double> damage;
  double time = 0.0;
};
Frame2d read_frame_2d(const FieldsReader& f, const FrameInfo& frame);

// Damage map of a 2D frame with the crack paths of summary.metrics.crack drawn over it
// (black dots: the tip positions up to the frame's time; white squares: the origins).
Raster damage_with_paths(const Frame2d& frame, const nlohmann::json& crack, double dx, int pixels_per_cell);

// Σ|φ_i − φ_m(i)| / Σ φ_i over the particles whose mirror m(i) (about the line
// x[axis] = position) is a particle too: 0 for a symmetric damage field.
// Records the "02_cracks" table of a problem: every crack path with ≥ 5 cracked
// particles (origin, start, tip, chord angle, max speed) next to the Rayleigh speed.
void record_crack_table(const std::string& problem, const nlohmann::json& crack, double rayleigh_speed,
                        const std::string& caption);

double mirror_asymmetry(const Frame2d& frame, int axis, double position, double dx);

}  // namespace pdmpm::test
