// Gates of the dog-bone tensile test (Noorian et al. §3-1; docs/verification/dogbone.md):
// a plane-stress steel specimen pulled to fracture, pure MPM and the adaptive SBPD–MPM
// hybrid (verification/scenes/dogbone/).
//
// Homogeneous answer. The J2 law works on the log strain ε and the rotated Kirchhoff
// stress τ (mpm_uniaxial_j2 gate): τ = E ε up to yield, τ = σ_y + E_t (ε − σ_y/E) beyond.
// In uniaxial stress the load over the initial section is F/A₀ = σ A/A₀ = (τ/J)(λ₂λ₃) = τ/λ₁,
// so the engineering curve is S(e) = τ(ln(1 + e)) / (1 + e), e the engineering strain.
// Considère: dS/dε = 0 ⇔ dτ/dε = τ; with linear hardening dτ/dε = E_t, so the maximum load
// lies at τ = E_t, i.e. ε_c = σ_y/E + 1 − σ_y/E_t, S_max = E_t exp(−ε_c).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "benchmarks/perf/stats.hpp"
#include "solver/io/scene.hpp"
#include "verification/support/gate.hpp"
#include "verification/support/scene_gate.hpp"
#include "verification/support/thread_count.hpp"

namespace pdmpm {
namespace {

using test::Compare;
using test::Gate;
using Json = nlohmann::json;

const char* kProblem = "dogbone";
const char* kSource = "[noorian] §3-1 (dog-bone, material and loading); docs/verification/dogbone.md";

// The homogeneous bilinear J2 answer in engineering measures.
struct Homogeneous {
  double E, sy, Et;
  explicit Homogeneous(const io::Scene& s)
      : E(s.material.E), sy(s.hardening.yield_stress), Et(s.hardening.tangent_modulus) {}
  double tau(double eps) const { return eps <= sy / E ? E * eps : sy + Et * (eps - sy / E); }
  double stress(double e) const { return tau(std::log1p(e)) / (1.0 + e); }
  double considere_log_strain() const { return sy / E + 1.0 - sy / Et; }
  double max_stress() const { return Et * std::exp(-considere_log_strain()); }
  double considere_strain() const { return std::expm1(considere_log_strain()); }
};

// One run as the report plots it: extensometer strain, load over the initial gauge
// section, energies, and the first time a particle failed.
struct Curve {
  std::vector<double> t, e, S, kinetic, internal;
  double first_failure = std::numeric_limits<double>::infinity();
  double wall = 0.0;
  std::size_t peak = 0;                                           // index of the maximum load
  std::size_t failure = std::numeric_limits<std::size_t>::max();  // first history row with a failure
  test::GateRun run;  // its outputs: summary.json (particle-steps, wall time per phase), history, fields.h5
};

// Gauge section A₀ from the lattice: the sites across the parallel length times Δx times
// the thickness (12.5 mm = 10 Δx at Δx = 1.25 mm, so A₀ is the nominal 37.5 mm²).
double gauge_section(const io::Scene& s) {
  const double width = 12.5e-3;
  return std::round(width / s.spacing) * s.spacing * s.measure;
}

// `mpm`: the MPM run's history, whose internal energy is the stored part and whose
// plastic work is a column of its own (the hybrid's history has the stored part only).
Curve run_curve(const io::Scene& scene, const std::string& tag, bool mpm) {
  const auto run = test::run_for_gate(scene, kProblem, tag);
  Curve c;
  c.run = run;
  c.wall = run.summary.value("wall_time_s", 0.0);
  c.t = run.history("time");
  const auto ul = run.history("probe_ext_left_ux"), ur = run.history("probe_ext_right_ux");
  const auto F = run.history("reaction_pulled_x");
  c.kinetic = run.history("kinetic_energy");
  c.internal = run.history("internal_energy");
  const auto failed = run.history(mpm ? "failed_particles" : "onsets");
  if (mpm) {
    const auto wp = run.history("plastic_work");
    for (std::size_t k = 0; k < c.internal.size(); ++k) c.internal[k] += wp[k];
  }
  const double L0 = 0.070625 - 0.053125;  // the probes' sites (scene [[probe]])
  const double A0 = gauge_section(scene);
  for (std::size_t k = 0; k < c.t.size(); ++k) {
    c.e.push_back((ur[k] - ul[k]) / L0);
    c.S.push_back(F[k] / A0);
    if (failed[k] > 0 && !std::isfinite(c.first_failure)) {
      c.first_failure = c.t[k];
      c.failure = k;
    }
    if (c.S[k] > c.S[c.peak]) c.peak = k;
  }
  return c;
}

// "Before necking": from t_lo to the maximum load (Considère's own definition of the
// onset of diffuse necking), and before the first failure. Largest |S − S_h(e)| / S_h(e).
double worst_against_homogeneous(const Curve& c, const Homogeneous& h, double t_lo) {
  double worst = 0.0;
  for (std::size_t k = 0; k <= c.peak; ++k) {
    if (c.t[k] >= c.first_failure || c.t[k] < t_lo) continue;
    worst = std::max(worst, std::abs(c.S[k] - h.stress(c.e[k])) / h.stress(c.e[k]));
  }
  return worst;
}

// The start-up transient: the 0.2 ms ramp plus two transits of a plastic wave
// (c_p = √(E_t/ρ) = 431 m/s) over the 80 mm between the grips' boxes, 0.37 ms.
double transient_end(const io::Scene& s) {
  const double cp = std::sqrt(s.hardening.tangent_modulus / s.material.rho);
  return 2e-4 + 2.0 * 0.080 / cp;
}

// S of curve `c` at time `time` (linear interpolation between history rows; NaN outside).
double stress_at_time(const Curve& c, double time) {
  for (std::size_t k = 1; k < c.t.size(); ++k)
    if (c.t[k] >= time && c.t[k - 1] < time) {
      const double w = (time - c.t[k - 1]) / (c.t[k] - c.t[k - 1]);
      return (1 - w) * c.S[k - 1] + w * c.S[k];
    }
  return std::nan("");
}

Json series(const std::string& label, const std::vector<double>& x, const std::vector<double>& y,
            const std::string& style = "line") {
  return {{"label", label}, {"x", x}, {"y", y}, {"style", style}};
}

std::vector<double> scaled(const std::vector<double>& v, double f) {
  std::vector<double> out;
  for (double x : v) out.push_back(x * f);
  return out;
}

// Largest K / (U + W_p) from t_lo to the maximum load, before the first failure.
double kinetic_ratio(const Curve& c, double t_lo) {
  double r = 0.0;
  for (std::size_t k = 0; k <= c.peak; ++k)
    if (c.t[k] >= t_lo && c.t[k] < c.first_failure && c.internal[k] > 0) r = std::max(r, c.kinetic[k] / c.internal[k]);
  return r;
}

// The engineering curves of both runs over the homogeneous answer (report plot `name`).
void curve_plot(const std::string& name, const std::string& title, const Curve& m, const Curve& y,
                const Homogeneous& h) {
  std::vector<double> eh, sh;
  const double e_end = std::max(m.e.back(), y.e.back());
  for (int n = 0; n <= 400; ++n) {
    const double e = e_end * n / 400.0;
    eh.push_back(e);
    sh.push_back(h.stress(e) / 1e6);
  }
  Json plot = Json::array();
  plot.push_back(series("homogeneous bilinear J2", eh, sh, "dashed"));
  plot.push_back(series("pure MPM", m.e, scaled(m.S, 1e-6)));
  plot.push_back(series("hybrid, expand/shrink", y.e, scaled(y.S, 1e-6)));
  plot.push_back(series("Considère maximum", {h.considere_strain()}, {h.max_stress() / 1e6}, "points"));
  test::record_data(kProblem, name,
                    {{"kind", "plot"},
                     {"title", title},
                     {"xlabel", "engineering strain e (extensometer, 17.5 mm)"},
                     {"ylabel", "F / A₀ (MPa)"},
                     {"xscale", "linear"},
                     {"yscale", "linear"},
                     {"series", plot},
                     {"caption",
                      "Δx = 1.25 mm, cell 2Δx, δ = 5Δx, right grip pulled at 10 m/s (0.2 ms ramp). The "
                      "paper prints no numbers: its experiment, FE and hybrid curves agree up to necking."}});
}

// Hybrid against pure MPM at equal times (both grips follow the same clock) from the end of
// the start-up transient to the maximum load and the first failure of either: largest
// |S_hybrid / S_mpm − 1|. The hybrid's step is the PD stable step (0.2 µs against MPM's
// 0.36 µs at Δx = 1.25 mm): two time discretisations of the same grid. During the transient
// S(e) is not single-valued, so times, not strains.
double hybrid_against_mpm(const Curve& m, const Curve& y, double t_lo) {
  double worst = 0.0;
  const double t_stop = std::min({m.first_failure, y.first_failure, m.t[m.peak]});
  for (std::size_t k = 0; k < y.t.size(); ++k) {
    if (y.t[k] < t_lo || y.t[k] > t_stop) continue;
    const double s_m = stress_at_time(m, y.t[k]);
    if (std::isfinite(s_m)) worst = std::max(worst, std::abs(y.S[k] - s_m) / s_m);
  }
  return worst;
}

// The gate on hybrid_against_mpm; `where` prefixes the claim (the resolution, when not the scenes').
void record_agreement(const std::string& id, const std::string& where, double measured) {
  test::record_gate(Gate{.id = id,
                         .claim = where +
                             "the hybrid's engineering stress shall equal the pure-MPM one within 0.5 % at equal "
                             "times, from the end of the start-up transient to the maximum load and the first "
                             "failure of either",
                         .measured = measured,
                         .expected = 0.005,
                         .compare = Compare::at_most,
                         .tolerance_reason =
                             "before any failure the hybrid is the MPM grid alone; it differs only by its smaller "
                             "(PD-stable) time step, an O(Δt) difference in the dynamic response, and by the "
                             "interpolation between history samples",
                         .source = kSource,
                         .unit = "",
                         .problem = kProblem});
}

// The two runs of a test: the MPM scene and the hybrid (expand_shrink) scene as written, to `end_time`.
struct Runs {
  io::Scene scene;
  Curve m, y;
  double t_lo;
};
Runs run_both(double end_time, const std::string& tag) {
  auto mpm_scene = io::parse_scene(test::scene_file("dogbone/mpm.toml"));
  auto hyb_scene = io::parse_scene(test::scene_file("dogbone/hybrid_expand_shrink.toml"));
  for (io::Scene* s : {&mpm_scene, &hyb_scene}) {
    s->time.end_time = end_time;
    s->output.frames = 5;
  }
  Runs r{mpm_scene, run_curve(mpm_scene, "mpm_" + tag, true), run_curve(hyb_scene, "hybrid_" + tag, false),
         transient_end(mpm_scene)};
  for (const auto* c : {&r.m, &r.y})
    std::cout << tag << ": peak S " << c->S[c->peak] << " Pa at e " << c->e[c->peak] << " (t " << c->t[c->peak]
              << " s), first failure " << c->first_failure << " s, wall " << c->wall << " s\n";
  return r;
}

// Fast tier: the scenes' own resolution (Δx = 1.25 mm, 10 particles across the gauge), to
// 5.6 ms: past the maximum load (≈ 5.55 ms with the moving grip) and before the neck
// separates (≈ 5.9 ms); the two runs cost ≈ 85 s of CPU. The curve, quasi-statics and
// Considère are gated in the full tier (the curve and K/U fail there: the start-up transient
// at this rate, docs/verification/dogbone.md); here they are measured and shown.
TEST(FastDogbone, HybridAgreesWithMpmBeforeFailure) {
  const Runs r = run_both(5.6e-3, "fast");
  const Curve &m = r.m, &y = r.y;
  const double t_lo = r.t_lo;
  const Homogeneous h(r.scene);
  const double worst = hybrid_against_mpm(m, y, t_lo);
  record_agreement("dogbone.hybrid.agrees_with_mpm", "", worst);

  // Report: the curves and the energy ratio.
  curve_plot("01_engineering_curve", "Engineering stress–strain curve (fast tier, to 5.6 ms)", m, y, h);
  auto energy_ratio = [](const Curve& c) {
    std::vector<double> x, ratio;
    for (std::size_t k = 0; k < c.t.size(); ++k)
      if (c.internal[k] > 0) {
        x.push_back(c.t[k] * 1e3);
        ratio.push_back(std::max(c.kinetic[k] / c.internal[k], 1e-8));
      }
    return std::make_pair(x, ratio);
  };
  const auto [xm, rm] = energy_ratio(m);
  const auto [xy, ry] = energy_ratio(y);
  test::record_data(kProblem, "02_kinetic_over_internal",
                    {{"kind", "plot"},
                     {"title", "Kinetic over internal energy"},
                     {"xlabel", "t (ms)"},
                     {"ylabel", "K / U"},
                     {"xscale", "linear"},
                     {"yscale", "log"},
                     {"series",
                      Json::array({series("pure MPM, K / (stored + plastic work)", xm, rm),
                                   series("hybrid, K / stored energy", xy, ry, "dashed")})},
                     {"caption",
                      "The ramp ends at 0.2 ms; the gated window starts at 0.57 ms (end of the start-up "
                      "transient). No particle fails in either run before 5.6 ms."}});
  test::record_data(
      kProblem, "03_measured",
      {{"kind", "table"},
       {"title", "Fast tier, measured: curve, quasi-statics and maximum load (gated in the full tier)"},
       {"columns",
        {"run", "max |S/S_h − 1| from 0.57 ms to the maximum load", "max K/(U + W_p), same window", "S_max (MPa)",
         "e at S_max", "Considère S_max (MPa)", "Considère e_c"}},
       {"rows",
        Json::array({Json::array({"pure MPM", worst_against_homogeneous(m, h, t_lo), kinetic_ratio(m, t_lo),
                                  m.S[m.peak] / 1e6, m.e[m.peak], h.max_stress() / 1e6, h.considere_strain()}),
                     Json::array({"hybrid, expand/shrink", worst_against_homogeneous(y, h, t_lo), "—",
                                  y.S[y.peak] / 1e6, y.e[y.peak], h.max_stress() / 1e6, h.considere_strain()})})},
       {"caption",
        "The neck forms in the gauge (material from x₀ = 70–80 mm) at e ≈ 0.89, earlier than Considère's "
        "homogeneous maximum; the moving grip did not move it (docs/verification/dogbone.md)."}});
}

// Full tier: the scenes as written (to 8 ms): the curve against the homogeneous answer, the
// quasi-statics, and the maximum load against Considère's.
TEST(FullDogbone, CurveQuasiStaticsAndConsidere) {
  const Runs r = run_both(8e-3, "full");
  const Curve &m = r.m, &y = r.y;
  const double t_lo = r.t_lo;
  const Homogeneous h(r.scene);
  const double dev_m = worst_against_homogeneous(m, h, t_lo);
  const double dev_y = worst_against_homogeneous(y, h, t_lo);
  curve_plot("04_engineering_curve_full", "Engineering stress–strain curve (full tier, the scenes to 8 ms)", m, y, h);
  const char* curve_reason =
      "the issue's bound: the homogeneous curve is exact for uniform uniaxial stress, so what remains is the "
      "extensometer's one-site resolution, the grid discretisation and inertia at the chosen rate";
  test::record_gate(Gate{.id = "dogbone.mpm.curve_before_necking",
                         .claim = "the pure-MPM engineering curve (extensometer strain e over 17.5 mm, load over the "
                                  "initial 12.5 × 3 mm section) shall follow the homogeneous bilinear J2 answer "
                                  "S = τ(ln(1 + e))/(1 + e) within 1 % from the end of the start-up transient "
                                  "(ramp + two plastic-wave transits, 0.57 ms) to the maximum load",
                         .measured = dev_m,
                         .expected = 0.01,
                         .compare = Compare::at_most,
                         .tolerance_reason = curve_reason,
                         .source = kSource,
                         .unit = "",
                         .problem = kProblem});
  test::record_gate(Gate{.id = "dogbone.hybrid.curve_before_necking",
                         .claim = "the same for the hybrid (expand_shrink) run (and before its first failure)",
                         .measured = dev_y,
                         .expected = 0.01,
                         .compare = Compare::at_most,
                         .tolerance_reason = curve_reason,
                         .source = kSource,
                         .unit = "",
                         .problem = kProblem});

  // Quasi-static: kinetic over internal energy (stored + plastic work) of the MPM run. The
  // hybrid is the same grid up to its first failure; its history has the stored energy only,
  // so its ratio is plotted, not gated. Window: the curve gate's.
  const double kr = kinetic_ratio(m, t_lo);
  test::record_gate(Gate{.id = "dogbone.kinetic_over_internal",
                         .claim = "the pure-MPM run shall be quasi-static: kinetic energy ≤ 1 % of the internal energy "
                                  "(stored + plastic work) from the end of the start-up transient (0.57 ms) to the "
                                  "maximum load",
                         .measured = kr,
                         .expected = 0.01,
                         .compare = Compare::at_most,
                         .tolerance_reason =
                             "explicit quasi-static practice asks for a kinetic energy of a few per cent "
                             "of the internal energy at most; 1 % is the stricter end, matching the "
                             "curve gate's 1 %",
                         .source = "[noorian] §3-1 (the test is quasi-static); docs/verification/dogbone.md",
                         .unit = "",
                         .problem = kProblem});

  // Considère: the maximum of S. The maximum is flat (S'' = −S/(1 + e)² there), so its value
  // is robust while its strain is not; the band on the value: the 1 % of the curve gate.
  test::record_gate(Gate{.id = "dogbone.mpm.max_stress_considere",
                         .claim = "the pure-MPM maximum engineering stress shall be the Considère value for linear "
                                  "hardening, S_max = E_t exp(−ε_c), ε_c = σ_y/E + 1 − σ_y/E_t (673 MPa), within 1 %",
                         .measured = m.S[m.peak],
                         .expected = h.max_stress(),
                         .tolerance = 0.01,
                         .compare = Compare::rel,
                         .tolerance_reason =
                             "the curve gate's 1 %: the maximum of a curve that follows the homogeneous "
                             "one within 1 % lies within 1 % of its maximum",
                         .source = "[considere1885] dF = 0 ⇔ dσ/dε = σ; docs/verification/dogbone.md",
                         .unit = "Pa",
                         .problem = kProblem});
  // Strain at the maximum, as a log strain: near ε_c, S = S_max (1 + x) e^{−x} ≈ S_max (1 − x²/2),
  // x = ε − ε_c, so a curve within 1 % of the homogeneous one may have its maximum anywhere with
  // x²/2 ≤ 1 %, |x| ≤ √0.02 = 0.141 (in e: 0.870 … 1.480 around 1.153, −25 % / +28 %).
  test::record_gate(Gate{.id = "dogbone.mpm.strain_at_max_stress",
                         .claim = "the extensometer log strain ln(1 + e) at the maximum load shall be Considère's "
                                  "ε_c = σ_y/E + 1 − σ_y/E_t (0.767) within ±0.141",
                         .measured = std::log1p(m.e[m.peak]),
                         .expected = h.considere_log_strain(),
                         .tolerance = std::sqrt(0.02),
                         .compare = Compare::abs,
                         .tolerance_reason =
                             "S is flat at its maximum: S ≈ S_max (1 − (ε − ε_c)²/2), so the 1 % of the curve gate "
                             "admits the maximum anywhere within |ε − ε_c| ≤ √0.02 = 0.141",
                         .source = "[considere1885]; docs/verification/dogbone.md",
                         .unit = "",
                         .problem = kProblem});
}

// Full tier: the paper's timing for the tensile test (its English abstract puts the "43 %"
// here): the hybrid's three modes of the dog-bone in one process, interleaved, one thread,
// to 5.6 ms — the fast tier's end, past the maximum load and before the MPM neck separates.
// No particle reaches the ductile criterion by then at this resolution
// (docs/verification/dogbone.md), so the adaptive modes run the grid alone: the table
// measures what the grid saves over pure SBPD on the deformation before fracture, with
// each mode's accuracy beside its time. Shown, not gated: the paper's savings include
// its PD regions, which do not form here.
constexpr int kDogboneTimingReps = 3;

TEST(FullDogbone, TimingTableOfTheThreeModes) {
  const test::ThreadCount one_thread(1);  // the table's claim; the full tier leaves OpenMP every core
  const std::vector<std::string> modes{"pd", "expand", "expand_shrink"};
  std::vector<std::vector<double>> wall(modes.size());
  std::vector<Curve> last(modes.size());
  io::Scene scene;
  for (int rep = 0; rep < kDogboneTimingReps; ++rep)
    for (std::size_t m = 0; m < modes.size(); ++m) {
      scene = io::parse_scene(test::scene_file("dogbone/hybrid_" + modes[m] + ".toml"));
      scene.time.end_time = 5.6e-3;
      scene.output.frames = 1;
      last[m] = run_curve(scene, "timing_" + modes[m], false);
      wall[m].push_back(last[m].wall);
    }
  const Homogeneous h(scene);
  const double t_lo = transient_end(scene);
  Json rows = Json::array();
  for (std::size_t m = 0; m < modes.size(); ++m) {
    const perf::Ratio ratio = perf::ratio_of_medians(wall[m], wall[0]);
    const Curve& c = last[m];
    const Json& ps = c.run.summary["particle_steps"];
    const Json& phases = c.run.summary["wall_time_phases"];
    const double pd_steps = ps.value("pd", 0.0), mpm_steps = ps.value("mpm", 0.0), total = phases.value("total", 1.0);
    // Largest |S − S_pd| / S_pd at equal times from the end of the start-up transient to pure
    // SBPD's maximum load: the accuracy the saving is bought at.
    double against_pd = 0.0;
    for (std::size_t k = 0; k < c.t.size(); ++k) {
      if (c.t[k] < t_lo || c.t[k] > last[0].t[last[0].peak]) continue;
      const double s_pd = stress_at_time(last[0], c.t[k]);
      if (std::isfinite(s_pd)) against_pd = std::max(against_pd, std::abs(c.S[k] - s_pd) / s_pd);
    }
    const int onsets = c.run.summary.value("events", Json::object()).value("onsets", 0);
    // The caption (and docs/verification/dogbone.md) read the adaptive modes as the grid
    // alone: a PD region forming before 5.6 ms makes that wrong, and they must be rewritten.
    if (m > 0) {
      EXPECT_EQ(onsets, 0) << modes[m] << ": a PD region formed; rewrite the table's reading";
    }
    rows.push_back({modes[m], perf::median(wall[m]), 1.0 - ratio.value, 1.0 - ratio.hi, 1.0 - ratio.lo,
                    phases.value("pd", 0.0) / total, phases.value("mpm", 0.0) / total,
                    1e9 * perf::median(wall[m]) / (pd_steps + mpm_steps), pd_steps / (pd_steps + mpm_steps),
                    worst_against_homogeneous(c, h, t_lo), against_pd, c.S[c.peak] / 1e6, c.e[c.peak], onsets});
  }
  test::record_data(
      kProblem, "05_timing",
      {{"kind", "table"},
       {"title", "The paper's timing for the tensile test, measured: the three modes in one process (to 5.6 ms)"},
       {"columns",
        {"mode", "median wall time (s)", "saving vs pd", "saving 95 % low", "saving 95 % high", "pd share", "mpm share",
         "ns per particle-step", "PD share of particle-steps", "max |S/S_h − 1| from 0.57 ms to the maximum load",
         "max |S/S_pd − 1| at equal times, same window", "S_max (MPa)", "e at S_max", "PD region onsets"}},
       {"rows", rows},
       {"caption",
        "Δx = 1.25 mm, δ = 5Δx, the hybrid's (PD-stable) step in every mode; " + std::to_string(kDogboneTimingReps) +
            " interleaved repetitions, one thread; saving = 1 − ratio of medians, bootstrap 95 % interval. No "
            "particle fails before 5.6 ms at this resolution, so the adaptive modes are the grid alone and pure "
            "SBPD's own accuracy (a 10-particle gauge with a 5-particle horizon) is in the row beside its time. "
            "The paper's abstract: 43 % saved on the tensile test."}});
}

// Angle (degrees, 0–90) between the load axis x and the principal axis of the points x
// weighted by w (w > 0 counts): the direction of a band or a crack through them; NaN for
// fewer than three points.
double angle_to_load(const std::vector<std::array<double, 2>>& x, const std::vector<double>& w) {
  double total = 0.0, mx = 0.0, my = 0.0;
  int n = 0;
  for (std::size_t k = 0; k < x.size(); ++k)
    if (w[k] > 0.0) {
      total += w[k], mx += w[k] * x[k][0], my += w[k] * x[k][1];
      ++n;
    }
  if (n < 3) return std::numeric_limits<double>::quiet_NaN();
  mx /= total, my /= total;
  double cxx = 0.0, cyy = 0.0, cxy = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k)
    if (w[k] > 0.0) {
      const double dx = x[k][0] - mx, dy = x[k][1] - my;
      cxx += w[k] * dx * dx, cyy += w[k] * dy * dy, cxy += w[k] * dx * dy;
    }
  return std::abs(0.5 * std::atan2(2.0 * cxy, cxx - cyy)) * 180.0 / std::numbers::pi;
}

// Reference positions (x, y) of a run's particles: its first frame's (t = 0, u = 0).
std::vector<std::array<double, 2>> reference_positions(const test::FieldsReader& f) {
  const auto pos = f.read(f.frames().front(), "position");
  std::vector<std::array<double, 2>> x(pos.size() / 3);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = {pos[3 * i], pos[3 * i + 1]};
  return x;
}

// Full tier: the scenes at half the spacing (fine_*.toml, Δx = 0.625 mm, 20 particles
// across the gauge), to 6.2 ms. At this spacing particles in the neck reach the ductile
// criterion before the neck separates (≈ 5.86 ms, none at 1.25 mm), so the hybrid forms PD
// regions: the fracture part of the test — first failure, the direction of the band and of
// the crack against Hill's localised-necking angle and the paper's ≈ 45°, the hybrid against
// MPM up to the first failure, and the region maps at first crack. Both runs ≈ 6 min of CPU.
TEST(FullDogbone, FractureAtHalfTheSpacing) {
  auto mpm_scene = io::parse_scene(test::scene_file("dogbone/fine_mpm.toml"));
  auto hyb_scene = io::parse_scene(test::scene_file("dogbone/fine_hybrid_expand_shrink.toml"));
  for (io::Scene* s : {&mpm_scene, &hyb_scene}) {
    s->time.end_time = 6.2e-3;
    s->output.frames = 32;  // every 0.2 ms
  }
  // The hybrid once more with both consistent options: transition particles' PD state over their
  // whole family (no ghost force on PD) and the elastic-state transfer (no spurious stress at
  // conversion, docs/models/hybrid.md).
  io::Scene consistent_scene = hyb_scene;
  consistent_scene.hybrid->coupling = hybrid::Coupling::full_state;
  consistent_scene.hybrid->plastic_transfer = hybrid::PlasticTransfer::elastic_state;
  const Curve m = run_curve(mpm_scene, "fine_mpm", true), y = run_curve(hyb_scene, "fine_hybrid", false);
  const Curve yc = run_curve(consistent_scene, "fine_hybrid_consistent", false);
  const double t_lo = transient_end(mpm_scene);
  const Homogeneous h(mpm_scene);
  record_agreement("dogbone.fine.hybrid.agrees_with_mpm", "at Δx = 0.625 mm ", hybrid_against_mpm(m, y, t_lo));

  // The band: a map of the MPM run's ε̄_p in the last frame before its first failure (in the
  // reference configuration). The crack: the direction of its failed particles at the end.
  const test::FieldsReader mf((m.run.dir / "fields.h5").string());
  const auto x0 = reference_positions(mf);
  const test::FrameInfo* before = &mf.frames().front();
  for (const auto& fr : mf.frames())
    if (fr.time < m.first_failure) before = &fr;
  auto ep = mf.read(*before, "eq_plastic_strain");
  const double ep_max = *std::max_element(ep.begin(), ep.end());
  for (double& v : ep) v /= ep_max;
  test::record_image(kProblem, "08_fine_band", test::damage_map(x0, ep, mpm_scene.spacing, 3),
                     "Equivalent plastic strain of the pure-MPM run at Δx = 0.625 mm, t = " +
                         std::to_string(before->time * 1e3).substr(0, 4) + " ms (before its first failure)",
                     "Reference configuration; blue 0, red the largest value (" + std::to_string(ep_max).substr(0, 4) +
                         "). The strain localises across the whole section where the gauge meets the pulled end's "
                         "fillet (x₀ ≈ 90–93 mm): no inclined band.");
  const auto failed = mf.read(mf.frames().back(), "failed");
  const double crack_angle = angle_to_load(x0, failed);
  double crack_x = 0.0, n_failed = 0.0;
  for (std::size_t i = 0; i < failed.size(); ++i)
    if (failed[i] > 0.0) crack_x += x0[i][0], n_failed += 1.0;
  crack_x /= std::max(n_failed, 1.0);
  test::record_gate(Gate{.id = "dogbone.fine.crack_angle",
                         .claim = "at Δx = 0.625 mm the crack (the pure-MPM run's failed particles at 6.2 ms) shall "
                                  "run at Hill's localised-necking angle arctan √2 = 54.7° to the load, within 5° "
                                  "(the paper reports a band at about 45°)",
                         .measured = crack_angle,
                         .expected = std::atan(std::sqrt(2.0)) * 180.0 / std::numbers::pi,
                         .tolerance = 5.0,
                         .compare = Compare::abs,
                         .tolerance_reason =
                             "a line across the 20-particle gauge is resolved to arctan(1/20) ≈ 3°; 5° leaves "
                             "room for the crack's one-particle steps. Hill's angle is the zero-extension "
                             "direction of a von Mises sheet in uniaxial tension",
                         .source = "[hill1952]; [noorian] §3-1; docs/verification/dogbone.md",
                         .unit = "°",
                         .problem = kProblem});

  // Region maps of both hybrids: the frame just after the first onset and the last.
  std::vector<test::Raster> after_onset, at_end;
  std::string times;
  for (const Curve* c : {&y, &yc}) {
    const test::FieldsReader yf((c->run.dir / "fields.h5").string());
    for (const test::FrameInfo* fr : {&yf.nearest(c->first_failure + 0.1e-3), &yf.frames().back()}) {
      const auto method = yf.read(*fr, "method");  // core::ParticleKind: 0 PD, 1 MPM, 2 transition, 3 removed
      const auto pos = yf.read(*fr, "position");
      std::vector<std::array<double, 2>> xy;
      std::vector<double> colour;
      for (std::size_t i = 0; i < method.size(); ++i) {
        if (method[i] == 3.0) continue;
        xy.push_back({pos[3 * i], pos[3 * i + 1]});
        colour.push_back(method[i] == 0.0 ? 1.0 : method[i] == 2.0 ? 0.66 : 0.0);
      }
      (fr == &yf.frames().back() ? at_end : after_onset).push_back(test::damage_map(xy, colour, hyb_scene.spacing, 2));
      if (c == &y) times += (times.empty() ? "" : " and ") + std::to_string(fr->time * 1e3).substr(0, 4) + " ms";
    }
  }
  std::vector<test::Raster> maps = after_onset;
  maps.insert(maps.end(), at_end.begin(), at_end.end());
  test::record_image(kProblem, "07_fine_regions", test::grid(maps, 2),
                     "Regions of the hybrid at Δx = 0.625 mm after its first onset (" + times +
                         "); left: as written, right: full_state coupling and elastic_state transfer",
                     "Red PD, yellow transition, blue MPM, in the deformed configuration; removed particles "
                     "left out. Top: just after the first onset, bottom: at 6.2 ms. As written the first region "
                     "(R_pd = 1.5δ) grows over the whole gauge, which fragments; with both consistent options it "
                     "stays where it formed (docs/verification/dogbone.md).");

  auto row = [&](const std::string& run, const Curve& c, const std::string& count_column) {
    const auto failures = c.run.history(count_column);
    double max_pd = 0.0, max_tips = 0.0;
    if (count_column == "onsets") {
      for (double v : c.run.history("pd_particles")) max_pd = std::max(max_pd, v);
      for (double v : c.run.history("tips")) max_tips = std::max(max_tips, v);
    }
    const bool failed_any = c.failure < c.t.size();
    return Json::array({run, c.S[c.peak] / 1e6, c.e[c.peak], failed_any ? c.first_failure * 1e3 : NAN,
                        failed_any ? c.e[c.failure] : NAN, failed_any ? c.S[c.failure] / 1e6 : NAN, failures.back(),
                        max_pd, max_tips});
  };
  test::record_data(kProblem, "06_fine_fracture",
                    {{"kind", "table"},
                     {"title", "Fracture at half the spacing (Δx = 0.625 mm, to 6.2 ms)"},
                     {"columns",
                      {"run", "S_max (MPa)", "e at S_max", "first failure (ms)", "e there", "S there (MPa)",
                       "failed particles / onsets at the end", "largest PD particle count", "most tips at once"}},
                     {"rows",
                      Json::array({row("pure MPM", m, "failed_particles"), row("hybrid, expand/shrink", y, "onsets"),
                                   row("hybrid, full_state + elastic_state", yc, "onsets")})},
                     {"caption",
                      "Considère: S_max = " + std::to_string(h.max_stress() / 1e6).substr(0, 5) +
                          " MPa at e = " + std::to_string(h.considere_strain()).substr(0, 5) +
                          ". Crack (the MPM run's failed particles): " + std::to_string(crack_angle).substr(0, 4) +
                          "° at x₀ = " + std::to_string(crack_x * 1e3).substr(0, 4) +
                          " mm (the gauge ends at 90.5 mm). Hill: 54.7°; the paper: ≈ 45°."}});
}

}  // namespace
}  // namespace pdmpm
