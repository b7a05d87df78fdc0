// The dog-bone's δ-convergence study (Noorian et al. §3-1; docs/verification/dogbone.md,
// "δ-convergence"): the peak stress at the first failure at Δx = 1.25, 0.625, 0.3125 and
// 0.15625 mm, δ = 5Δx. The first failure is where the hybrid's first PD region is born; before it
// the hybrid is the grid alone (dogbone.*.hybrid.agrees_with_mpm), and with the elastic-state
// transfer the region starts with the grid's stress, so the pure-MPM runs measure the peak stress
// the PD region holds at the first crack at half the cost of a hybrid (whose step is the PD-stable
// one). The finest level takes 70 minutes on one core, so CI does not run them: they are run by
// the README's command (section on the dog-bone's δ-convergence) and digested
// (verification/tools/dogbone_delta_digest.py); these tests read the digests: the fast tier
// shows them, the full tier gates the convergence (observed order and Richardson's extrapolated
// value from the three finest levels with a failure).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "solver/io/scene.hpp"
#include "verification/support/gate.hpp"
#include "verification/support/raster_image.hpp"
#include "verification/support/scene_gate.hpp"

namespace pdmpm {
namespace {

using Json = nlohmann::json;
using test::Compare;
using test::Gate;

const char* kProblem = "dogbone";
const char* kLevels[] = {"1250um", "625um", "312um", "156um"};  // coarse to fine, Δx halved each time
constexpr double kHorizonRatio = 5.0;                           // δ/Δx of the hybrid scenes
constexpr double kGauge = 12.5e-3, kThickness = 3e-3;           // m: the gauge's section (scenes)
constexpr double kExtensometer = 17.5e-3;                       // m: the probes' distance at every level
// Steel and ductile criterion of the scenes: a particle fails at ε̄_p = ε_f(η) = d₀ exp(c η),
// with the flow stress σ_y + H ε̄_p there, H = E E_t/(E − E_t) the plastic modulus; so the
// criterion's strain at the first failure gives the triaxiality it failed at, η = ln(ε̄_p/d₀)/c.
struct Criterion {
  double yield, plastic_modulus, d0, c;
  explicit Criterion(const io::Scene& s)
      : yield(s.hardening.yield_stress),
        plastic_modulus(s.material.E * s.hardening.tangent_modulus / (s.material.E - s.hardening.tangent_modulus)),
        d0(s.failure.d0),
        c(s.failure.c) {}
  double flow_stress(double eq_plastic_strain) const { return yield + plastic_modulus * eq_plastic_strain; }
  double triaxiality_at_failure(double eq_plastic_strain) const { return std::log(eq_plastic_strain / d0) / c; }
};

std::string measured_dir() { return std::string(PDMPM_SOURCE_DIR) + "/verification/measured/dogbone_delta/"; }

Json read_digest(const std::string& level) {
  std::ifstream in(measured_dir() + "mpm_" + level + ".json");
  if (!in) return nullptr;
  return Json::parse(in);
}

// The engineering curve of a level's history: extensometer strain and load over A₀.
struct Curve {
  std::vector<double> e, S;
};
Curve engineering_curve(const Json& history) {
  Curve c;
  const auto& ul = history["probe_ext_left_ux"];
  const auto& ur = history["probe_ext_right_ux"];
  const auto& F = history["reaction_pulled_x"];
  for (std::size_t k = 0; k < F.size(); ++k) {
    c.e.push_back((ur[k].get<double>() - ul[k].get<double>()) / kExtensometer);
    c.S.push_back(F[k].get<double>() / (kGauge * kThickness) / 1e6);
  }
  return c;
}

// A level's ε̄_p map before its first failure (the digest's raster, −1 outside the body),
// drawn as cells on the damage scale over the largest value of all levels.
test::Raster band_map(const Json& map, double top) {
  const double cell = map["cell"], x_min = map["min"][0], y_min = map["min"][1];
  std::vector<std::array<double, 2>> xy;
  std::vector<double> v;
  const auto& rows = map["values"];
  for (std::size_t j = 0; j < rows.size(); ++j)
    for (std::size_t i = 0; i < rows[j].size(); ++i)
      if (const double value = rows[j][i]; value >= 0.0) {
        xy.push_back({x_min + (static_cast<double>(i) + 0.5) * cell, y_min + (static_cast<double>(j) + 0.5) * cell});
        v.push_back(value / top);
      }
  return test::damage_map(xy, v, cell, 2);
}

// The stored levels, coarse to fine, and the fit over the three finest with a failure:
// ρ = (f₃ − f₂)/(f₂ − f₁), the ratio of successive differences (0 < ρ < 1: monotone, contracting
// convergence), the observed order p = −log₂ ρ and Richardson's limit f₃ + (f₃ − f₂) ρ/(1 − ρ),
// both defined only for a contracting sequence.
struct Study {
  std::vector<Json> runs;
  double rho = std::numeric_limits<double>::quiet_NaN();
  bool converging() const { return rho > 0.0 && rho < 1.0; }
  double order() const { return -std::log2(rho); }
  double limit = std::numeric_limits<double>::quiet_NaN();
};

Study read_study() {
  Study st;
  for (const char* level : kLevels) {
    st.runs.push_back(read_digest(level));
    EXPECT_FALSE(st.runs.back().is_null()) << "no stored run mpm_" << level << ".json in " << measured_dir();
    if (st.runs.back().is_null()) return st;
    const Json& s = st.runs.back()["summary"];
    // What a reader trusts a row for: the run completed its steps, or stopped after its first
    // failure (the digest takes no other; the table shows why it stopped).
    if (s["status"] == "completed")
      EXPECT_EQ(s["steps"], s["steps_requested"]) << level;
    else
      EXPECT_TRUE(st.runs.back().contains("first_failure")) << level << ": stopped before its first failure";
  }
  std::vector<std::size_t> failing;
  for (std::size_t l = 0; l < st.runs.size(); ++l)
    if (st.runs[l].contains("first_failure")) failing.push_back(l);
  EXPECT_GE(failing.size(), 3u) << "the fit needs three levels with a failure";
  if (failing.size() < 3) return st;
  const std::size_t n = failing.size();
  double f[3], dx[3];
  for (int i = 0; i < 3; ++i) {
    const Json& r = st.runs[failing[n - 3 + i]];
    f[i] = r["first_failure"]["peak_von_mises"];
    dx[i] = r["summary"]["spacing"];
  }
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(dx[i] / dx[i + 1], 2.0, 1e-9) << "levels must halve Δx";
  st.rho = (f[2] - f[1]) / (f[1] - f[0]);
  if (st.converging()) st.limit = f[2] + (f[2] - f[1]) * st.rho / (1.0 - st.rho);
  return st;
}

// Full tier: the gate. Its claim fails today (the levels oscillate; docs/verification/dogbone.md),
// so it is the full tier's, as the project keeps reproduction gates the solver does not meet.
TEST(FullDogbone, DeltaConvergenceOfThePeakStress) {
  const Study st = read_study();
  ASSERT_FALSE(std::isnan(st.rho));
  test::record_gate(
      Gate{.id = "dogbone.delta.monotone_convergence",
           .claim = "the peak stress at the first failure shall converge monotonically as δ = 5Δx halves: the ratio "
                    "of successive differences of the three finest levels with a failure, (f₃ − f₂)/(f₂ − f₁), "
                    "shall lie in [0, 1] (observed order p = −log₂ of it ≥ 0)",
           .measured = st.rho,
           .expected = 0.5,
           .tolerance = 0.5,
           .compare = Compare::abs,
           .tolerance_reason =
               "the interval is the definition: a ratio below 0 is an oscillation, above 1 a divergence; the "
               "order itself is shown, not bounded, since three levels give one estimate and no check that it is "
               "in its asymptotic range",
           .source = "[noorian] §3-1 (δ-convergence at fixed δ/Δx); stored runs, verification/measured/dogbone_delta",
           .unit = "",
           .problem = kProblem});
}

// Fast tier: the study's tables, plots and maps (the gate above is the full tier's).
TEST(FastDogbone, DeltaConvergenceFromStoredRuns) {
  const Criterion criterion(io::parse_scene(test::scene_file("dogbone/delta_study/mpm_625um.toml")));
  const Study st = read_study();
  ASSERT_FALSE(std::isnan(st.rho));
  const std::vector<Json>& runs = st.runs;
  Json rows = Json::array(), curves = Json::array(), peak_x = Json::array(), peak_y = Json::array();
  std::vector<test::Raster> maps;
  double top = 0.0;
  for (const Json& r : runs) top = std::max(top, r["before_failure"]["eq_plastic_strain"].get<double>());
  std::string how;
  for (std::size_t l = 0; l < runs.size(); ++l) {
    const Json& r = runs[l];
    const Json& s = r["summary"];
    const double spacing = s["spacing"];
    const Curve c = engineering_curve(r["history"]);
    curves.push_back({{"label", "Δx = " + std::to_string(spacing * 1e3).substr(0, 7) + " mm"},
                      {"x", c.e},
                      {"y", c.S},
                      {"style", "line"}});
    maps.push_back(band_map(r["before_failure"]["map"], top));
    const Json& b = r["before_failure"];
    const std::string site = std::to_string(b["site"][0].get<double>() * 1e3).substr(0, 5) + ", " +
        std::to_string(b["site"][1].get<double>() * 1e3).substr(0, 5);
    const std::string commit = s["provenance"]["git_sha"].get<std::string>().substr(0, 7);
    how += (how.empty() ? "" : "; ") + std::string(kLevels[l]) + ": " + r["how"].get<std::string>();
    const double reached = s["steps"].get<double>() * s["dt"].get<double>();
    const std::string ended = s["status"] == "completed" ? "completed"
                                                         : "stopped at " + std::to_string(reached * 1e3).substr(0, 4) +
            " ms: " + s.value("message", std::string("(no message)"));
    const Json common = {spacing * 1e3, kHorizonRatio * spacing * 1e3, s["particles"], s["steps"], s["wall_time_s"],
                         ended};
    Json row = common;
    if (r.contains("first_failure")) {
      const Json& ff = r["first_failure"];
      const double t = ff["time"], ep = ff["max_eq_plastic_strain"];
      const auto& times = r["history"]["time"];
      std::size_t k = 0;
      while (k + 1 < times.size() && times[k].get<double>() < t) ++k;
      peak_x.push_back(kHorizonRatio * spacing * 1e3);
      peak_y.push_back(ff["peak_von_mises"].get<double>() / 1e6);
      for (const Json& v : {Json(t * 1e3), Json(c.e[k]), Json(ff["peak_von_mises"].get<double>() / 1e6), Json(ep),
                            Json(criterion.triaxiality_at_failure(ep)), Json(criterion.flow_stress(ep) / 1e6)})
        row.push_back(v);
    } else {
      row.push_back("none by " + std::to_string(s["end_time"].get<double>() * 1e3).substr(0, 3) + " ms");
      for (int i = 0; i < 5; ++i) row.push_back("—");
    }
    for (const Json& v : {Json(site), Json(b["time"].get<double>() * 1e3), Json(b["eq_plastic_strain"]),
                          Json(b["triaxiality"]), Json(commit)})
      row.push_back(v);
    rows.push_back(row);
  }
  const std::string fit = "ρ = " + std::to_string(st.rho).substr(0, 5) +
      (st.converging() ? ", order " + std::to_string(st.order()).substr(0, 4) : ": not monotone, no order or limit");
  Json richardson = {"Richardson, three finest", "→ 0", "", "", "", "", "", ""};
  richardson.push_back(st.converging() ? Json(st.limit / 1e6) : Json("—"));
  for (int i = 0; i < 8; ++i) richardson.push_back(i == 7 ? fit : "");
  rows.push_back(richardson);
  test::record_data(
      kProblem, "09_delta_convergence",
      {{"kind", "table"},
       {"title", "δ-convergence of the peak stress at the first failure (pure MPM, δ = 5Δx)"},
       {"columns",
        {"Δx (mm)", "δ (mm)", "particles", "steps", "wall time (s)", "run", "first failure (ms)", "e there",
         "peak von Mises stress up to it (MPa)", "largest ε̄_p there", "η the criterion failed at, ln(ε̄_p/d₀)/c",
         "σ_y + H ε̄_p (MPa)", "first to fail: x₀, y₀ (mm)", "frame before (ms)", "its ε̄_p there", "its η there",
         "commit"}},
       {"rows", rows},
       {"caption",
        "Single runs, stored (" + how +
            "). The peak: the largest von Mises stress of any particle over the history rows (every ≈ 1 µs) up "
            "to the first failure, where the largest ε̄_p is the criterion's ε_f; the first to fail: of the "
            "particles failed at the first field frame (every 0.1 ms) with a failure, the one with the largest "
            "ε̄_p at the frame before (without a failure: the largest ε̄_p at the end). The paper: δ = 0.4, 0.3, 0.2, "
            "0.1, 0.05 mm (Δx = 0.08 … 0.01 mm), its converged value printed "
            "garbled (\"2/4 MPa\"); its δ are out of this machine's reach (docs/verification/dogbone.md)."}});
  Json peak_series = Json::array({{{"label", "measured"}, {"x", peak_x}, {"y", peak_y}, {"style", "points"}}});
  if (st.converging())
    peak_series.push_back({{"label", "Richardson's limit"},
                           {"x", Json::array({peak_x.back(), peak_x.front()})},
                           {"y", Json::array({st.limit / 1e6, st.limit / 1e6})},
                           {"style", "dashed"}});
  test::record_data(
      kProblem, "10_delta_peak_stress",
      {{"kind", "plot"},
       {"title", "Peak stress at the first failure against δ"},
       {"xlabel", "δ = 5Δx (mm)"},
       {"ylabel", "peak von Mises stress (MPa)"},
       {"xscale", "log"},
       {"yscale", "linear"},
       {"series", peak_series},
       {"caption", "Levels without a failure are left out (at Δx = 1.25 mm the neck separates first). " + fit + "."}});
  test::record_data(kProblem, "11_delta_curves",
                    {{"kind", "plot"},
                     {"title", "Engineering curves of the δ-convergence levels (pure MPM, to 6.1 ms)"},
                     {"xlabel", "engineering strain e (extensometer, 17.5 mm)"},
                     {"ylabel", "F / A₀ (MPa)"},
                     {"xscale", "linear"},
                     {"yscale", "linear"},
                     {"series", curves},
                     {"caption", "Every tenth history row, every row within 50 µs of the first failure."}});
  test::record_image(kProblem, "12_delta_band", test::grid(maps, 1),
                     "Equivalent plastic strain before the first failure at Δx = 1.25, 0.625, 0.3125, 0.15625 mm "
                     "(top to bottom)",
                     "Reference configuration on a 0.625 mm raster (each cell the largest ε̄_p of the sites it "
                     "meets); blue 0, red " +
                         std::to_string(top).substr(0, 4) + ", the largest of all levels.");
}

}  // namespace
}  // namespace pdmpm
