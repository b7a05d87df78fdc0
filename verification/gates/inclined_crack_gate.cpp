// Square rock plate with a central 45° crack under biaxial edge tension (Gu & Zhou 2017
// §5.2, docs/verification/inclined_crack.md), at the paper's resolution (200 × 200 particles,
// Δt = 1.3367e-8 s). The paper: initiation at 3.99 µs; the lower wing branches by
// 9.31 µs; a through-crack, roughly along 45°, at 10.64 µs. The run goes on to
// 2000 steps (26.7 µs) so that this model's later events are measured.
//
// A bound worth knowing when reading the times: the loads start at the edges at
// t = 0 and the crack tips are 23 mm from the nearest edges, so no signal reaches
// them before 23 mm / c_p = 4.69 µs (c_p = 4899 m/s for this rock in plane strain;
// PD waves are not faster than c_p). An initiation at 3.99 µs cannot be reproduced
// with the loading as stated.
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
const char* problem = "inclined_crack";
const char* source = "[gu-zhou2017] §5.2 (fig. 5); docs/verification/inclined_crack.md";

const std::vector<double> paper_moments{3.99e-6, 9.31e-6, 10.64e-6};
const std::vector<double> later_moments{8e-6, 12e-6, 16e-6, 20e-6, 26.7e-6};

double opt(const json& v) { return v.is_null() ? std::nan("") : v.get<double>(); }

// Full tier: the seed-004 times are not reproduced by this model (see the closing note of
// issue 5 and reference_data/README.md); a failing reproduction is reported, not hidden,
// and CI's fast tier stays for gates the solver meets.
TEST(FullInclinedCrack, CracksAgainstSeed004) {
  auto scene = io::parse_scene(test::scene_file("inclined_crack.toml"));
  scene.time.steps = 2000;
  scene.output.every.reset();
  scene.output.frames.reset();
  scene.output.frame_times = paper_moments;
  scene.output.frame_times.insert(scene.output.frame_times.end(), later_moments.begin(), later_moments.end());
  const auto run = test::run_for_gate(scene, problem, "seed_resolution");
  const json& crack = run.summary.at("metrics").at("crack");
  const double dx = scene.spacing, cR = crack.at("rayleigh_speed").get<double>();

  const double t_init = opt(crack.at("initiation_time")), t_sep = opt(crack.at("separation_time"));
  const double angle = opt(crack.at("overall_angle_at_separation_deg"));
  double max_speed = 0.0;
  for (const auto& c : crack.at("cracks")) max_speed = std::max(max_speed, c.at("max_speed").get<double>());

  test::record_gate({.id = "inclined_crack.initiation_time",
                     .claim = "the wing cracks shall initiate (first particle with φ ≥ ½ outside the notch) within ±20 % of the paper's 3.99 µs",
                     .measured = t_init, .expected = 3.99e-6, .tolerance = 0.20, .compare = test::Compare::rel, .tolerance_reason = "issue 5 sets ±20 % for this seed's times", .source = source, .unit = "s", .problem = problem});
  test::record_gate({.id = "inclined_crack.through_crack_time",
                     .claim = "the plate shall be cut through (two pieces) within ±20 % of the paper's 10.64 µs", .measured = t_sep, .expected = 10.64e-6, .tolerance = 0.20,
                     .compare = test::Compare::rel, .tolerance_reason = "issue 5 sets ±20 % for this seed's times", .source = source, .unit = "s", .problem = problem});
  test::record_gate({.id = "inclined_crack.overall_direction",
                     .claim = "the through-crack's overall direction (principal axis of the cracked particles when the plate separates) "
                     "shall be within 15° of 45°",
                     .measured = angle, .expected = 45.0, .tolerance = 15.0, .compare = test::Compare::abs, .tolerance_reason = "issue 5 sets 15°", .source = source, .unit = "°", .problem = problem});
  const double resolution = dx / (crack.at("speed_window").get<double>() * cR);  // one site over the fit window, / c_R
  test::record_gate({.id = "inclined_crack.crack_speed",
                     .claim = "no crack shall outrun the Rayleigh wave speed beyond the speed measurement's resolution", .measured = max_speed,
                     .expected = cR * (1.0 + resolution), .tolerance = 0.0, .compare = test::Compare::at_most,
                     .tolerance_reason = "mode-I cracks cannot outrun Rayleigh waves (Freund 1990); the tip is known to one lattice site and the "
                     "speed is fitted over W = 10 Δx / c_R, so one site is worth 10 % of c_R",
                     .source = "[freund1990] §5; [rayleigh1885]", .unit = "m/s", .problem = problem});

  auto loc = [&](const char* name) { return opt(crack.at("locations").at(name).at("first_bond_failure")); };
  json rows = json::array();
  rows.push_back({"earliest arrival of the edge loads at a crack tip (23 mm / c_p)", "—", 0.023 / 4899.0});
  rows.push_back({"first bond failure within δ of the upper tip", 3.99e-6, loc("tip_upper")});
  rows.push_back({"first bond failure within δ of the lower tip", 3.99e-6, loc("tip_lower")});
  rows.push_back({"crack initiation (φ ≥ ½ outside the notch)", 3.99e-6, t_init});
  rows.push_back({"lower wing branched (paper)", 9.31e-6, "—"});
  rows.push_back({"through-crack: two pieces", 10.64e-6, t_sep});
  rows.push_back({"overall direction at separation [°]", 45.0, angle});
  rows.push_back({"time step Δt (paper) / Lanczos stable step of this model", *scene.time.dt,
                  run.summary.at("dt_estimate").at("lanczos")});
  test::record_data(problem, "01_times",
                    {{"kind", "table"},
                     {"title", "Measured times against Gu & Zhou 2017 §5.2"},
                     {"columns", {"event", "paper", "pdmpm"}},
                     {"rows", rows},
                     {"caption", "Times in seconds unless marked. Run at the paper's resolution and Δt, continued to 2000 "
                                 "steps; times are history samples (every 5 steps = 0.067 µs). The paper's times are the frames of "
                                 "its fig. 5 (steps 300, 700, 800 × 1.33e-8 s): each event happened at or before its frame "
                                 "(reference_data/README.md)."}});
  test::record_crack_table(problem, crack, cR,
                           "Angle: chord origin → tip from the x axis.");

  const auto fields = run.fields();
  for (const auto& [name, moments, title] :
       {std::tuple{"03_paper_moments", paper_moments, "Damage and crack paths at the paper's moments (fig. 5)"},
        std::tuple{"04_later_moments", later_moments, "Damage and crack paths, later"}}) {
    std::vector<test::Raster> cells;
    std::string when;
    for (double t : moments) {
      const auto& f = fields.nearest(t);
      cells.push_back(test::damage_with_paths(test::read_frame_2d(fields, f), crack, dx, 1));
      when += (when.empty() ? "" : ", ") + std::to_string(f.time * 1e6).substr(0, 5);
    }
    test::record_image(problem, name, test::grid(cells, 3), title,
                       "t = " + when + " µs (left to right, top to bottom). Colour: φ from 0 (dark blue) to 1 (dark red); "
                       "black dots: crack tip positions at every history sample; white: crack origins. The pre-crack is the 45° segment at the centre.");
  }
}

}  // namespace
}  // namespace pdmpm
