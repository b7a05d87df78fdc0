// One body, two methods: the plane-stress steel strips of verification/scenes/
// plastic_strip.toml and plastic_notched_strip.toml, integrated by elastoplastic PD
// (lps_plastic, as the files say) and by MPM J2 (the same scene with [model] type =
// "mpm": GIMP, MUSL, cell 2Δx). Dynamic runs, slow enough to be quasi-static.
//  (1) plain strip: the interior stress of each method follows the bilinear curve of
//      its own kinematics (PD: small strain; MPM: logarithmic strain, Kirchhoff stress);
//  (2) notched strip pulled to localisation: both load–displacement curves and both
//      bands of ε̄_p, with their difference reported (the methods localise differently).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "solver/io/scene.hpp"
#include "verification/gates/mpm_gate_util.hpp"
#include "verification/support/gate.hpp"
#include "verification/support/raster_image.hpp"
#include "verification/support/scene_gate.hpp"
#include "verification/support/strip_gauge.hpp"

namespace pdmpm {
namespace {

namespace mu = test::mpm_util;
const char* kProblem = "lps_plastic";

using test::as_mpm_j2;
using test::gauge_history;
using test::interpolate;

TEST(FastLpsPlasticSameBody, StripFollowsTheCurveInBothMethods) {
  const auto pd_scene = io::parse_scene(test::scene_file("plastic_strip.toml"));
  const double E = pd_scene.material.E, nu = pd_scene.material.nu;
  const double sy = pd_scene.hardening.yield_stress, Et = pd_scene.hardening.tangent_modulus;
  auto bilinear = [&](double e) { return e <= sy / E ? E * e : sy + Et * (e - sy / E); };
  // Gauge: 10–30 mm along the strip, the rows at least δ from both free edges.
  const double delta = pd_scene.delta, width = 0.01;
  std::vector<double> es_pd, ss_pd, es_mpm, ss_mpm, exact_e, exact_s;
  double worst_pd = 0.0, worst_mpm = 0.0, last_pd = 0.0;
  for (const bool pd : {true, false}) {
    const auto run = test::run_for_gate(pd ? pd_scene : as_mpm_j2(pd_scene), kProblem, pd ? "strip_pd" : "strip_mpm");
    for (const auto& g : gauge_history(run, 0.010, 0.030, delta, width - delta)) {
      // PD is small-strain: σ = bilinear(ε). MPM's J2 is bilinear in the log strain for the
      // Kirchhoff stress; Cauchy σ = τ/J with J = exp((1 − 2ν) τ/E) (plastic flow is isochoric).
      const double log_strain = std::log1p(g.strain), tau = bilinear(log_strain);
      const double exact = pd ? bilinear(g.strain) : tau * std::exp(-(1 - 2 * nu) * tau / E);
      const double error = g.strain > 0.25 * sy / E ? std::abs(g.stress - exact) / sy : 0.0;
      (pd ? worst_pd : worst_mpm) = std::max(pd ? worst_pd : worst_mpm, error);
      (pd ? es_pd : es_mpm).push_back(100 * g.strain);
      (pd ? ss_pd : ss_mpm).push_back(g.stress / 1e6);
      if (pd) last_pd = g.strain;
    }
  }
  ASSERT_GT(last_pd, 10 * sy / E) << "the strip must be pulled to 10 σ_y/E for this claim";
  for (double e = 0.0; e <= 100 * last_pd; e += 0.02) exact_e.push_back(e), exact_s.push_back(bilinear(e / 100) / 1e6);
  const std::string reason =
      "1 % of σ_y, the issue's bound: the dynamic residue of the finite pull rate (ramp over 20 wave transits, "
      "then ≈ 25 /s) and, in PD, the gauge's discrete strain measure; the material response is exact along this path";
  test::record_gate({.id = "lps_plastic.same_body.pd",
                     .claim =
                         "The plastic_strip scene with elastoplastic PD: the mean σ_xx of the gauge's interior "
                         "particles (≥ δ from the free edges) shall follow σ_y + E_t(ε − σ_y/E) of the gauge strain "
                         "within 1 % of σ_y, from σ_y/(4E) to 10 σ_y/E and beyond",
                     .measured = worst_pd,
                     .expected = 0.01,
                     .compare = test::Compare::at_most,
                     .tolerance_reason = reason,
                     .source = "[simo-hughes1998] bilinear uniaxial law; [noorian] material",
                     .unit = "",
                     .problem = kProblem});
  test::record_gate({.id = "lps_plastic.same_body.mpm",
                     .claim =
                         "The same scene with MPM J2 (GIMP, MUSL, cell 2Δx): the gauge's mean σ_xx shall follow the "
                         "bilinear law of its logarithmic strain within 1 % of σ_y",
                     .measured = worst_mpm,
                     .expected = 0.01,
                     .compare = test::Compare::at_most,
                     .tolerance_reason = reason,
                     .source = "[simo-hughes1998] bilinear uniaxial law (Hencky strain, Kirchhoff stress)",
                     .unit = "",
                     .problem = kProblem});
  test::record_data(kProblem, "07_same_body_strip",
                    {{"kind", "plot"},
                     {"title", "One strip, two methods: gauge stress against gauge strain"},
                     {"xlabel", "gauge strain (%)"},
                     {"ylabel", "σ_xx (MPa)"},
                     {"xscale", "linear"},
                     {"yscale", "linear"},
                     {"series",
                      {mu::series("bilinear law (small strain)", exact_e, exact_s),
                       mu::series("elastoplastic PD (lps_plastic)", es_pd, ss_pd, "points"),
                       mu::series("MPM J2 (GIMP, MUSL)", es_mpm, ss_mpm, "dashed")}},
                     {"caption",
                      "verification/scenes/plastic_strip.toml: 40 × 10 mm, Δx = 1 mm, δ = 3.015Δx, plane "
                      "stress; grips pulled apart at ±0.48 m/s. Gauge: 10–30 mm, rows ≥ δ from the free "
                      "edges. MPM's curve is the same law in the log strain (≈ ε²/2 apart at 2 %)."}});
}

// Final-frame reference positions and ε̄_p of a 2D run.
struct PlasticMap {
  std::vector<std::array<double, 2>> x0;
  std::vector<double> eq_plastic;
};

PlasticMap final_plastic_map(const test::GateRun& run) {
  const auto fields = run.fields();
  const auto& frame = fields.frames().back();
  const auto pos = fields.read(frame, "position"), u = fields.read(frame, "displacement");
  PlasticMap m;
  m.eq_plastic = fields.read(frame, "eq_plastic_strain");
  for (std::size_t i = 0; i < m.eq_plastic.size(); ++i)
    m.x0.push_back({pos[3 * i] - u[3 * i], pos[3 * i + 1] - u[3 * i + 1]});
  return m;
}

// Mean ε̄_p of the particles with |x₀ − x_c| ≤ half_width (a band across the strip).
double band_mean(const PlasticMap& m, double x_c, double half_width) {
  double sum = 0.0, n = 0.0;
  for (std::size_t i = 0; i < m.x0.size(); ++i)
    if (std::abs(m.x0[i][0] - x_c) <= half_width) sum += m.eq_plastic[i], n += 1;
  return sum / n;
}

TEST(FastLpsPlasticSameBody, NotchedStripLocalisesInBothMethods) {
  const auto pd_scene = io::parse_scene(test::scene_file("plastic_notched_strip.toml"));
  const double thickness = pd_scene.measure, ligament = 0.004, sy = pd_scene.hardening.yield_stress;
  const double limit_load = sy * ligament * thickness;  // the ligament at yield, no hardening
  std::vector<double> d[2], f[2];
  PlasticMap maps[2];
  double localisation[2];
  for (const int k : {0, 1}) {
    const bool pd = k == 0;
    const auto run =
        test::run_for_gate(pd ? pd_scene : as_mpm_j2(pd_scene), kProblem, pd ? "notched_pd" : "notched_mpm");
    const auto right = run.history("probe_grip_right_ux"), left = run.history("probe_grip_left_ux");
    const auto reaction = run.history("reaction_right_x");
    for (std::size_t i = 0; i < right.size(); ++i) {
      d[k].push_back(1e3 * (right[i] - left[i]));
      f[k].push_back(reaction[i] / limit_load);
    }
    maps[k] = final_plastic_map(run);
    // ε̄_p across the ligament (± 2 mm) against a band of the same width 10 mm away.
    localisation[k] = band_mean(maps[k], 0.020, 0.002) / std::max(band_mean(maps[k], 0.010, 0.002), 1e-12);
  }
  double difference = 0.0, peak = 0.0;
  for (std::size_t i = 0; i < d[1].size(); ++i) {
    peak = std::max(peak, f[1][i]);
    difference = std::max(difference, std::abs(interpolate(d[0], f[0], d[1][i]) - f[1][i]));
  }
  std::cout << "notched: localisation PD " << localisation[0] << " MPM " << localisation[1] << ", peak MPM " << peak
            << ", max |F_PD − F_MPM| / F_limit " << difference << "\n";
  for (const int k : {0, 1})
    test::record_gate({.id = std::string("lps_plastic.notched_strip.localisation.") + (k == 0 ? "pd" : "mpm"),
                       .claim = std::string("A notched strip pulled to ≈ 5 % (") +
                           (k == 0 ? "elastoplastic PD" : "MPM J2") +
                           ") shall localise its plastic flow in the ligament: mean ε̄_p across the ligament ≥ 5× "
                           "the mean 10 mm away",
                       .measured = localisation[k],
                       .expected = 5.0,
                       .compare = test::Compare::at_least,
                       .tolerance_reason = "A bound, not a band: with E_t/E < 1 % the ligament (40 % of the section) "
                                           "flows while the shoulders stay near yield; 5× separates a band from "
                                           "uniform flow",
                       .source = "[simo-hughes1998] limit load of a plane-stress ligament; [noorian] material",
                       .unit = "",
                       .problem = kProblem});
  test::record_data(
      kProblem, "08_notched_strip",
      {{"kind", "plot"},
       {"title", "Notched strip: load against grip displacement, PD and MPM"},
       {"xlabel", "grip separation change (mm)"},
       {"ylabel", "load / (σ_y × ligament area)"},
       {"xscale", "linear"},
       {"yscale", "linear"},
       {"series",
        {mu::series("elastoplastic PD (lps_plastic)", d[0], f[0]),
         mu::series("MPM J2 (GIMP, MUSL)", d[1], f[1], "dashed")}},
       {"caption",
        "verification/scenes/plastic_notched_strip.toml (two R 3 mm notches, 4 mm ligament, "
        "Δx = 1 mm). Largest difference of the PD load from MPM's at equal displacement: " +
            std::to_string(difference) + " of the ligament's yield load (MPM's peak: " + std::to_string(peak) +
            "). No band: PD's horizon (3 mm) spans most of the ligament, "
            "MPM's GIMP stencil one cell, and the methods localise differently. PD is the stiffer and "
            "stronger: its bonds are formed between all sites within δ, so near the ligament "
            "they bridge the notches (no visibility criterion for subtracted shapes)."}});
  double scale = 0.0;
  for (const auto& m : maps) scale = std::max(scale, *std::max_element(m.eq_plastic.begin(), m.eq_plastic.end()));
  for (const int k : {0, 1}) {
    std::vector<double> v;
    for (double e : maps[k].eq_plastic) v.push_back(e / scale);
    test::record_image(kProblem, std::string("09_notched_band_") + (k == 0 ? "pd" : "mpm"),
                       test::damage_map(maps[k].x0, v, pd_scene.spacing, 12),
                       std::string("Band of ε̄_p at the end, ") + (k == 0 ? "elastoplastic PD" : "MPM J2"),
                       "Colour: ε̄_p / " + std::to_string(scale) + " (one scale for both methods).");
  }
}

}  // namespace
}  // namespace pdmpm
