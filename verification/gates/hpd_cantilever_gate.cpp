// Static cantilever, the first example of the stabilized hybrid PD paper ([hpd2023];
// docs/models/hpd.md "Static cantilever"): a plane-stress beam (L/h = 10, ν = 0.3) clamped at
// x = 0 and loaded by a shear force P at its free end, solved quasi-statically by adaptive
// dynamic relaxation (verification/scenes/hpd/cantilever.toml), against Timoshenko beam theory
//   δ = P ℓ³/(3EI) + P ℓ/(κ G A),  κ = 5/6 (rectangle), I = t h³/12, A = t h,
// ([timoshenko-gere1972]; the elasticity solution: [timoshenko-goodier1970]).
// Convergence series: δ = 2.015Δx fixed, h/Δx = 6, 8, 12 (fast) and 8 … 32 (full); HPD at
// δ = 3.015Δx and LPS at both ratios on the same beam for comparison.
//
// Fair comparison (what the beam theory is compared with):
// - the clamp is a fixed layer 4Δx (≥ δ) deep behind the face x = 0, so the beam's particles
//   near the clamp keep full families and the face is fully built in;
// - the load is a uniform shear traction on the end face, applied as a body force over the
//   last column of cells; its resultant acts at the column's centre x = L − Δx/2, which is
//   therefore the span ℓ of the beam formula (the deflection is measured at the same column);
// - the deflection is that of the centre line: the mean u_y of the particles within Δx/2 of
//   y = 0 in that column (the middle row, or the two rows beside y = 0).
// What the beam theory leaves out at L/h = 10: the shear term is 0.78 % of δ, and how the section
// is clamped changes it (Timoshenko & Goodier's two clamp conditions of the elasticity solution
// give shear factors 0 and 3/2 in place of 1/κ = 6/5), so the continuum answer lies within
// −0.8 % … +0.2 % of the formula; the 2 % bound is the issue's.
//
// What was found (docs/models/hpd.md "Static cantilever"): HPD is too soft by ≈ 2.4–3.5 (δ/h)²,
// nearly the same function of δ/h for δ = 2.015Δx and 3.015Δx; that is why the series runs at the
// smaller ratio (at 3.015Δx, 2 % would need h/Δx ≈ 40: hours of ADR on one core). LPS is too stiff,
// by an error that hardly changes with Δx at fixed δ/Δx.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <string>
#include <vector>

#include "solver/io/scene.hpp"
#include "solver/sim/pd_setup.hpp"
#include "solver/time/dynamic_relaxation.hpp"
#include "verification/support/convergence_fit.hpp"
#include "verification/support/gate.hpp"
#include "verification/support/scene_gate.hpp"

namespace pdmpm {
namespace {

using nlohmann::json;

const char* kProblem = "hpd";
const char* kSource = "[timoshenko-gere1972] (δ = Pℓ³/3EI + Pℓ/κGA, κ = 5/6); [hpd2023] (the static cantilever)";
constexpr double kSpan = 0.1;      // L: clamp face to the free end (m)
constexpr double kDepth = 0.01;    // h
constexpr double kClampCells = 4;  // fixed layer depth in Δx (≥ δ/Δx)
// ADR residual / load scale. At h/Δx = 8 the deflection moved by 1e-4 of itself between 1e-6 and
// 1e-8; each study re-solves one level at kTolerance/100 and shows the change (table caption).
constexpr double kTolerance = 1e-7;

struct Level {
  std::string model;
  int n = 0;       // h/Δx
  double m = 0.0;  // δ/Δx
  double dx = 0, span = 0, deflection = 0, reference = 0, error = 0, residual = 0, seconds = 0;
  long particles = 0, iterations = 0;
};

// Timoshenko beam theory for the scene's beam with span ℓ.
double timoshenko(const io::Scene& s, double span, double load) {
  const double E = s.material.E, G = E / (2.0 * (1.0 + s.material.nu)), t = s.measure;
  const double I = t * kDepth * kDepth * kDepth / 12.0, A = t * kDepth, kappa = 5.0 / 6.0;
  return load * span * span * span / (3.0 * E * I) + load * span / (kappa * G * A);
}

Level solve(const std::string& model, int n, double m, double tolerance = kTolerance) {
  Level lv;
  lv.model = model;
  lv.n = n;
  lv.m = m;
  lv.dx = kDepth / n;
  io::Scene s = io::parse_scene(test::scene_file("hpd/cantilever.toml"));
  s.model = model;
  s.spacing = lv.dx;
  s.delta = m * lv.dx;
  s.shapes.front().min = {-kClampCells * lv.dx, -0.5 * kDepth};
  s.shapes.front().max = {kSpan, 0.5 * kDepth};
  auto& tip = s.boundaries.at(1);
  tip.region.front().min[0] = kSpan - lv.dx;  // the last column of cells
  tip.layer = lv.dx;
  const double traction = -std::stod(tip.value.at(1));  // τ = P/(h t)
  const double load = traction * kDepth * s.measure;
  const double t0 = omp_get_wtime();
  auto setup = sim::build_pd<2>(s);
  auto st = sim::make_simulation(setup);
  time::DynamicRelaxation<2> relax(st);
  const auto res = relax.solve(1.0, tolerance, 4000000);
  EXPECT_TRUE(res.converged) << model << " h/Δx = " << n;
  lv.iterations = res.iterations;
  lv.residual = res.residual;
  const auto& p = setup.system.particles;
  lv.particles = p.n_real;
  double xmax = -1.0;
  for (Index i = 0; i < p.n_real; ++i) xmax = std::max(xmax, p.x0[i][0]);
  double sum = 0.0;
  int count = 0;
  for (Index i = 0; i < p.n_real; ++i)
    if (p.x0[i][0] > xmax - 0.25 * lv.dx && std::abs(p.x0[i][1]) < 0.75 * lv.dx) sum += -p.u[i][1], ++count;
  EXPECT_NEAR(xmax, kSpan - 0.5 * lv.dx, 1e-9 * kSpan);  // the load's column
  lv.deflection = sum / count;
  lv.span = xmax;
  lv.reference = timoshenko(s, lv.span, load);
  lv.error = lv.deflection / lv.reference - 1.0;
  lv.seconds = omp_get_wtime() - t0;
  std::printf("  %s m=%.3f h/dx=%d: error %+.5f, %ld iterations, %.1f s\n", model.c_str(), m, n, lv.error,
              lv.iterations, lv.seconds);
  return lv;
}

struct Study {
  std::vector<Level> hpd;     // the convergence series: hpd at δ = kMain Δx
  std::vector<Level> others;  // hpd at another m, LPS: the same beam, for comparison
  double order = 0.0;         // least-squares slope of log |error| against log Δx (hpd series)
};

constexpr double kMain = 2.015;  // δ/Δx of the convergence series

Study study(const std::string& tier, const std::vector<int>& ns, const std::vector<Level>& others, int check_n) {
  Study st;
  for (int n : ns) st.hpd.push_back(solve("hpd", n, kMain));
  st.others = others;
  // The ADR tolerance's share of the error: one level again at a 100× tighter residual.
  const auto tight = solve("hpd", check_n, kMain, kTolerance / 100.0);
  double adr_change = 0.0;
  for (const auto& lv : st.hpd)
    if (lv.n == check_n) adr_change = std::abs(lv.deflection / tight.deflection - 1.0);
  std::vector<double> h, err;
  for (const auto& lv : st.hpd) h.push_back(lv.dx), err.push_back(std::abs(lv.error));
  st.order = test::fitted_order(h, err);
  char order_text[96];
  std::snprintf(order_text, sizeof order_text, "%.2f", st.order);
  char adr_text[96];
  std::snprintf(adr_text, sizeof adr_text, "%.1e", adr_change);
  json rows = json::array();
  json series = json::array();
  auto add = [&](const std::vector<Level>& set, const std::string& label, const std::string& style) {
    json xs = json::array(), ys = json::array();
    for (const auto& lv : set) {
      rows.push_back({label, lv.m, lv.n, 1e3 * lv.dx, lv.m / lv.n, 1e3 * lv.span, lv.particles, lv.iterations,
                      lv.residual, 1e6 * lv.reference, 1e6 * lv.deflection, 100.0 * lv.error, lv.seconds});
      xs.push_back(lv.m / lv.n);
      ys.push_back(std::abs(lv.error));
    }
    series.push_back({{"label", label}, {"x", xs}, {"y", ys}, {"style", style}});
  };
  add(st.hpd, "hpd, δ = 2.015Δx", "line");
  for (const std::string label : {"hpd, δ = 3.015Δx", "lps, δ = 2.015Δx", "lps, δ = 3.015Δx"}) {
    std::vector<Level> set;
    for (const auto& lv : others)
      if (label.rfind(lv.model, 0) == 0 &&
          std::abs(lv.m - (label.find("2.015") != std::string::npos ? 2.015 : 3.015)) < 1e-9)
        set.push_back(lv);
    if (!set.empty()) add(set, label, "points");
  }
  const std::string t = tier == "full" ? "Full tier" : "Fast tier";
  test::record_data(kProblem, tier + "_1_cantilever_levels",
                    {{"kind", "table"},
                     {"title", t + ": static cantilever, tip deflection against Timoshenko beam theory"},
                     {"columns",
                      {"model", "δ/Δx", "h/Δx", "Δx [mm]", "δ/h", "span ℓ [mm]", "particles", "ADR iterations",
                       "ADR residual", "Timoshenko δ [µm]", "PD δ [µm]", "error [%]", "wall [s]"}},
                     {"rows", rows},
                     {"caption",
                      "L/h = 10, plane stress, E = 200 GPa, ν = 0.3, P = 0.5 N; ℓ = L − Δx/2 (the load's line "
                      "of action). Observed order of the hpd error (δ = 2.015Δx, least-squares slope in Δx): " +
                          std::string(order_text) + ". ADR: at h/Δx = " + std::to_string(check_n) +
                          " a 100× tighter residual changes the deflection by " + adr_text + " of itself."}});
  test::record_data(kProblem, tier + "_2_cantilever_convergence",
                    {{"kind", "plot"},
                     {"title", t + ": |tip deflection error| against δ/h"},
                     {"xlabel", "δ/h"},
                     {"ylabel", "|δ_PD/δ_Timoshenko − 1|"},
                     {"xscale", "log"},
                     {"yscale", "log"},
                     {"series", series},
                     {"caption",
                      "hpd is too soft (error > 0), LPS too stiff (error < 0); against δ/h, so that the two horizon "
                      "ratios can be compared. hpd at δ = 2.015Δx: observed order " +
                          std::string(order_text) + " in Δx."}});
  // The convergence series against Δx with the least-squares power law it gives.
  double mean_lh = 0.0, mean_le = 0.0;
  const auto levels = static_cast<double>(h.size());
  for (std::size_t k = 0; k < h.size(); ++k) mean_lh += std::log(h[k]) / levels, mean_le += std::log(err[k]) / levels;
  json xs = json::array(), ys = json::array(), fit = json::array();
  for (std::size_t k = 0; k < h.size(); ++k) {
    xs.push_back(1e3 * h[k]);
    ys.push_back(err[k]);
    fit.push_back(std::exp(mean_le + st.order * (std::log(h[k]) - mean_lh)));
  }
  test::record_data(
      kProblem, tier + "_3_cantilever_order",
      {{"kind", "plot"},
       {"title", t + ": hpd tip deflection error against Δx (δ = 2.015Δx)"},
       {"xlabel", "Δx (mm)"},
       {"ylabel", "|δ_PD/δ_Timoshenko − 1|"},
       {"xscale", "log"},
       {"yscale", "log"},
       {"series",
        {{{"label", "hpd"}, {"x", xs}, {"y", ys}, {"style", "points"}},
         {{"label", "least squares, order " + std::string(order_text)}, {"x", xs}, {"y", fit}, {"style", "dashed"}}}},
       {"caption",
        "h = 10 mm: h/Δx = " + std::to_string(ns.front()) + " … " + std::to_string(ns.back()) +
            "; the 2 % bound of the issue is gated at the finest level of the full tier."}});
  return st;
}

// Why the error falls faster than Δx: HPD's energy density at a particle is the mean of ψ at its
// bonds' midpoints. In a bending field ψ ∝ y²; inside the body the family is symmetric and the
// mean differs from ψ(y) by O(δ²ψ''), and within δ of the top and bottom faces the family points
// inwards, so the midpoints sit O(δ) nearer the neutral axis, in a layer of depth δ: O(δ²/h²) of
// the bending energy. This argument gives order 2 at fixed δ/Δx; measured: 1.82 (fast levels),
// 1.75 (full), a local slope of 1.73 between h/Δx = 16 and 32 — what else is cut within δ (the
// corners, the loaded column) is not in the argument.
const std::string kOrderReason =
    "the surface argument gives order 2 (O(δ²/h²) of the bending energy, δ ∝ Δx) and 1.73–1.82 is measured; 1.5 "
    "separates this from a first-order error, which a load or clamp misplaced by O(Δx) would give";

TEST(FastHpdCantilever, TipDeflectionConverges) {
  std::vector<Level> others{solve("lps", 8, 2.015), solve("lps", 8, 3.015)};
  const auto st = study("fast", {6, 8, 12}, others, 6);
  test::record_gate({.id = "hpd.cantilever.order_fast",
                     .claim = "The tip deflection error of the HPD cantilever (δ = 2.015Δx, h/Δx = 6, 8, 12) shall "
                              "converge at an observed order of at least 1.5 in Δx",
                     .measured = st.order,
                     .expected = 1.5,
                     .compare = test::Compare::at_least,
                     .tolerance_reason = kOrderReason,
                     .source = kSource,
                     .unit = "",
                     .problem = kProblem});
}

TEST(FullHpdCantilever, TipDeflectionWithinTwoPercent) {
  std::vector<Level> others{solve("hpd", 8, 3.015),  solve("hpd", 16, 3.015), solve("lps", 8, 2.015),
                            solve("lps", 16, 2.015), solve("lps", 8, 3.015),  solve("lps", 16, 3.015)};
  const auto st = study("full", {8, 12, 16, 24, 32}, others, 16);
  test::record_gate({.id = "hpd.cantilever.error_finest",
                     .claim = "At the finest resolution (h/Δx = 32, δ = 2.015Δx) the HPD cantilever's tip deflection "
                              "shall be within 2 % of Timoshenko beam theory",
                     .measured = std::abs(st.hpd.back().error),
                     .expected = 0.02,
                     .compare = test::Compare::at_most,
                     .tolerance_reason = "the issue's bound; the beam theory's own idealisation of the clamp is worth "
                                         "≤ 0.8 % of δ at L/h = 10 (Timoshenko & Goodier's clamp conditions)",
                     .source = kSource,
                     .unit = "",
                     .problem = kProblem});
  test::record_gate({.id = "hpd.cantilever.order_full",
                     .claim =
                         "Over h/Δx = 8 … 32 (δ = 2.015Δx) the HPD cantilever's tip deflection error shall converge "
                         "at an observed order of at least 1.5 in Δx",
                     .measured = st.order,
                     .expected = 1.5,
                     .compare = test::Compare::at_least,
                     .tolerance_reason = kOrderReason,
                     .source = kSource,
                     .unit = "",
                     .problem = kProblem});
}

}  // namespace
}  // namespace pdmpm
