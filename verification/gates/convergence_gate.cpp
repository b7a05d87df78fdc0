// Convergence of the spherical wave (Deryugin et al. 2023 §9, issue 4 item 5): how the
// error at t = 3×10⁻⁵ s falls with the choices a user makes, and what each costs.
//  (a) Δx → 0 at the seeds' m = δ/Δx = 3.015 (δ-convergence), all eight cases;
//  (b) m = 2 … 6 at the paper's δ = 1.5075 cm (m-convergence);
//  (c) δ → 0 at fixed m for m = 2, 3.015 and 4. On a lattice δ = mΔx, so at fixed
//      m "δ → 0" and "Δx → 0" are the same refinement: (c) plots (a) against δ
//      and adds the families m = 2 and m = 4, so that at one δ the effect of m shows.
// Every run: octant with the "layer" source, cut at 21 cm (the front is at
// ≤ 19.4 cm at 3×10⁻⁵ s; spherical_wave_gate.cpp checks the cut changes nothing),
// Δt = T/⌈T/(0.8 Δt_Lanczos)⌉, 2 OpenMP threads.
//
// What to expect. At fixed m the lattice sums that set the bonds' stiffness do
// not change with Δx, so δ → 0 converges to a local elastic medium whose P-wave
// speed is the lattice's long-wave speed c_p·R(m), not c_p (R: dispersion() in
// spherical_wave_run.hpp; PMB's micromodulus is calibrated on the continuum,
// docs/models/pmb.md). Measured against the true c_p the error then levels off at the phase
// lag of that speed. Measured against the wave with speed c_p·R(m) (R along a
// lattice axis) it falls further, but not to zero where the lattice sums are
// anisotropic (PMB with the seed's partial volume: R differs between axis and
// diagonal), so that column is a diagnostic. Gates: the true error falls
// monotonically over the three finest levels for all eight cases.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "verification/gates/spherical_wave_run.hpp"
#include "verification/support/convergence_fit.hpp"
#include "verification/support/gate.hpp"
#include "verification/support/speed_accuracy.hpp"

namespace pdmpm {
namespace {

using nlohmann::json;
using namespace test::wave;
using test::fitted_order;

const char* problem = "convergence";

struct Point {
  std::string study;
  Case c;
  double dx = 0, m = 0;
  double l2 = 0, max = 0, l2_lattice = 0, speed_ratio = 0;
  double seconds = 0;  // set-up + run (the stable-step estimate excluded: it can be tabulated)
  long particles = 0;
  long long bonds = 0, steps = 0;
  double delta() const { return m * dx; }
};

// e(m) = e∞ + C m^(−p), p searched in 0.05 … 4: a power fit in 1/m.
test::PowerFit fit_limit(const std::vector<double>& m, const std::vector<double>& e) {
  std::vector<double> inverse;
  for (double v : m) inverse.push_back(1.0 / v);
  return test::fit_power(inverse, e, 0.05, 4.0, 0.01);
}

class Study {
 public:
  // One run per (case, Δx, m); repeated requests reuse it.
  const Point& get(const std::string& study, const Case& c, double dx, double m) {
    const std::string key = c.key() + "/" + std::to_string(dx) + "/" + std::to_string(m);
    if (auto it = runs_.find(key); it != runs_.end()) return it->second;
    Config cfg;
    cfg.spacing = dx;
    cfg.ratio = m;
    cfg.extent = 0.21;
    const std::string rkey = c.key() + "/" + std::to_string(m);
    if (!speed_.count(rkey)) speed_[rkey] = dispersion(c, dx, m, cfg.partial_volume, 0.0, t_compare).long_wave_ratio;
    cfg.lattice_speed_ratio = speed_[rkey];
    const auto res = run(c, cfg);
    Point p;
    p.study = study;
    p.c = c;
    p.dx = dx;
    p.m = m;
    p.l2 = res.metrics.back().l2;
    p.max = res.metrics.back().max;
    p.l2_lattice = res.metrics.back().l2_lattice;
    p.speed_ratio = speed_[rkey];
    p.seconds = res.setup_seconds + res.run_seconds;
    p.particles = res.n_real;
    p.bonds = res.bonds;
    p.steps = res.steps;
    return runs_[key] = p;
  }
  const std::map<std::string, Point>& runs() const { return runs_; }

 private:
  std::map<std::string, Point> runs_;
  std::map<std::string, double> speed_;
};

json row(const Point& p) {
  return {p.c.label, 100 * p.dx, p.m, 100 * p.delta(), p.particles, p.bonds, p.steps, p.l2, p.max, p.speed_ratio, p.l2_lattice, p.seconds};
}
const std::vector<std::string> row_columns = {"case", "Δx [cm]", "m", "δ [cm]", "particles", "bond sides", "steps", "e₂", "e_∞/w₀",
                                              "R(m) = c(k→0)/c_p", "e₂ vs c_p·R(m)", "wall [s]"};

TEST(FullConvergence, Study) {
  omp_set_num_threads(2);
  Study study;
  const std::vector<double> spacings = {0.02, 0.01, 0.005, 0.0025};
  const auto cases = paper_cases();
  const std::vector<Case> focus = {find_case("lps", pd::Influence::inverse_distance), find_case("pmb", pd::Influence::quadratic)};

  // (a) Δx → 0 at m = 3.015.
  json rows_a = json::array(), order_rows = json::array(), series_a = json::array(), series_al = json::array();
  for (const auto& c : cases) {
    std::vector<double> x, e, el;
    for (double dx : spacings) {
      const auto& p = study.get("a", c, dx, paper_ratio);
      rows_a.push_back(row(p));
      x.push_back(100 * dx), e.push_back(p.l2), el.push_back(p.l2_lattice);
    }
    // Orders over the three finest levels (the coarsest, 2.75 points per wavelength, is not resolved).
    const std::vector<double> xf(x.begin() + 1, x.end()), ef(e.begin() + 1, e.end()), elf(el.begin() + 1, el.end());
    const double p_true = fitted_order(xf, ef), p_lat = fitted_order(xf, elf);
    series_a.push_back({{"label", c.label + " (p = " + std::to_string(p_true).substr(0, 4) + ")"}, {"x", x}, {"y", e}, {"style", "line"}});
    series_al.push_back({{"label", c.label + " (p = " + std::to_string(p_lat).substr(0, 4) + ")"}, {"x", x}, {"y", el}, {"style", "line"}});
    const double p_last = std::log(el[2] / el[3]) / std::log(2.0);
    order_rows.push_back({c.label, p_true, p_lat, p_last, e.back(), el.back()});
    const bool monotone = e[1] > e[2] && e[2] > e[3];
    test::record_gate({.id = "convergence.delta." + c.key() + ".monotone",
                       .claim = "At m = 3.015, " + c.label + ": the relative L2 error at t = 3×10⁻⁵ s shall fall at each halving of Δx = 1 → 0.5 → 0.25 cm",
                       .measured = monotone ? 1.0 : 0.0, .expected = 1.0, .tolerance = 0, .compare = test::Compare::at_least, .tolerance_reason = "a yes/no check of monotone convergence",
                       .source = "[pdmpm] docs/design.md: convergence gates need ≥ 3 levels and a monotone error", .unit = "", .problem = problem});
  }
  test::record_data(problem, "01_delta_table", {{"kind", "table"}, {"title", "(a) Δx → 0 at m = 3.015: error at t = 3×10⁻⁵ s"}, {"columns", row_columns},
                                                {"rows", rows_a}});
  test::record_data(problem, "02_delta_plot",
                    {{"kind", "plot"}, {"title", "(a) Relative L2 error against the exact wave (c_p) vs Δx, m = 3.015"}, {"xlabel", "Δx [cm]"},
                     {"ylabel", "e₂ at t = 3×10⁻⁵ s"}, {"xscale", "log"}, {"yscale", "log"}, {"series", series_a},
                     {"caption", "Levels off where the phase lag of the lattice's long-wave speed c_p·R(m) takes over (R ≠ 1 at fixed m)."}});
  test::record_data(problem, "03_delta_plot_lattice_speed",
                    {{"kind", "plot"}, {"title", "(a) Relative L2 error against the wave with the lattice's speed c_p·R(m) vs Δx, m = 3.015"},
                     {"xlabel", "Δx [cm]"}, {"ylabel", "e₂ vs c_p·R(m)"}, {"xscale", "log"}, {"yscale", "log"}, {"series", series_al}});
  test::record_data(problem, "04_delta_orders",
                    {{"kind", "table"}, {"title", "(a) Observed orders of δ-convergence at m = 3.015 (fit over Δx = 1, 0.5, 0.25 cm)"},
                     {"columns", {"case", "order of e₂ (vs c_p)", "order of e₂ vs c_p·R(m)", "order, last halving (vs c_p·R(m))", "e₂ at 0.25 cm",
                                  "e₂ vs c_p·R(m) at 0.25 cm"}},
                     {"rows", order_rows},
                     {"caption", "Dispersion of a lattice wave of wave number k is O((kδ)²), so the phase error and, once small, e₂ fall as δ² "
                                 "(order 2) at fixed m — until the lattice's own long-wave speed c_p·R(m) ≠ c_p takes over (order → 0 against "
                                 "c_p). The levels here are pre-asymptotic for most cases (e₂ of order 0.1–1). Against c_p·R(m) (R along a "
                                 "lattice axis) the error also stalls where the lattice sums are anisotropic (PMB constant: R is 0.924 along an "
                                 "axis, different along the diagonal)."}});

  // (b) m = 2 … 6 at δ = 1.5075 cm.
  const double delta_b = paper_ratio * 0.005;
  json rows_b = json::array(), series_b = json::array(), fit_rows = json::array();
  for (const auto& c : focus) {
    std::vector<double> ms, e;
    for (double m : {2.0, paper_ratio, 4.0, 5.0, 6.0}) {
      const auto& p = study.get("b", c, delta_b / m, m);
      rows_b.push_back(row(p));
      ms.push_back(m), e.push_back(p.l2);
    }
    series_b.push_back({{"label", c.label}, {"x", ms}, {"y", e}, {"style", "line"}});
    const auto f = fit_limit(ms, e);
    const double hi = *std::max_element(e.begin() + 1, e.end()), lo = *std::min_element(e.begin() + 1, e.end());
    fit_rows.push_back({c.label, f.limit, f.coefficient, f.order, f.residual, (hi - lo) / (0.5 * (hi + lo))});
    std::vector<double> fx, fy;
    for (double m = 2; m <= 6.001; m += 0.1) fx.push_back(m), fy.push_back(f.limit + f.coefficient * std::pow(m, -f.order));
    series_b.push_back({{"label", c.label + " fit e∞ + C m^−p"}, {"x", fx}, {"y", fy}, {"style", "dashed"}});
  }
  test::record_data(problem, "05_m_table", {{"kind", "table"}, {"title", "(b) m = 2 … 6 at δ = 1.5075 cm: error at t = 3×10⁻⁵ s"}, {"columns", row_columns},
                                            {"rows", rows_b}});
  test::record_data(problem, "06_m_plot",
                    {{"kind", "plot"}, {"title", "(b) m-convergence at δ = 1.5075 cm"}, {"xlabel", "m = δ/Δx"}, {"ylabel", "e₂ at t = 3×10⁻⁵ s"},
                     {"xscale", "linear"}, {"yscale", "linear"}, {"series", series_b}});
  test::record_data(problem, "07_m_fit",
                    {{"kind", "table"}, {"title", "(b) Fit e₂(m) = e∞ + C m^−p (p searched in 0.05 … 4)"},
                     {"columns", {"case", "e∞ (the δ = 1.5 cm continuum)", "C", "order p", "rms residual", "spread of e₂ over m = 3.015 … 6 (relative)"}},
                     {"rows", fit_rows},
                     {"caption", "At fixed δ, m → ∞ converges to the peridynamic continuum with horizon δ, whose own dispersion at "
                                 "kδ ≈ 1.5 leaves the error e∞. From m ≈ 3 on the error hardly moves (the spread column): at this δ it is set "
                                 "by δ, not by Δx, so a fitted order means little once the spread is within the fit's residual."}});

  // (c) δ → 0 at fixed m = 2, 3.015, 4.
  json rows_c = json::array(), series_c = json::array(), order_c = json::array();
  for (const auto& c : focus)
    for (double m : {2.0, paper_ratio, 4.0}) {
      std::vector<double> d, e, el;
      for (double dx : spacings) {
        const auto& p = study.get("c", c, dx, m);
        rows_c.push_back(row(p));
        d.push_back(100 * p.delta()), e.push_back(p.l2), el.push_back(p.l2_lattice);
      }
      const std::vector<double> df(d.begin() + 1, d.end()), ef(e.begin() + 1, e.end()), elf(el.begin() + 1, el.end());
      series_c.push_back({{"label", c.label + ", m = " + std::to_string(m).substr(0, 5) + " (p = " + std::to_string(fitted_order(df, ef)).substr(0, 4) + ")"},
                          {"x", d}, {"y", e}, {"style", "line"}});
      order_c.push_back({c.label, m, fitted_order(df, ef), fitted_order(df, elf), e.back(), el.back()});
    }
  test::record_data(problem, "08_fixed_m_table", {{"kind", "table"}, {"title", "(c) δ → 0 at fixed m: error at t = 3×10⁻⁵ s"}, {"columns", row_columns},
                                                  {"rows", rows_c}});
  test::record_data(problem, "09_fixed_m_plot",
                    {{"kind", "plot"}, {"title", "(c) δ → 0 at fixed m"}, {"xlabel", "δ [cm]"}, {"ylabel", "e₂ at t = 3×10⁻⁵ s"}, {"xscale", "log"},
                     {"yscale", "log"}, {"series", series_c}});
  test::record_data(problem, "10_fixed_m_orders",
                    {{"kind", "table"}, {"title", "(c) Observed orders in δ at fixed m (fit over the three finest levels)"},
                     {"columns", {"case", "m", "order of e₂ (vs c_p)", "order vs c_p·R(m)", "e₂ finest", "e₂ vs c_p·R(m) finest"}},
                     {"rows", order_c}});

  // Speed against accuracy: every run, Pareto front marked.
  std::vector<const Point*> all;
  std::vector<test::SpeedAccuracyPoint> points;
  for (const auto& [k, p] : study.runs()) {
    all.push_back(&p);
    points.push_back({p.c.label, p.seconds, p.l2});
  }
  json front_rows = json::array();
  for (std::size_t k : test::pareto_front(points)) front_rows.push_back(row(*all[k]));
  test::record_data(problem, "11_speed_accuracy",
                    test::speed_accuracy_plot(points, "Speed against accuracy: one point per (ω, m, Δx), t = 3×10⁻⁵ s",
                                              "wall time [s] (2 threads)", "e₂",
                                              "Wall time = particles, families and time stepping to 3×10⁻⁵ s on the octant cut at 21 cm "
                                              "(the Lanczos stable-step estimate is left out). Pareto front: no other run is both faster "
                                              "and more accurate."));
  test::record_data(problem, "12_pareto_front", {{"kind", "table"}, {"title", "Runs on the Pareto front"}, {"columns", row_columns}, {"rows", front_rows}});
}

}  // namespace
}  // namespace pdmpm
