// The spherically symmetric elastic wave of Deryugin et al. 2023 §9 (docs/verification/spherical_wave.md,
// §9): PMB with the six influence functions of Deryugin et al. 2023 table 4.1 (ν = 1/4) and
// LPS with ω = 1 and ω = 1/r (ν = 0.33), compared with the closed-form solution
// (solver/analytic/spherical_wave.hpp). How runs are set up and how errors are
// measured: spherical_wave_run.hpp. Convergence studies: convergence_gate.cpp.
//
// Fast tier: the closed form against GSL ODE integration, the particle count of
// both readings, and the octant at Δx = 1 cm (68 913 particles) and at the paper's
// Δx = 0.5 cm on the part of the octant the wave reaches by t = 3×10⁻⁵ s
// (79 480 particles; the Full tier checks that the truncation changes nothing).
// Full tier: both readings at the paper's resolution for all eight cases to
// t = 7×10⁻⁵ s, with the source choice, partial volume and time step varied.
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "solver/core/particle_builder.hpp"
#include "solver/sim/geometry_from_scene.hpp"
#include "verification/gates/spherical_wave_run.hpp"
#include "verification/support/gate.hpp"
#include "verification/support/hdf5_gold.hpp"
#include "verification/support/raster_image.hpp"
#include "verification/support/scene_gate.hpp"

namespace pdmpm {
namespace {

using nlohmann::json;
using namespace test::wave;

const char* problem = "spherical_wave";

// The paper's relative errors at t = 3×10⁻⁵ s (Deryugin et al. 2023 §9; metric and reading not
// stated), as stored in reference_data/paper_numbers.h5.
struct PaperErrors {
  double lps_inverse_distance = 0, lps_constant = 0;
};
PaperErrors paper_errors() {
  const test::gold::Reader f(test::gold::reference_data_dir() + "/paper_numbers.h5");
  return {f.scalar("/spherical_wave/lps_inverse_distance_error"), f.scalar("/spherical_wave/lps_constant_error")};
}

std::string fmt(double v, int digits = 4) {
  std::ostringstream s;
  s.precision(digits);
  s << v;
  return s.str();
}
std::string percent(double v) { return fmt(v * 100, 3) + " %"; }

// ---------------------------------------------------------------------------
// 1. The closed form against numerical integration of its defining ODE.

struct OdeParams {
  analytic::SphericalWave w;
};

int rhs(double t, const double y[], double dydt[], void* params) {
  const auto& w = static_cast<OdeParams*>(params)->w;
  dydt[0] = -(w.cp / w.r0) * y[0] - w.cp * w.r0 * w.source(t);
  return GSL_SUCCESS;
}

TEST(FastSphericalWave, ClosedFormMatchesOdeIntegration) {
  // F' + (c_p/r₀) F = −c_p r₀ g(t), F(0) = 0, integrated by GSL's adaptive
  // Runge–Kutta–Prince–Dormand (8,9) to 1e-14 relative per step; then u_r and v_r
  // built from the integrated F (F' and F'' from the ODE itself) against the
  // closed form on a grid of r ∈ [r₀, r₁] and t ∈ [0, 7×10⁻⁵ s], for both
  // materials (the PMB and LPS wave speeds).
  double worst_F = 0, worst_u = 0, worst_v = 0;
  for (double nu : {0.25, 0.33}) {
    io::Scene s;
    s.material = {youngs, nu, density};
    s.setting = core::Setting::solid3d;
    OdeParams prm{exact_wave(s)};
    const auto& w = prm.w;
    gsl_odeiv2_system sys{rhs, nullptr, 1, &prm};
    auto* drv = gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, 1e-10, 0.0, 1e-14);
    const int n = 700;
    std::vector<double> tg(n + 1), Fode(n + 1);
    double y[1] = {0.0}, t = 0.0, Fmax = 0.0;
    for (int k = 0; k <= n; ++k) {
      const double tk = t_end * k / n;
      if (tk > t) {
        ASSERT_EQ(gsl_odeiv2_driver_apply(drv, &t, tk, y), GSL_SUCCESS);
      }
      tg[static_cast<std::size_t>(k)] = tk;
      Fode[static_cast<std::size_t>(k)] = y[0];
      Fmax = std::max(Fmax, std::abs(w.F(tk)));
    }
    gsl_odeiv2_driver_free(drv);
    for (int k = 0; k <= n; ++k) worst_F = std::max(worst_F, std::abs(Fode[static_cast<std::size_t>(k)] - w.F(tg[static_cast<std::size_t>(k)])) / Fmax);

    // u_r, v_r on the grid: retarded times τ = t − (r − r₀)/c_p that fall on the
    // ODE grid (r chosen so), F', F'' from the ODE right-hand side.
    double umax = 0, vmax = 0, du = 0, dv = 0;
    for (int k = 1; k <= n; ++k) {
      for (int lag = 0; lag < k; lag += 7) {
        const double tau = tg[static_cast<std::size_t>(k - lag)], tt = tg[static_cast<std::size_t>(k)];
        const double r = w.r0 + w.cp * (tt - tau);
        if (r > r1) continue;
        const double F = Fode[static_cast<std::size_t>(k - lag)];
        const double dF = -(w.cp / w.r0) * F - w.cp * w.r0 * w.source(tau);
        const double d2F = -(w.cp / w.r0) * dF - w.cp * w.r0 * w.source_rate(tau);
        const double u = -dF / (w.cp * r) - F / (r * r), v = -d2F / (w.cp * r) - dF / (r * r);
        const double ue = w.radial_displacement(r, tt), ve = w.radial_velocity(r, tt);
        umax = std::max(umax, std::abs(ue));
        vmax = std::max(vmax, std::abs(ve));
        du = std::max(du, std::abs(u - ue));
        dv = std::max(dv, std::abs(v - ve));
      }
    }
    worst_u = std::max(worst_u, du / umax);
    worst_v = std::max(worst_v, dv / vmax);
  }
  const std::string why =
      "the integrator is asked for 1e-14 relative per step over ~10³ steps; 1e-10 leaves room for the "
      "accumulated round-off and still catches any error in a coefficient of the closed form";
  const std::string src = "[pdmpm] docs/verification/spherical_wave.md: F' + (c_p/r₀)F = −c_p r₀ g(t); GSL gsl_odeiv2 rk8pd";
  test::record_gate({.id = "spherical_wave.analytic.potential_vs_ode", .claim = "The closed-form potential F(t) shall agree with GSL ODE integration to 1e-10 of max|F|",
                     .measured = worst_F, .expected = 1e-10, .tolerance = 0, .compare = test::Compare::at_most, .tolerance_reason = why, .source = src, .unit = "", .problem = problem});
  test::record_gate({.id = "spherical_wave.analytic.displacement_vs_ode", .claim = "u_r(r, t) from the closed form shall agree with u_r from the integrated F to 1e-10 of max|u_r|",
                     .measured = worst_u, .expected = 1e-10, .tolerance = 0, .compare = test::Compare::at_most, .tolerance_reason = why, .source = src, .unit = "", .problem = problem});
  test::record_gate({.id = "spherical_wave.analytic.velocity_vs_ode", .claim = "v_r(r, t) from the closed form shall agree with v_r from the integrated F to 1e-10 of max|v_r|",
                     .measured = worst_v, .expected = 1e-10, .tolerance = 0, .compare = test::Compare::at_most, .tolerance_reason = why, .source = src, .unit = "", .problem = problem});
}

// ---------------------------------------------------------------------------
// 2. The particle count of both readings (lattice fill only: no families).

TEST(FastSphericalWave, ParticleCountIs531414InBothReadings) {
  for (Reading r : {Reading::octant, Reading::cube}) {
    long counts[2] = {0, 0};  // free particles: layer source (body = all), points source (body − 27 held)
    for (Source src : {Source::layer, Source::points}) {
      const io::Scene s = io::parse_scene(scene_path(r, src));
      core::Lattice<3> lat;
      lat.spacing = s.spacing;
      lat.origin = sim::to_vec<3>(*s.lattice_origin);
      const auto body = core::fill_lattice<3>(sim::make_geometry<3>(s.shapes), lat, std::pow(s.spacing, 3));
      long inner = 0;  // sites with max(|x|,|y|,|z|) ≤ r₀: the cavity
      for (Index i = 0; i < body.n_real; ++i) inner += body.x0[i].cwiseAbs().maxCoeff() <= r0 * (1 + 1e-9) ? 1 : 0;
      counts[src == Source::layer ? 0 : 1] = body.n_real - inner;
      ASSERT_EQ(inner, src == Source::layer ? 0 : 27);
    }
    EXPECT_EQ(counts[0], counts[1]);
    test::record_gate({.id = std::string("spherical_wave.particles.") + name(r),
                       .claim = std::string("The ") + name(r) + " reading (" + (r == Reading::octant ? "[0, 40 cm]³, Δx = 0.5 cm" : "[−40, 40 cm]³, Δx = 1 cm") +
                           ") shall have N = 81³ − 27 = 531414 particles outside the inner cube, as the seed states",
                       .measured = static_cast<double>(counts[0]), .expected = static_cast<double>(paper_particles), .tolerance = 0, .compare = test::Compare::abs,
                       .tolerance_reason = "a count: exact", .source = "[deryugin2023] §9: N = 531414; docs/verification/spherical_wave.md", .unit = "", .problem = problem});
  }
}

// ---------------------------------------------------------------------------
// 3. Fast runs: octant at Δx = 1 cm, and at the paper's Δx on the reached part.

struct FastBound {
  double l2_coarse;  // bound on e₂ at Δx = 1 cm
  double l2_paper;   // bound on e₂ at Δx = 0.5 cm
};

void fast_octant(const Case& c, const std::string& key, const FastBound& bound, const std::string& bound_reason) {
  Config coarse;
  coarse.reading = Reading::octant;
  coarse.spacing = 0.01;
  coarse.times = {t_compare};
  const auto rc = run(c, coarse);
  EXPECT_GT(rc.n_real, 20000);  // "a few × 10⁴ particles"
  Config paper = coarse;
  paper.spacing = 0.005;
  paper.extent = 0.21;  // the front is at ≤ 19.4 cm at 3×10⁻⁵ s (LPS)
  const auto rp = run(c, paper);
  const auto& mc = rc.metrics.back();
  const auto& mp = rp.metrics.back();
  test::record_data(problem, "fast_" + key,
                    json{{"kind", "table"},
                         {"title", "Fast tier: " + c.label + ", octant, t = 3×10⁻⁵ s"},
                         {"columns", {"Δx [cm]", "extent [cm]", "particles", "Δt [s]", "steps", "e₂ (L2)", "e_∞ / w₀", "run [s]"}},
                         {"rows",
                          {{100 * coarse.spacing, 100 * coarse.extent, rc.n_real, rc.dt, rc.steps, mc.l2, mc.max, rc.run_seconds},
                           {100 * paper.spacing, 100 * paper.extent, rp.n_real, rp.dt, rp.steps, mp.l2, mp.max, rp.run_seconds}}}});
  test::record_gate({.id = "spherical_wave.fast." + key + ".coarse_l2",
                     .claim = "Octant at Δx = 1 cm (" + std::to_string(rc.n_real) + " particles), " + c.label +
                         ": relative L2 error of u_r at t = 3×10⁻⁵ s shall stay within the bound from the convergence study",
                     .measured = mc.l2, .expected = bound.l2_coarse, .tolerance = 0, .compare = test::Compare::at_most, .tolerance_reason = bound_reason,
                     .source = "convergence study (verification/gates/convergence_gate.cpp), [deryugin2023] §9", .unit = "", .problem = problem});
  test::record_gate({.id = "spherical_wave.fast." + key + ".paper_l2",
                     .claim = "Octant at the paper's Δx = 0.5 cm (the 79 480 particles within 21 cm), " + c.label +
                         ": relative L2 error of u_r at t = 3×10⁻⁵ s shall stay within the bound from the convergence study",
                     .measured = mp.l2, .expected = bound.l2_paper, .tolerance = 0, .compare = test::Compare::at_most, .tolerance_reason = bound_reason,
                     .source = "convergence study (verification/gates/convergence_gate.cpp), [deryugin2023] §9", .unit = "", .problem = problem});
  test::record_gate({.id = "spherical_wave.fast." + key + ".refinement_ratio",
                     .claim = "Halving Δx from 1 cm to 0.5 cm (m = 3.015) shall reduce the L2 error (" + c.label + ")",
                     .measured = mp.l2 / mc.l2, .expected = 1.0, .tolerance = 0, .compare = test::Compare::at_most,
                     .tolerance_reason = "δ-convergence: the error must fall as δ = 3.015 Δx halves", .source = "[pdmpm] docs/verification/spherical_wave.md (convergence); [deryugin2023] §9", .unit = "", .problem = problem});
}

// Bounds: the Full-tier study measured e₂(3×10⁻⁵ s) with these very runs (the
// solver is deterministic for any thread count); the bounds sit 3 % above those
// values so that a change of the solver that worsens the wave by more than that
// fails CI. See the convergence section of the report for the values.
TEST(FastSphericalWave, CoarseOctantLpsInverseDistance) {
  fast_octant(find_case("lps", pd::Influence::inverse_distance), "lps_inverse_distance", {1.045 * 1.03, 0.5875 * 1.03},
              "3 % above the values the convergence study measured (1.045 at Δx = 1 cm, 0.5875 at 0.5 cm): a regression guard");
}

TEST(FastSphericalWave, CoarseOctantPmbQuadratic) {
  fast_octant(find_case("pmb", pd::Influence::quadratic), "pmb_quadratic", {0.6915 * 1.03, 0.2867 * 1.03},
              "3 % above the values the convergence study measured (0.6915 at Δx = 1 cm, 0.2867 at 0.5 cm): a regression guard");
}

// ---------------------------------------------------------------------------
// 4. Full tier: the paper's resolution.

// Schlieren picture of |v| on z = 0 (seed eq 9.3: S = 0.8 |v| exp(−5 |v| / |v|_max),
// taken literally; S/S_max → colour), one panel per time, left to right.
test::Raster schlieren(const std::vector<Slice>& slices) {
  std::vector<test::Raster> panels;
  for (const auto& sl : slices) {
    const int n = sl.n, scale = std::max(2, 330 / n);
    double vmax = 0;
    for (double v : sl.speed)
      if (std::isfinite(v)) vmax = std::max(vmax, v);
    const double Speak = 0.8 * vmax / (5.0 * std::numbers::e);  // max of 0.8 x e^{−5x/vmax}, at x = vmax/5
    test::Raster panel(n * scale, n * scale);
    for (int row = 0; row < n; ++row)  // slice rows run top to bottom, raster y bottom to top
      for (int x = 0; x < n; ++x) {
        const double v = sl.speed[static_cast<std::size_t>(row) * static_cast<std::size_t>(n) + static_cast<std::size_t>(x)];
        const test::Rgb c = std::isfinite(v) && vmax > 0 ? test::viridis(0.8 * v * std::exp(-5.0 * v / vmax) / Speak)
                                                         : test::Rgb{235, 235, 235};
        const int y = n - 1 - row;
        panel.fill(x * scale, y * scale, (x + 1) * scale - 1, (y + 1) * scale - 1, c);
      }
    panels.push_back(std::move(panel));
  }
  return test::grid(panels, static_cast<int>(panels.size()), 6);
}

json profile_plot(const std::string& title, const std::vector<std::pair<std::string, const Profile*>>& runs, const std::string& caption) {
  json series = json::array();
  const Profile* first = runs.front().second;
  std::vector<double> r_cm;
  for (double r : first->r) r_cm.push_back(100 * r);
  std::vector<double> ex;
  for (double u : first->exact) ex.push_back(u / amplitude);
  series.push_back({{"label", "analytic"}, {"x", r_cm}, {"y", ex}, {"style", "line"}});
  for (const auto& [label, p] : runs) {
    std::vector<double> x, y;
    for (std::size_t k = 0; k < p->r.size(); ++k) x.push_back(100 * p->r[k]), y.push_back(p->u[k] / amplitude);
    series.push_back({{"label", label}, {"x", x}, {"y", y}, {"style", "dashed"}});
  }
  return {{"kind", "plot"}, {"title", title}, {"xlabel", "r along +x [cm]"}, {"ylabel", "u_r / w₀"}, {"xscale", "linear"},
          {"yscale", "linear"}, {"series", series}, {"caption", caption}};
}

TEST(FullSphericalWave, PaperResolution) {
  omp_set_num_threads(2);
  const auto paper = paper_errors();
  const auto cases = paper_cases();
  const std::vector<double> times = {1e-5, 2e-5, 3e-5, 7e-5};
  json rows = json::array();
  std::map<std::string, Result> results;  // reading/case → result
  for (Reading rd : {Reading::octant, Reading::cube}) {
    for (const auto& c : cases) {
      Config cfg;
      cfg.reading = rd;
      cfg.spacing = paper_spacing(rd);
      cfg.times = times;
      cfg.keep_profiles = true;
      cfg.keep_slices = c.key() == "pmb_quadratic" || c.key() == "lps_inverse_distance";
      auto res = run(c, cfg);
      EXPECT_EQ(res.n_free + (res.n_real - res.n_free), paper_particles);  // body = 531414 with the layer source
      const auto& m3 = res.metrics[2];
      const auto& m7 = res.metrics[3];
      rows.push_back({name(rd), c.label, 100 * cfg.spacing, res.n_real, res.bonds, res.dt, res.steps, m3.l2, m3.max, m3.l2_velocity,
                      m7.l2, m7.max, res.stable_step_seconds, res.setup_seconds, res.run_seconds, res.peak_rss_mb});
      results[std::string(name(rd)) + "/" + c.key()] = std::move(res);
    }
  }
  test::record_data(problem, "01_paper_resolution",
                    {{"kind", "table"},
                     {"title", "Paper resolution, source \"layer\": errors, cost and memory (2 OpenMP threads)"},
                     {"columns", {"reading", "case", "Δx [cm]", "particles", "bond sides", "Δt [s]", "steps", "e₂ at 3×10⁻⁵ s",
                                  "e_∞/w₀ at 3×10⁻⁵ s", "e₂(v_r) at 3×10⁻⁵ s", "e₂ at 7×10⁻⁵ s", "e_∞/w₀ at 7×10⁻⁵ s",
                                  "stable step [s]", "set-up [s]", "run [s]", "peak RSS [MB]"}},
                     {"rows", rows},
                     {"caption",
                      "e₂ = relative L2 error of u_r and e_∞ = max |u_r − u_r,exact| / w₀ over the free particles with "
                      "max(|x|,|y|,|z|) > r₀ + δ and r ≤ r₀ + c_p t (full-body sums; definitions in the text below). "
                      "Stable step = Lanczos on a small copy (0 when an earlier case had the same configuration); set-up = particles, "
                      "families, model, first forces; run = velocity Verlet to 7×10⁻⁵ s "
                      "with the error evaluations. Peak RSS = the process's resident-set high-water mark during the case "
                      "(reset before each case). Paper (Deryugin et al. 2023 §9, reading and metric not stated): LPS ω = 1/r " + percent(paper.lps_inverse_distance) +
                          ", LPS ω = 1 " + percent(paper.lps_constant) + "."}});

  // Profiles along +x at each time (seed figs 9.1 and 9.4 show t = 3×10⁻⁵ s).
  const char* tnames[] = {"1", "2", "3", "7"};
  for (Reading rd : {Reading::octant, Reading::cube}) {
    for (std::size_t k = 0; k < times.size(); ++k) {
      if (rd == Reading::cube && k != 2) continue;
      std::vector<std::pair<std::string, const Profile*>> pmb, lps;
      for (const auto& c : cases) {
        const auto& res = results.at(std::string(name(rd)) + "/" + c.key());
        (c.model == "pmb" ? pmb : lps).push_back({c.label, &res.profiles[k]});
      }
      const std::string tt = std::string(tnames[k]) + "×10⁻⁵ s";
      const std::string prefix = std::string("0") + (rd == Reading::octant ? "2" : "3") + "_profile_" + name(rd) + "_t" + tnames[k];
      test::record_data(problem, prefix + "_pmb",
                        profile_plot("PMB, six ω: u_r along +x at t = " + tt + " (" + name(rd) + ", Δx = " + fmt(100 * paper_spacing(rd)) + " cm)", pmb,
                                     "Deryugin et al. 2023 fig. 9.1. Particles on the x axis; the analytic curve is u_r(r, t) of docs/verification/analytic_solutions.md."));
      test::record_data(problem, prefix + "_lps",
                        profile_plot("LPS, ω = 1 and ω = 1/r: u_r along +x at t = " + tt + " (" + name(rd) + ", Δx = " + fmt(100 * paper_spacing(rd)) + " cm)", lps,
                                     "Deryugin et al. 2023 fig. 9.4."));
    }
  }

  // Error per ω (seed fig 9.2): e₂ and e_∞ at 3×10⁻⁵ s against the case index, and
  // the pointwise error along the ray.
  {
    json series = json::array();
    for (Reading rd : {Reading::octant, Reading::cube}) {
      std::vector<double> x, l2, mx;
      for (std::size_t k = 0; k < cases.size(); ++k) {
        const auto& m = results.at(std::string(name(rd)) + "/" + cases[k].key()).metrics[2];
        x.push_back(static_cast<double>(k));
        l2.push_back(m.l2);
        mx.push_back(m.max);
      }
      series.push_back({{"label", std::string("e₂, ") + name(rd)}, {"x", x}, {"y", l2}, {"style", "points"}});
      series.push_back({{"label", std::string("e_∞/w₀, ") + name(rd)}, {"x", x}, {"y", mx}, {"style", "points"}});
    }
    series.push_back({{"label", "paper (LPS): " + percent(paper.lps_constant) + ", " + percent(paper.lps_inverse_distance)},
                      {"x", {6, 7}}, {"y", {paper.lps_constant, paper.lps_inverse_distance}}, {"style", "points"}});
    test::record_data(problem, "04_error_per_case",
                      {{"kind", "plot"}, {"title", "Error at t = 3×10⁻⁵ s per case (seed fig 9.2)"}, {"xlabel",
                       "case: 0 constant, 1 triangular, 2 quadratic, 3 semi-elliptical, 4 exponential, 5 Gaussian (PMB); 6 LPS ω = 1, 7 LPS ω = 1/r"},
                       {"ylabel", "relative error"}, {"xscale", "linear"}, {"yscale", "log"}, {"series", series}});
    json ray = json::array();
    for (const auto& c : cases) {
      const auto& p = results.at("octant/" + c.key()).profiles[2];
      std::vector<double> x, y;
      for (std::size_t k = 0; k < p.r.size(); ++k) x.push_back(100 * p.r[k]), y.push_back((p.u[k] - p.exact[k]) / amplitude);
      ray.push_back({{"label", c.label}, {"x", x}, {"y", y}, {"style", "line"}});
    }
    test::record_data(problem, "05_error_along_ray",
                      {{"kind", "plot"}, {"title", "Pointwise error (u_r − u_r,exact)/w₀ along +x at t = 3×10⁻⁵ s (octant, Δx = 0.5 cm)"},
                       {"xlabel", "r [cm]"}, {"ylabel", "error / w₀"}, {"xscale", "linear"}, {"yscale", "linear"}, {"series", ray}});
  }

  // Schlieren images (seed figs 9.3, 9.5).
  for (Reading rd : {Reading::octant, Reading::cube})
    for (const std::string key : {"pmb_quadratic", "lps_inverse_distance"}) {
      const auto& res = results.at(std::string(name(rd)) + "/" + key);
      test::record_image(problem, std::string("06_schlieren_") + name(rd) + "_" + key, schlieren(res.slices),
                         std::string("Schlieren of |v| on z = 0, ") +
                             (key == "pmb_quadratic" ? "PMB quadratic (seed fig 9.3)" : "LPS ω = 1/r (seed fig 9.5)") + ", " + name(rd) + " reading",
                         "t = 1, 2, 3, 7 × 10⁻⁵ s from left to right, the whole plane −40 … 40 cm (the octant mirrored). "
                         "Colour = S/S_max with S = 0.8 |v| exp(−5 |v| / |v|_max) (seed eq 9.3 as printed; |v|_max per panel): "
                         "the scale peaks at |v| = |v|_max / 5, so weak waves show and the strongest motion near the source "
                         "fades. Grey: no particle (the cavity).");
    }

  // Closing note: the measured errors of all eight cases in both readings, against
  // the paper's anchors, with the phase speed that explains them.
  {
    std::ostringstream h;
    h.precision(3);
    h << "<p>Measured at the paper's resolution (N = 531414 in both readings, δ = 3.015 Δx, source \"layer\", partial "
         "volume seed001), errors at t = 3×10<sup>−5</sup> s (at 7×10<sup>−5</sup> s in brackets), e<sub>2</sub> = relative L2, "
         "e<sub>∞</sub> = max error / w<sub>0</sub>; c(Ω)/c<sub>p</sub> = phase speed of the driven wave on the lattice along x "
         "with the run's Δt; \"none\": the driven frequency (Ω with Verlet's shift) lies above the highest frequency of the lattice "
         "along x, so no wave of that frequency propagates and e<sub>2</sub> ≈ 1.</p><table><tr><th>case</th><th>octant Δx = 0.5 cm: e<sub>2</sub></th><th>e<sub>∞</sub></th>"
         "<th>c(Ω)/c<sub>p</sub></th><th>wall [s]</th><th>cube Δx = 1 cm: e<sub>2</sub></th><th>e<sub>∞</sub></th><th>c(Ω)/c<sub>p</sub></th>"
         "<th>wall [s]</th></tr>";
    double worst_rss = 0;
    for (const auto& c : cases) {
      h << "<tr><td>" << c.label << "</td>";
      for (Reading rd : {Reading::octant, Reading::cube}) {
        const auto& r = results.at(std::string(name(rd)) + "/" + c.key());
        const auto d = dispersion(c, paper_spacing(rd), paper_ratio, pd::PartialVolume::seed001, r.dt, t_compare);
        h << "<td>" << 100 * r.metrics[2].l2 << " % (" << 100 * r.metrics[3].l2 << " %)</td><td>" << 100 * r.metrics[2].max << " % ("
          << 100 * r.metrics[3].max << " %)</td><td>" << (d.speed_ratio > 0 ? fmt(d.speed_ratio, 3) : "none") << "</td><td>" << r.stable_step_seconds + r.setup_seconds + r.run_seconds
          << "</td>";
        worst_rss = std::max(worst_rss, r.peak_rss_mb);
      }
      h << "</tr>";
    }
    const auto& lr = results.at("octant/lps_inverse_distance").metrics[2];
    const auto& l1 = results.at("octant/lps_constant").metrics[2];
    h << "</table><p>Peak resident memory of any case: " << worst_rss << " MB (2 OpenMP threads; wall times on a shared 2-core "
      << "machine). Paper anchors (Deryugin et al. 2023 §9; metric and reading not stated): LPS ω = 1/r " << percent(paper.lps_inverse_distance)
      << ", LPS ω = 1 " << percent(paper.lps_constant) << ". Ours in the octant reading: e<sub>2</sub> " << 100 * lr.l2 << " % and "
      << 100 * l1.l2 << " %, i.e. " << lr.l2 / paper.lps_inverse_distance << " and " << l1.l2 / paper.lps_constant
      << " times the paper's; e<sub>∞</sub> " << 100 * lr.max << " % and " << 100 * l1.max << " %. "
      << "Why: at Δx = 0.5 cm the source's wavelength (≈ 6 cm for LPS) spans 12 spacings and δ = 1.5 cm is a quarter of it; the "
      << "lattice's dispersion makes the driven wave travel a few per cent slow (c(Ω)/c<sub>p</sub> above; velocity Verlet at the "
      << "stable step makes up part of it), and after the ~17 cm the wave has travelled by 3×10<sup>−5</sup> s the lag is a sizeable "
      << "fraction of a wavelength, which an L2 norm over the whole wave counts in full (see the dispersion table: the lag alone "
      << "predicts errors of the measured size). A pointwise error relative to the source amplitude w<sub>0</sub> weighs the "
      << "well-resolved near field, where the wave has not yet lagged, and comes much closer to the paper's figures: the paper's "
      << "metric is likely of that kind. The convergence section shows the error falling with Δx and what limits it at fixed m.</p>";
    test::record_data(problem, "00_closing_note", {{"kind", "text"}, {"title", "Closing note: the eight cases at the paper's resolution"}, {"html", h.str()}});
  }

  // Gates: the two qualitative claims of the seed, in the octant reading
  // (Δx = 0.5 cm, the finer of the two readings).
  double best_other = 1e9;
  for (const auto& c : cases)
    if (c.model == "pmb" && c.key() != "pmb_quadratic") best_other = std::min(best_other, results.at("octant/" + c.key()).metrics[2].l2);
  test::record_gate({.id = "spherical_wave.paper.pmb_quadratic_best",
                     .claim = "PMB with the quadratic ω shall have the smallest L2 error of the six PMB influence functions at t = 3×10⁻⁵ s (octant, paper resolution)",
                     .measured = results.at("octant/pmb_quadratic").metrics[2].l2 / best_other, .expected = 1.0, .tolerance = 0, .compare = test::Compare::at_most,
                     .tolerance_reason = "a ranking: the ratio to the best of the other five must be below 1",
                     .source = "[deryugin2023] §9: \"the best convergence to the analytic solution is with the quadratic bond stiffness function\"", .unit = "", .problem = problem});
  test::record_gate({.id = "spherical_wave.paper.lps_inverse_distance_better",
                     .claim = "LPS with ω = 1/r shall be closer to the analytic solution than LPS with ω = 1 at t = 3×10⁻⁵ s (octant, paper resolution)",
                     .measured = results.at("octant/lps_inverse_distance").metrics[2].l2 / results.at("octant/lps_constant").metrics[2].l2, .expected = 1.0, .tolerance = 0,
                     .compare = test::Compare::at_most, .tolerance_reason = "a ranking: the ratio must be below 1", .source = "[deryugin2023] §9: " + percent(paper.lps_inverse_distance) + " (ω = 1/r) < " + percent(paper.lps_constant) + " (ω = 1)", .unit = "", .problem = problem});
  double worst_rss = 0;
  for (const auto& [k, r] : results) worst_rss = std::max(worst_rss, r.peak_rss_mb);
  test::record_gate({.id = "spherical_wave.paper.memory", .claim = "Every paper-resolution case shall fit the 24 GB machine (peak resident set, MB)",
                     .measured = worst_rss, .expected = 24000, .tolerance = 0, .compare = test::Compare::at_most, .tolerance_reason = "the machine's memory (issue 4)", .source = "[pdmpm] docs/verification/spherical_wave.md; [deryugin2023] §9", .unit = "MB", .problem = problem});
}

// The octant with symmetry planes at Δx is the full cube at Δx: same step,
// same answer (the metric sums over the full body).
TEST(FullSphericalWave, OctantEqualsCubeAtOneCentimetre) {
  omp_set_num_threads(2);
  for (const auto& c : {find_case("lps", pd::Influence::inverse_distance), find_case("pmb", pd::Influence::quadratic)}) {
    Config o;
    o.reading = Reading::octant;
    o.spacing = 0.01;
    o.times = {t_compare, t_end};
    Config q = o;
    q.reading = Reading::cube;
    const auto ro = run(c, o), rq = run(c, q);
    double diff = 0;
    for (std::size_t k = 0; k < ro.metrics.size(); ++k)
      diff = std::max({diff, std::abs(ro.metrics[k].l2 - rq.metrics[k].l2) / rq.metrics[k].l2, std::abs(ro.metrics[k].max - rq.metrics[k].max) / rq.metrics[k].max});
    test::record_gate({.id = "spherical_wave.symmetry." + c.key(),
                       .claim = "The octant with three symmetry planes at Δx = 1 cm shall reproduce the full cube at Δx = 1 cm (" + c.label +
                           ", e₂ and e_∞ at 3 and 7 ×10⁻⁵ s)",
                       .measured = diff, .expected = 1e-9, .tolerance = 0, .compare = test::Compare::at_most,
                       .tolerance_reason = "the same lattice operator on the symmetric modes; only summation order differs (round-off ~1e-13)",
                       .source = "[pdmpm] docs/discretisation.md (mirror ghosts, solver/bc/symmetry.hpp)", .unit = "", .problem = problem});
  }
}

// Variants at t = 3×10⁻⁵ s on the octant cut at 21 cm (which the wave does not
// reach by then; gated below): where the source's displacement is prescribed,
// and the partial-volume rule, with the lattice dispersion that explains the
// errors. The cube reading at Δx = 1 cm is the octant at 1 cm (gated above).
TEST(FullSphericalWave, SourcePartialVolumeAndDispersion) {
  omp_set_num_threads(2);
  json source_rows = json::array(), pv_rows = json::array();
  for (Reading rd : {Reading::octant, Reading::cube})
    for (const auto& c : paper_cases()) {
      std::map<std::string, Metrics> m;
      std::map<std::string, double> dts;
      for (auto [src, pv] : {std::pair{Source::layer, pd::PartialVolume::seed001}, {Source::points, pd::PartialVolume::seed001},
                             {Source::layer, pd::PartialVolume::extended}}) {
        Config cfg;
        cfg.source = src;
        cfg.partial_volume = pv;
        cfg.spacing = paper_spacing(rd);
        cfg.extent = 0.21;
        const auto res = run(c, cfg);
        const std::string key = std::string(name(src)) + "/" + std::string(name(pv));
        m[key] = res.metrics.back();
        dts[std::string(name(pv))] = res.dt;
      }
      source_rows.push_back({name(rd), c.label, m["layer/seed001"].l2, m["points/seed001"].l2, m["layer/seed001"].max, m["points/seed001"].max});
      if (rd == Reading::cube) continue;
      for (auto pv : {pd::PartialVolume::seed001, pd::PartialVolume::extended}) {
        const std::string pvn(name(pv));
        const double dt = dts[pvn], dx = paper_spacing(rd);
        const auto along = dispersion(c, dx, paper_ratio, pv, dt, t_compare);
        const auto diag = dispersion(c, dx, paper_ratio, pv, dt, t_compare, Vec<3>(1, 1, 1));
        const auto exact_time = dispersion(c, dx, paper_ratio, pv, 0.0, t_compare);
        pv_rows.push_back({c.label, pvn, along.long_wave_ratio, exact_time.speed_ratio, along.speed_ratio, diag.speed_ratio,
                           along.phase_error_l2, diag.phase_error_l2, m["layer/" + pvn].l2, m["layer/" + pvn].max});
      }
    }
  test::record_data(problem, "07_source_choice",
                    {{"kind", "table"},
                     {"title", "Source choice: error at t = 3×10⁻⁵ s with the analytic displacement on a δ-thick layer or on the 27 inner points"},
                     {"columns", {"reading", "case", "e₂ layer", "e₂ points", "e_∞/w₀ layer", "e_∞/w₀ points"}},
                     {"rows", source_rows},
                     {"caption",
                      "layer: the cavity (27 sites) is empty and the particles with r₀ < max(|x|,|y|,|z|) ≤ r₀ + δ follow the analytic "
                      "solution, so every free particle sees the exact field wherever its bonds reach into the source. points: the 27 "
                      "sites with max(|x|,|y|,|z|) ≤ r₀ follow it (the seed's \"faces of the inner cube\"; inside r < r₀ the homogeneous "
                      "expansion g(t) x/r₀) and all 531414 others are free. Both measured on the same particles (outside r₀ + δ)."}});
  test::record_data(problem, "08_dispersion",
                    {{"kind", "table"},
                     {"title", "Why the error is what it is: phase speed of the driven wave on the lattice (octant, Δx = 0.5 cm, m = 3.015)"},
                     {"columns", {"case", "partial volume", "c(k→0)/c_p", "c(Ω)/c_p, exact time", "c(Ω)/c_p, Verlet Δt, along x",
                                  "… along (1,1,1)", "e₂ from the lag alone, x", "… (1,1,1)", "e₂ measured", "e_∞/w₀ measured"}},
                     {"rows", pv_rows},
                     {"caption",
                      "c(k→0): long-wave speed of the lattice (its effective P-wave modulus; PMB's micromodulus is calibrated on the "
                      "continuum, LPS's weighted volume m is summed on the lattice). c(Ω): phase speed of the wave the source drives at "
                      "Ω = 2π/T, from the lattice dispersion relation ω(k) (one force evaluation per k on a block), with and without the "
                      "velocity-Verlet shift sin(ΩΔt/2) = ω(k)Δt/2. A phase speed off by a few % puts the wave a sizeable part of a "
                      "wavelength (c_p T ≈ 5.5–6.1 cm) out of place after the ~17 cm it travels by 3×10⁻⁵ s; the 'lag alone' columns are "
                      "the L2 error such a lag gives for a far field with no amplitude error. Where the long-wave speed is too high (PMB "
                      "constant, exponential and Gaussian with the 'extended' partial volume) it cancels part of the dispersion at this "
                      "frequency and the error drops: two errors offsetting each other at one Δx, not convergence."}});
}

// Time-step sensitivity: velocity Verlet's phase error has the opposite sign of
// the lattice's dispersion, so the step changes the measured error.
TEST(FullSphericalWave, TimeStep) {
  omp_set_num_threads(2);
  json rows = json::array();
  for (const auto& c : {find_case("lps", pd::Influence::inverse_distance), find_case("pmb", pd::Influence::quadratic)})
    for (double safety : {0.8, 0.4, 0.2, 0.1}) {
      Config cfg;
      cfg.extent = 0.21;
      cfg.safety = safety;
      const auto res = run(c, cfg);
      rows.push_back({c.label, safety, res.dt, res.dt_stable, res.metrics.back().l2, res.metrics.back().max,
                      dispersion(c, cfg.spacing, cfg.ratio, cfg.partial_volume, res.dt, t_compare).speed_ratio});
    }
  test::record_data(problem, "09_time_step",
                    {{"kind", "table"},
                     {"title", "Time step: error at t = 3×10⁻⁵ s (octant, Δx = 0.5 cm) for Δt = T/⌈T/(f Δt_stable)⌉"},
                     {"columns", {"case", "f", "Δt [s]", "Δt_stable (Lanczos) [s]", "e₂", "e_∞/w₀", "c(Ω)/c_p along x"}},
                     {"rows", rows},
                     {"caption", "All other runs use f = 0.8."}});
}

// Cutting the octant at 21 cm changes nothing before the wave gets there: the
// fast tier and the convergence study rely on it.
TEST(FullSphericalWave, TruncatedOctantIsExactBeforeTheFrontArrives) {
  omp_set_num_threads(2);
  const auto c = find_case("lps", pd::Influence::inverse_distance);  // the faster wave
  Config full;
  full.times = {t_compare};
  Config cut = full;
  cut.extent = 0.21;
  const auto a = run(c, full), b = run(c, cut);
  const double diff = std::max(std::abs(a.metrics[0].l2 - b.metrics[0].l2) / a.metrics[0].l2, std::abs(a.metrics[0].max - b.metrics[0].max) / a.metrics[0].max);
  test::record_gate({.id = "spherical_wave.truncation", .claim = "The octant cut at 21 cm shall give the errors of the 40 cm octant at t = 3×10⁻⁵ s (LPS ω = 1/r, Δx = 0.5 cm)",
                     .measured = diff, .expected = 1e-4, .tolerance = 0, .compare = test::Compare::at_most,
                     .tolerance_reason = "the reported errors carry 3–4 significant digits, so the cut must not move them by 1e-4; the front "
                     "(c_p = 6.1 km/s) is at 19.4 cm and only the lattice's small precursor ahead of it (the force reaches δ per "
                     "step) touches the cut: measured 2e-6",
                     .source = "[pdmpm] docs/verification/spherical_wave.md (causality of the wave)", .unit = "", .problem = problem});
}

}  // namespace
}  // namespace pdmpm
