// Peak stress at a hole under δ-convergence (issue 4 item 6; docs/verification/analytic_solutions.md "plate with
// a circular hole"): a plane-stress LPS plate (ω = 1, ν = 0.3) of width W = 6a and
// length L = 12a with a central hole of radius a = 5 mm, pulled along y by
// σ = 10 MPa, quasi-static by adaptive dynamic relaxation, one quarter with two
// symmetry planes (verification/scenes/hole_concentration_quarter.toml). The
// peak σ_yy sits on the hole's edge across the load, on the ligament y = 0.
// Reference: Kirsch K_t = 3 with the finite-width correction of a long plate,
// d/W = 1/3 (solver/analytic/kirsch.hpp): Heywood 3.444, Roark/Peterson 3.460.
//
// Levels: δ = 4, 2, 1, 0.5 × a base value at δ/Δx = 3.015, with a/Δx an integer
// at every level, so that the ligament particle next to the hole sits at
// x = a + Δx/2 on every level (self-similar), and the hole's edge around it is a
// straight column of sites over more than ±2δ from a/Δx = 40 on.
//
// What PD gives there. The particle stress (F from the particle's own family,
// Hooke's law) at a free surface carries the peridynamic surface effect: the
// particles within δ of a free edge have incomplete families, and the equilibrium
// field near the edge differs from the local one by a layer whose relative size
// does not shrink with δ (at fixed m it is scale-free). It is measured here on a
// flat free edge in uniform tension parallel to it (the stress state at the
// hole's peak): σ_yy(edge particle)/σ = 1 + b (b ≈ −4 %).
//
// How fast. On the lattice the hole is a staircase: around the ligament its edge
// is one straight column of sites, which replaces the arc over a half-length
// ℓ ≈ √(aΔx) (the sites (N + ½, j + ½)Δx, N = a/Δx, stay outside the circle for
// (j + ½)² < N − ¼). A flat of length ℓ and sagitta ~Δx changes the root of the
// notch by a slope Δx/ℓ = (Δx/a)^½, so the peak converges as (δ/a)^½ at fixed m;
// the nonlocal smoothing over δ adds O(δ/a). Measured orders (free fit of
// K∞ − C (δ/a)^p over all levels) come out between 0.4 and 0.7, with scatter
// from the staircase. The limit is therefore taken from the fit with p = ½ over
// all four levels; a free fit and Richardson from the three finest are shown too.
// Reported: the raw edge value K, and K/(1 + b), the value with the flat-edge
// surface effect divided out; the gate is on the latter.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "solver/analytic/kirsch.hpp"
#include "solver/io/scene.hpp"
#include "solver/pd/stress.hpp"
#include "solver/time/dynamic_relaxation.hpp"
#include "solver/sim/pd_setup.hpp"
#include "verification/support/convergence_fit.hpp"
#include "verification/support/gate.hpp"
#include "verification/support/speed_accuracy.hpp"

namespace pdmpm {
namespace {

using nlohmann::json;

const char* problem = "hole_concentration";
constexpr double a = 0.005;        // hole radius
constexpr double half_w = 0.015;   // W/2 = 3a
constexpr double half_l = 0.03;    // L/2 = 6a
constexpr double sigma = 10e6;     // remote tension
constexpr double ratio = 3.015;    // δ/Δx
constexpr double tolerance = 1e-7; // ADR residual / load scale: K_t changes < 1e-5 between 1e-6 and 1e-8 (checked at a/Δx = 10)

std::string scene_file() { return std::string(PDMPM_SOURCE_DIR) + "/verification/scenes/hole_concentration_quarter.toml"; }

double reference_kt() {
  using analytic::WidthCorrection;
  return 0.5 * (analytic::finite_width_kt(2 * a / (2 * half_w), WidthCorrection::heywood) +
                analytic::finite_width_kt(2 * a / (2 * half_w), WidthCorrection::roark));
}

struct Level {
  int n = 0;  // a/Δx
  double dx = 0, delta = 0;
  long particles = 0, iterations = 0;
  double residual = 0;
  double k_edge = 0;  // σ_yy of the ligament particle next to the hole / σ
  double k_max = 0;   // largest σ_yy within δ of the hole / σ
  double far = 0;     // mean σ_yy across the plate at y = 0.75 L/2 (equilibrium check: 1)
  double seconds = 0;
};

Level solve(int n, double m = ratio, std::optional<pd::Influence> influence = std::nullopt) {
  Level lv;
  lv.n = n;
  lv.dx = a / n;
  lv.delta = m * lv.dx;
  io::Scene s = io::parse_scene(scene_file());
  s.spacing = lv.dx;
  s.delta = lv.delta;
  if (influence) s.influence = *influence;
  auto& top = s.boundaries.front();
  top.region.front().min[1] = half_l - lv.dx;  // the top row of sites (at L/2 − Δx/2)
  top.layer = lv.dx;
  const double t0 = omp_get_wtime();
  auto setup = sim::build_pd<2>(s);
  auto st = sim::make_simulation(setup);
  time::DynamicRelaxation<2> relax(st);
  const auto res = relax.solve(1.0, tolerance, 4000000);
  EXPECT_TRUE(res.converged) << "a/Δx = " << n;
  lv.iterations = res.iterations;
  lv.residual = res.residual;
  const auto stress = pd::particle_stress<2>(setup.system);
  const auto& p = setup.system.particles;
  lv.particles = p.n_real;
  double xmin = 1e9, far_sum = 0;
  int far_n = 0;
  const auto far_row = static_cast<int>(std::lround(0.75 * half_l / lv.dx - 0.5));
  for (Index i = 0; i < p.n_real; ++i) {
    const double syy = stress[static_cast<std::size_t>(i)][1] / sigma;
    if (p.site[i][1] == 0 && p.x0[i][0] < xmin) xmin = p.x0[i][0], lv.k_edge = syy;
    if (p.x0[i].norm() <= a + lv.delta) lv.k_max = std::max(lv.k_max, syy);
    if (p.site[i][1] == far_row) far_sum += syy, ++far_n;
  }
  EXPECT_NEAR(xmin, a + 0.5 * lv.dx, 1e-9);  // the self-similar ligament site
  lv.far = far_sum / far_n;
  lv.seconds = omp_get_wtime() - t0;
  return lv;
}

// σ_yy/σ at a straight free edge in uniaxial tension parallel to it, same model,
// ω, ν and m: a square of 20δ whose particles follow the exact field u = H x
// (ε_yy = σ/E, ε_xx = −ν σ/E) except a free band 8δ wide along the edge x = 20δ
// (away from the top and bottom 3δ). Scale-free at fixed m, so one Δx serves.
struct Surface {
  double edge = 0, inside = 0;  // σ_yy/σ at the edge particle and 6δ inside, mid-height
};
Surface surface_factor() {
  const double dx = 1e-4, delta = ratio * dx, side = 20 * delta;
  const io::Scene base = io::parse_scene(scene_file());
  const double eps = sigma / base.material.E, nu = base.material.nu;
  std::ostringstream t;
  t.precision(17);
  t << "[scene]\nid = \"surface_effect\"\n[discretization]\ndimension = 2\nplane = \"stress\"\nspacing = " << dx
    << "\nhorizon_ratio = " << ratio << "\nthickness = 1e-3\n[[shape]]\ntype = \"rectangle\"\nmin = [0.0, 0.0]\nmax = [" << side << ", " << side
    << "]\n[material]\ndensity = " << base.material.rho << "\nyoungs_modulus = " << base.material.E << "\npoissons_ratio = " << nu
    << "\n[model]\ntype = \"lps\"\ninfluence = \"" << name(base.influence) << "\"\n[time]\nintegrator = \"adr\"\ntolerance = 1e-9\n"
    << "[[boundary]]\nname = \"far\"\nkind = \"analytic\"\ncallback = \"affine\"\nparameters = { h_xx = " << -nu * eps << ", h_yy = " << eps << " }\n"
    << "region = [{ type = \"box\", min = [0.0, 0.0], max = [" << side - 8 * delta << ", " << side << "] },"
    << " { type = \"box\", min = [0.0, 0.0], max = [" << side << ", " << 3 * delta << "] },"
    << " { type = \"box\", min = [0.0, " << side - 3 * delta << "], max = [" << side << ", " << side << "] }]\n";
  const auto s = io::parse_scene_text(t.str(), "surface_effect");
  auto setup = sim::build_pd<2>(s);
  auto st = sim::make_simulation(setup);
  time::DynamicRelaxation<2> relax(st);
  EXPECT_TRUE(relax.solve(1.0, 1e-9, 1000000).converged);
  const auto stress = pd::particle_stress<2>(setup.system);
  const auto& p = setup.system.particles;
  int imax = 0;
  for (Index i = 0; i < p.n_real; ++i) imax = std::max(imax, p.site[i][0]);
  const int mid = static_cast<int>(std::lround(0.5 * side / dx));
  const int inside = imax - static_cast<int>(std::lround(6 * delta / dx));
  Surface out;
  for (Index i = 0; i < p.n_real; ++i) {
    if (p.site[i][1] != mid) continue;
    if (p.site[i][0] == imax) out.edge = stress[static_cast<std::size_t>(i)][1] / sigma;
    if (p.site[i][0] == inside) out.inside = stress[static_cast<std::size_t>(i)][1] / sigma;
  }
  return out;
}

// Richardson from the three finest levels (refinement ratio 2): K = K∞ + C h^p.
test::PowerFit richardson(double k1, double k2, double k3) {
  test::PowerFit e;
  const double d1 = k2 - k1, d2 = k3 - k2;
  e.order = std::log(d1 / d2) / std::log(2.0);
  e.limit = k3 + d2 / (std::pow(2.0, e.order) - 1.0);
  return e;
}
// Least squares K = K∞ + C h^p over all levels (h = δ/a; C < 0 when K rises as δ
// falls): p = ½, or the order fitted too (grid 0.1 … 3).
test::PowerFit half_order_fit(const std::vector<double>& h, const std::vector<double>& k) { return test::fit_power(h, k, 0.5, 0.5); }
test::PowerFit free_order_fit(const std::vector<double>& h, const std::vector<double>& k) { return test::fit_power(h, k, 0.1, 3.0); }

void study(const std::string& tier, const std::vector<int>& ns) {
  omp_set_num_threads(tier == "full" ? 2 : omp_get_max_threads());
  const double kref = reference_kt();
  const auto surf = surface_factor();
  std::vector<Level> levels;
  for (int n : ns) levels.push_back(solve(n));

  json rows = json::array();
  std::vector<double> x, ke, km, kc;
  for (const auto& lv : levels) {
    rows.push_back({lv.n, 1e3 * lv.dx, 1e3 * lv.delta, lv.delta / a, lv.particles, lv.iterations, lv.residual, lv.k_edge, lv.k_edge / surf.edge,
                    lv.k_max, lv.far, lv.seconds});
    x.push_back(lv.delta / a), ke.push_back(lv.k_edge), km.push_back(lv.k_max), kc.push_back(lv.k_edge / surf.edge);
  }
  const auto n3 = levels.size();
  const auto raw_half = half_order_fit(x, ke), corr_half = half_order_fit(x, kc), corr_free = free_order_fit(x, kc);
  const auto raw_free = free_order_fit(x, ke);
  const auto corr_rich = richardson(kc[n3 - 3], kc[n3 - 2], kc[n3 - 1]);
  const std::string t = tier == "full" ? "Full tier" : "Fast tier";
  test::record_data(problem, tier + "_1_levels",
                    {{"kind", "table"},
                     {"title", t + ": peak σ_yy at the hole per level (δ = 3.015 Δx)"},
                     {"columns", {"a/Δx", "Δx [mm]", "δ [mm]", "δ/a", "particles", "ADR iterations", "ADR residual", "K edge (raw)",
                                  "K edge / (1 + b)", "K max within δ", "far-field σ_yy/σ", "wall [s]"}},
                     {"rows", rows},
                     {"caption", "K edge = σ_yy/σ of the ligament particle next to the hole (x = a + Δx/2, y = Δx/2); K max = the "
                                 "largest σ_yy/σ of the particles within δ of the hole (sites on the corners of the lattice's staircase "
                                 "hole); far field = mean σ_yy/σ across the plate at y = 0.75 L/2. 1 + b = " + std::to_string(surf.edge) +
                                 " is σ_yy/σ at a straight free edge in uniform tension along it (" + std::to_string(surf.inside) +
                                 " at 6δ inside)."}});
  test::record_data(problem, tier + "_2_extrapolation",
                    {{"kind", "table"},
                     {"title", t + ": observed order and extrapolated K (fits K∞ − C (δ/a)^p)"},
                     {"columns", {"quantity", "fit", "order p", "extrapolated K∞", "reference K_t", "deviation"}},
                     {"rows",
                      {{"K edge (raw)", "p = ½, all levels", 0.5, raw_half.limit, kref, raw_half.limit / kref - 1},
                       {"K edge (raw)", "p free, all levels", raw_free.order, raw_free.limit, kref, raw_free.limit / kref - 1},
                       {"K edge / (1 + b)", "p = ½, all levels", 0.5, corr_half.limit, kref, corr_half.limit / kref - 1},
                       {"K edge / (1 + b)", "p free, all levels", corr_free.order, corr_free.limit, kref, corr_free.limit / kref - 1},
                       {"K edge / (1 + b)", "Richardson, three finest", corr_rich.order, corr_rich.limit, kref, corr_rich.limit / kref - 1}}},
                     {"caption", "Reference: Kirsch K_t = 3 with the finite-width correction for d/W = 1/3, the mean of Heywood (3.444) and "
                                 "Roark/Peterson (3.460) (solver/analytic/kirsch.hpp); the two fits of Howland's solution differ by 0.5 %. "
                                 "The raw edge value converges to K_t (1 + b), the corrected one to K_t. Free-order fits and Richardson "
                                 "react to the staircase's scatter (see the source's header for the order ½)."}});
  std::vector<double> rx = {0.0, x.front()}, ry = {kref, kref}, fit_x, fit_y;
  for (double h = 0; h <= x.front() * 1.0001; h += x.front() / 100) fit_x.push_back(h), fit_y.push_back(corr_half.limit + corr_half.coefficient * std::sqrt(h));
  test::record_data(problem, tier + "_3_plot",
                    {{"kind", "plot"},
                     {"title", t + ": K against δ/a"},
                     {"xlabel", "δ / a"},
                     {"ylabel", "σ_yy,max / σ"},
                     {"xscale", "linear"},
                     {"yscale", "linear"},
                     {"series",
                      {{{"label", "K edge (raw)"}, {"x", x}, {"y", ke}, {"style", "line"}},
                       {{"label", "K edge / (1 + b)"}, {"x", x}, {"y", kc}, {"style", "line"}},
                       {{"label", "K max within δ"}, {"x", x}, {"y", km}, {"style", "points"}},
                       {{"label", "reference (finite width)"}, {"x", rx}, {"y", ry}, {"style", "dashed"}},
                       {{"label", "fit K∞ − C (δ/a)^½ of K edge / (1 + b)"}, {"x", fit_x}, {"y", fit_y}, {"style", "dashed"}}}}});

  bool monotone = true;
  for (std::size_t k = 1; k < ke.size(); ++k) monotone = monotone && ke[k] > ke[k - 1];
  test::record_gate({.id = "hole_concentration." + tier + ".monotone",
                     .claim = "The hole-edge σ_yy/σ shall rise monotonically toward K_t as δ halves (δ = 4, 2, 1, 0.5 × base at δ/Δx = 3.015)",
                     .measured = monotone ? 1.0 : 0.0, .expected = 1.0, .tolerance = 0, .compare = test::Compare::at_least, .tolerance_reason = "a yes/no check of monotone convergence",
                     .source = "[pdmpm] docs/design.md (convergence gates); [kirsch1898]", .unit = "", .problem = problem});
  test::record_gate({.id = "hole_concentration." + tier + ".extrapolated_kt",
                     .claim = "The hole-edge K extrapolated to δ → 0 (fit K∞ − C (δ/a)^½ over the four levels), with the flat-edge surface effect "
                     "divided out, shall lie within 3 % of the finite-width reference K_t",
                     .measured = corr_half.limit, .expected = kref, .tolerance = 0.03, .compare = test::Compare::rel,
                     .tolerance_reason = "3 % (issue 4): the reference fits differ by 0.5 %, the rest is left for the extrapolation of a slowly (order ½) "
                     "converging, staircase-scattered sequence",
                     .source = "[kirsch1898]; [heywood1952] and Roark table 17.1 fits of [howland1930] (solver/analytic/kirsch.hpp)", .unit = "", .problem = problem});
}

TEST(FastHoleConcentration, KtConverges) { study("fast", {5, 10, 20, 40}); }

// Speed against accuracy (issue 6 item 5): the same quarter plate over
// ω × m × Δx, error = |K edge / K_t − 1| as a user would read it off the run
// (raw: the surface layer's −4 % included, so the front levels off there).
TEST(FastHoleConcentration, SpeedAgainstAccuracy) {
  const double kref = reference_kt();
  const std::vector<pd::Influence> influences = {pd::Influence::constant, pd::Influence::quadratic, pd::Influence::inverse_distance};
  const std::vector<double> ratios = {2.015, 3.015, 4.015};
  const std::vector<int> ns = {5, 10, 20};
  std::vector<test::SpeedAccuracyPoint> points;
  json rows = json::array();
  bool refinement_pays = true;
  std::string worst;
  for (auto w : influences)
    for (double m : ratios) {
      const std::string label = std::string(name(w)) + ", m = " + std::to_string(m).substr(0, 5);
      std::vector<double> err;
      for (int n : ns) {
        const Level lv = solve(n, m, w);
        err.push_back(std::abs(lv.k_edge / kref - 1.0));
        points.push_back({label, lv.seconds, err.back()});
        rows.push_back({std::string(name(w)), m, n, 1e3 * lv.dx, lv.particles, lv.iterations, lv.k_edge, err.back(), lv.seconds});
      }
      if (!(err.back() < err.front())) refinement_pays = false, worst += label + "; ";
    }
  const std::string threads = std::to_string(omp_get_max_threads()) + (omp_get_max_threads() == 1 ? " thread" : " threads");
  test::record_data(problem, "fast_4_speed_accuracy",
                    test::speed_accuracy_plot(points, "Speed against accuracy: one point per (ω, m, Δx)", "wall time [s] (" + threads + ")",
                                              "|K edge / K_t − 1|",
                                              "Quarter plate of the convergence study at a/Δx = 5, 10, 20 for each ω and m; wall time = "
                                              "set-up and dynamic relaxation to the same residual. The error is the raw edge value's; it "
                                              "falls slowly (order ≈ ½, the staircase hole) and at fixed m toward the surface layer's "
                                              "≈ −4 %, so at these resolutions Δx matters far more than ω or m. Pareto front: no other run "
                                              "is both faster and more accurate."));
  json front = json::array();
  for (std::size_t k : test::pareto_front(points)) front.push_back(rows[k]);
  const json columns = {"ω", "m", "a/Δx", "Δx [mm]", "particles", "ADR iterations", "K edge", "|K edge / K_t − 1|", "wall [s]"};
  test::record_data(problem, "fast_5_speed_accuracy_runs",
                    {{"kind", "table"}, {"title", "Speed against accuracy: every run"}, {"columns", columns}, {"rows", rows}});
  test::record_data(problem, "fast_6_pareto_front",
                    {{"kind", "table"}, {"title", "Runs on the Pareto front"}, {"columns", columns}, {"rows", front}});
  test::record_gate({.id = "hole_concentration.fast.refinement_pays",
                     .claim = "For every ω and m, the hole-edge error at a/Δx = 20 shall be below the one at a/Δx = 5" +
                         (worst.empty() ? std::string() : " (not so for: " + worst + ")"),
                     .measured = refinement_pays ? 1.0 : 0.0, .expected = 1.0, .tolerance = 0, .compare = test::Compare::at_least,
                     .tolerance_reason = "a yes/no check: the speed/accuracy plot is only a trade if more time buys accuracy",
                     .source = "[pdmpm] docs/verification/hole_plate_kirsch.md (speed/accuracy study)", .unit = "", .problem = problem});
}

TEST(FullHoleConcentration, KtConverges) { study("full", {10, 20, 40, 80}); }

}  // namespace
}  // namespace pdmpm
