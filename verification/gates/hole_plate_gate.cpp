// Rock plate with a central hole under a sudden edge tension (Gu & Zhou 2017 §5.1, docs/verification/
// hole_plate), at the paper's resolution (200 × 100 particles, Δt = 1.3367e-8 s).
// The paper: no crack at 0.0133 µs; cracks start at the hole edges perpendicular to
// the load at 11.97 µs; still growing at 13.3 µs; the plate is fully broken at
// 15.96 µs (its 1200 steps end at 16.04 µs). Crack observables are the solver's
// (solver/pd/crack_observables.hpp, summary.json metrics.crack). The run goes on to
// 2400 steps (32 µs): in this model the events come later than in the paper, and a
// gate needs the event to measure its time.
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
const char* problem = "hole_plate";
const char* source = "[gu-zhou2017] §5.1 (fig. 3); docs/verification/hole_plate_kirsch.md";

// Paper's moments (fig. 3 a–d) and later ones at which this model's cracks grow.
const std::vector<double> paper_moments{0.0133e-6, 11.97e-6, 13.3e-6, 15.96e-6};
const std::vector<double> later_moments{20e-6, 24e-6, 28e-6, 32e-6};

double opt(const json& v) { return v.is_null() ? std::nan("") : v.get<double>(); }

// Full tier: the seed-004 times are not reproduced by this model (see the closing note of
// issue 5 and reference_data/README.md); a failing reproduction is reported, not hidden,
// and CI's fast tier stays for gates the solver meets.
TEST(FullHolePlate, CracksAgainstSeed004) {
  auto scene = io::parse_scene(test::scene_file("hole_plate.toml"));
  ASSERT_EQ(*scene.time.steps, 1200) << "the scene is the paper's set-up: 1200 steps";
  scene.time.steps = 2400;
  scene.output.every.reset();
  scene.output.frames.reset();
  scene.output.frame_times = paper_moments;
  scene.output.frame_times.insert(scene.output.frame_times.end(), later_moments.begin(), later_moments.end());
  const auto run = test::run_for_gate(scene, problem, "seed_resolution");
  const json& crack = run.summary.at("metrics").at("crack");
  const double dx = scene.spacing, delta = scene.delta, cR = crack.at("rayleigh_speed").get<double>();

  // The hole's edges perpendicular to the load (load along x): (40, 20 ± 8) mm.
  const std::vector<std::array<double, 2>> edges{{0.040, 0.028}, {0.040, 0.012}};
  auto edge_distance = [&](const json& pt) {
    double d = 1e300;
    for (const auto& e : edges) d = std::min(d, std::hypot(pt[0].get<double>() - e[0], pt[1].get<double>() - e[1]));
    return d;
  };
  std::vector<json> main_cracks;
  for (const auto& c : crack.at("cracks"))
    if (edge_distance(c.at("origin")) <= 2.0 * delta) main_cracks.push_back(c);

  const double t_init = opt(crack.at("initiation_time")), t_sep = opt(crack.at("separation_time"));
  double site_distance = 0.0;
  for (const auto& s : crack.at("initiation_sites")) site_distance = std::max(site_distance, edge_distance(s));
  if (crack.at("initiation_sites").empty()) site_distance = std::nan("");

  test::record_gate({.id = "hole_plate.initiation_time",
                     .claim = "cracks shall initiate (first particle with φ ≥ ½) within ±15 % of the paper's 11.97 µs", .measured = t_init, .expected = 11.97e-6,
                     .tolerance = 0.15, .compare = test::Compare::rel, .tolerance_reason = "issue 5 sets ±15 % for this seed's times", .source = source, .unit = "s", .problem = problem});
  test::record_gate({.id = "hole_plate.initiation_site",
                     .claim = "every crack shall start at a hole edge perpendicular to the load: its origin within 2δ of (40, 20 ± 8) mm",
                     .measured = site_distance, .expected = 2.0 * delta, .tolerance = 0.0, .compare = test::Compare::at_most,
                     .tolerance_reason = "a crack's origin is the centroid of its first cracked particles, which lie within a horizon of the "
                     "stress concentration: 2δ separates the hole's top and bottom from every other place on the plate",
                     .source = source, .unit = "m", .problem = problem});
  test::record_gate({.id = "hole_plate.separation_time",
                     .claim = "the plate shall separate into two pieces within ±15 % of the paper's 15.96 µs", .measured = t_sep, .expected = 15.96e-6, .tolerance = 0.15,
                     .compare = test::Compare::rel, .tolerance_reason = "issue 5 sets ±15 % for this seed's times", .source = source, .unit = "s", .problem = problem});

  double worst_angle = main_cracks.empty() ? std::nan("") : 0.0, max_speed = 0.0;
  for (const auto& c : main_cracks) {
    const double a = std::abs(c.at("angle_deg").get<double>());
    worst_angle = std::max(worst_angle, std::abs(a - 90.0));
    max_speed = std::max(max_speed, c.at("max_speed").get<double>());
  }
  test::record_gate({.id = "hole_plate.crack_direction",
                     .claim = "both cracks from the hole shall run within 10° of perpendicular to the load (chord origin → tip)",
                     .measured = worst_angle, .expected = 10.0, .tolerance = 0.0, .compare = test::Compare::at_most, .tolerance_reason = "issue 5 sets 10°", .source = source, .unit = "°", .problem = problem});
  const double resolution = dx / (crack.at("speed_window").get<double>() * cR);  // one site over the fit window, / c_R
  test::record_gate({.id = "hole_plate.crack_speed",
                     .claim = "no crack from the hole shall outrun the Rayleigh wave speed beyond the speed measurement's resolution",
                     .measured = max_speed, .expected = cR * (1.0 + resolution), .tolerance = 0.0, .compare = test::Compare::at_most,
                     .tolerance_reason = "mode-I cracks cannot outrun Rayleigh waves (Freund 1990); the tip is known to one lattice site and the "
                     "speed is fitted over W = 10 Δx / c_R, so one site is worth 10 % of c_R",
                     .source = "[freund1990] §5; [rayleigh1885]", .unit = "m/s", .problem = problem});

  // Symmetry about the load axis y = 20 mm, at the last frame.
  const auto fields = run.fields();
  const auto last = test::read_frame_2d(fields, fields.frames().back());
  const double asym = test::mirror_asymmetry(last, 1, 0.020, dx);
  test::record_gate({.id = "hole_plate.symmetry",
                     .claim = "the damage field shall be symmetric about the load axis y = 20 mm at the end (32 µs): Σ|φ − φ_mirror| / Σφ ≤ 5 %",
                     .measured = asym, .expected = 0.05, .tolerance = 0.0, .compare = test::Compare::at_most,
                     .tolerance_reason = "the set-up is exactly symmetric on this lattice; mirrored particles sum their bonds in mirrored order, so "
                     "a bond within round-off of s₀ can break a step earlier on one side and the difference grows as cracks "
                     "branch. 5 % of the damage allows that and still rejects a one-sided crack (which gives ~100 %)",
                     .source = source, .unit = "", .problem = problem});
  EXPECT_EQ(main_cracks.size(), 2u) << "one crack from the top and one from the bottom of the hole";

  // Evidence: every measured time against the paper's.
  auto loc = [&](const char* name) { return opt(crack.at("locations").at(name).at("first_bond_failure")); };
  json rows = json::array();
  rows.push_back({"no crack (paper: at 0.0133 µs)", 0.0133e-6, "—"});
  rows.push_back({"first bond failure within δ of the hole top", 11.97e-6, loc("hole_top")});
  rows.push_back({"first bond failure within δ of the hole bottom", 11.97e-6, loc("hole_bottom")});
  rows.push_back({"crack initiation (φ ≥ ½)", 11.97e-6, t_init});
  rows.push_back({"cracks still growing (paper)", 13.3e-6, "—"});
  rows.push_back({"separation into two pieces", 15.96e-6, t_sep});
  rows.push_back({"time step Δt (paper) / Lanczos stable step of this model", *scene.time.dt,
                  run.summary.at("dt_estimate").at("lanczos")});
  test::record_data(problem, "01_times",
                    {{"kind", "table"},
                     {"title", "Measured times against Gu & Zhou 2017 §5.1"},
                     {"columns", {"event", "paper [s]", "pdmpm [s]"}},
                     {"rows", rows},
                     {"caption", "Run at the paper's resolution and Δt, continued to 2400 steps. Times are history samples "
                                 "(every 5 steps = 0.067 µs). The paper's 1200 steps end at 16.04 µs. Its times are the frames of "
                                 "its fig. 3 (steps 1, 900, 1000, 1200 × 1.33e-8 s): each event happened at or before its "
                                 "frame (reference_data/README.md)."}});
  test::record_crack_table(problem, crack, cR,
                           "Angle: chord origin → tip from the x axis (the load axis). Overall principal-axis angle of all "
                               "cracked particles: " + std::to_string(crack.at("overall_angle_deg").get<double>()) + "°.");
  json series = json::array();
  for (const auto& c : main_cracks)
    series.push_back({{"label", "crack from (" + std::to_string(c.at("origin")[0].get<double>() * 1e3).substr(0, 5) + ", " +
                                    std::to_string(c.at("origin")[1].get<double>() * 1e3).substr(0, 5) + ") mm"},
                      {"x", c.at("path").at("t")}, {"y", c.at("path").at("extent")}, {"style", "line"}});
  if (!main_cracks.empty()) {
    const double t0 = main_cracks.front().at("start_time").get<double>();
    series.push_back({{"label", "Rayleigh speed from the first crack's start"},
                      {"x", {t0, t0 + 0.012 / cR}}, {"y", {0.0, 0.012}}, {"style", "dashed"}});
  }
  test::record_data(problem, "03_extent",
                    {{"kind", "plot"}, {"title", "Crack extent |tip − origin| against time"}, {"xlabel", "t [s]"},
                     {"ylabel", "extent [m]"}, {"xscale", "linear"}, {"yscale", "linear"}, {"series", series},
                     {"caption", "The ligament from the hole to the plate edge is 12 mm long."}});

  // Damage maps with the crack paths at the paper's moments and later.
  std::vector<test::Raster> cells;
  std::string when;
  for (double t : paper_moments) {
    const auto& f = fields.nearest(t);
    cells.push_back(test::damage_with_paths(test::read_frame_2d(fields, f), crack, dx, 2));
    when += (when.empty() ? "" : ", ") + std::to_string(f.time * 1e6).substr(0, 5);
  }
  test::record_image(problem, "04_paper_moments", test::grid(cells, 2),
                     "Damage and crack paths at the paper's moments (fig. 3 a–d)",
                     "t = " + when + " µs (left to right, top to bottom). Colour: φ from 0 (dark blue) to 1 (dark red); black dots: "
                     "crack tip positions at every history sample up to that moment; white: crack origins.");
  cells.clear();
  when.clear();
  for (double t : later_moments) {
    const auto& f = fields.nearest(t);
    cells.push_back(test::damage_with_paths(test::read_frame_2d(fields, f), crack, dx, 2));
    when += (when.empty() ? "" : ", ") + std::to_string(f.time * 1e6).substr(0, 5);
  }
  test::record_image(problem, "05_later_moments", test::grid(cells, 2), "Damage and crack paths after the paper's window",
                     "t = " + when + " µs, as above.");
}

}  // namespace
}  // namespace pdmpm
