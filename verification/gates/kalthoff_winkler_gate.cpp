// Kalthoff–Winkler edge-impact test (verification/scenes/kalthoff_winkler.toml says
// which parameters are taken and from where). Kalthoff & Winkler (1987) observed
// brittle cracks leaving the notch tips at about 70° to the notch line; numerical
// studies of the test find 60°–72° (issue 5's band). Fast: the scene's Δx = 0.5 mm;
// full: Δx = 0.25 mm, to show the angle does not hinge on the resolution.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "solver/io/scene.hpp"
#include "verification/support/gate.hpp"
#include "verification/support/scene_gate.hpp"

namespace pdmpm {
namespace {

using nlohmann::json;
const char* problem = "kalthoff_winkler";
const char* source = "[kalthoff-winkler1988]; [kalthoff2000]";

void run_case(double spacing, const std::string& tag) {
  auto scene = io::parse_scene(test::scene_file("kalthoff_winkler.toml"));
  const double scale = spacing / scene.spacing;
  scene.spacing = spacing;
  scene.delta *= scale;
  // The impacted column and the excluded layer scale with Δx.
  scene.boundaries.at(0).region.at(0).max[0] = spacing;
  scene.crack.exclude.at(0).max[0] = 4.0 * spacing;
  const auto run = test::run_for_gate(scene, problem, tag);
  const json& crack = run.summary.at("metrics").at("crack");
  const double cR = crack.at("rayleigh_speed").get<double>();
  // Speed resolution as a fraction of c_R: one lattice site over the fit window.
  const double resolution = spacing / (crack.at("speed_window").get<double>() * cR);

  // The crack from the notch tip (50, 25) mm: the longest one starting within 10 mm of it.
  const json* main = nullptr;
  for (const auto& c : crack.at("cracks")) {
    const double d = std::hypot(c.at("origin")[0].get<double>() - 0.050, c.at("origin")[1].get<double>() - 0.025);
    if (d <= 0.010 && (!main || c.at("extent").get<double>() > main->at("extent").get<double>())) main = &c;
  }
  ASSERT_NE(main, nullptr) << "no crack left the notch tip";
  const double angle = main->at("angle_deg").get<double>();  // notch line = +x
  const std::string at = " (Δx = " + std::to_string(spacing * 1e3).substr(0, 4) + " mm)";
  test::record_gate({.id = "kalthoff_winkler.crack_angle." + tag,
                     .claim = "the crack from the notch tip shall run at 60°–72° to the notch line (chord origin → tip)" + at, .measured = angle,
                     .expected = 66.0, .tolerance = 6.0, .compare = test::Compare::abs,
                     .tolerance_reason = "issue 5's band 60°–72°: Kalthoff & Winkler measured about 70°; simulations of the test spread over the band",
                     .source = source, .unit = "°", .problem = problem});
  test::record_gate({.id = "kalthoff_winkler.crack_speed." + tag,
                     .claim = "the crack shall not outrun the Rayleigh wave speed beyond the speed measurement's resolution" + at,
                     .measured = main->at("max_speed").get<double>(), .expected = cR * (1.0 + resolution), .tolerance = 0.0, .compare = test::Compare::at_most,
                     .tolerance_reason = "mode-I cracks cannot outrun Rayleigh waves (Freund 1990); the tip is known to one lattice site and "
                     "the speed is fitted over W = 10 Δx / c_R, so one site is worth 10 % of c_R",
                     .source = "[freund1990] §5; [rayleigh1885]", .unit = "m/s", .problem = problem});

  json rows = json::array();
  auto opt = [](const json& v) { return v.is_null() ? json("—") : v; };
  rows.push_back({"first bond failure within δ of the notch tip [s]", opt(crack.at("locations").at("notch_tip").at("first_bond_failure"))});
  rows.push_back({"crack initiation (φ ≥ ½ outside the notch) [s]", opt(crack.at("initiation_time"))});
  rows.push_back({"crack angle to the notch line [°]", angle});
  rows.push_back({"crack tip at the end [mm]", std::to_string(main->at("tip")[0].get<double>() * 1e3).substr(0, 5) + ", " +
                                                   std::to_string(main->at("tip")[1].get<double>() * 1e3).substr(0, 5)});
  rows.push_back({"max crack speed [m/s]", main->at("max_speed")});
  rows.push_back({"Rayleigh speed [m/s]", cR});
  rows.push_back({"particles", run.summary.at("particles")});
  rows.push_back({"steps", run.summary.at("steps")});
  test::record_data(problem, "01_" + tag,
                    {{"kind", "table"}, {"title", "Kalthoff–Winkler" + at}, {"columns", {"quantity", "value"}}, {"rows", rows},
                     {"caption", "Upper half of the plate (mirror plane y = 0). Experiment: about 70°."}});
  json series = json::array({{{"label", "crack path" + at}, {"x", main->at("path").at("x")}, {"y", main->at("path").at("y")},
                              {"style", "line"}},
                             {{"label", "notch"}, {"x", {0.0, 0.050}}, {"y", {0.025, 0.025}}, {"style", "line"}},
                             {{"label", "70° from the notch tip"},
                              {"x", {0.050, 0.050 + 0.075 / std::tan(70.0 * std::acos(-1.0) / 180.0)}},
                              {"y", {0.025, 0.100}},
                              {"style", "dashed"}}});
  test::record_data(problem, "02_path_" + tag,
                    {{"kind", "plot"}, {"title", "Crack tip path" + at}, {"xlabel", "x [m]"}, {"ylabel", "y [m]"},
                     {"xscale", "linear"}, {"yscale", "linear"}, {"series", series},
                     {"caption", "Tip positions at every history sample."}});
  const auto fields = run.fields();
  std::vector<test::Raster> cells;
  std::string when;
  for (const auto& f : fields.frames())
    if (f.step > 0) {
      cells.push_back(test::damage_with_paths(test::read_frame_2d(fields, f), crack, spacing, spacing < 0.4e-3 ? 1 : 2));
      when += (when.empty() ? "" : ", ") + std::to_string(f.time * 1e6).substr(0, 4);
    }
  test::record_image(problem, "03_damage_" + tag, test::grid(cells, static_cast<int>(cells.size())), "Damage and crack path" + at,
                     "t = " + when + " µs. Upper half of the plate; impact on the left edge below the notch (y < 25 mm). "
                     "Colour: φ from 0 (dark blue) to 1 (dark red); black dots: crack tip positions at every history sample; white: origins.");
}

TEST(FastKalthoffWinkler, CrackAngle) { run_case(0.5e-3, "dx0.5mm"); }
TEST(FullKalthoffWinkler, CrackAngleFiner) { run_case(0.25e-3, "dx0.25mm"); }

}  // namespace
}  // namespace pdmpm
