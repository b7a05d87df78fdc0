// HPD with MPM's J2 law against MPM J2 on one body (issue: "a nonlinear case … against MPM J2
// on the same body within 2 %"; docs/models/hpd.md): the plane-stress steel strip of
// verification/scenes/plastic_strip.toml (40 × 10 mm, Δx = 1 mm, δ = 3.015Δx) pulled to ≈ 2.4 %
// strain, once with [model] type = "hpd", constitutive = "j2" and once with MPM J2 (GIMP, MUSL,
// cell 2Δx). Both carry the same law (log strain, Kirchhoff stress, plane-stress return map), so
// along this homogeneous path they must give the same gauge stress at the same gauge strain;
// what can differ is each method's dynamic residue and its gauge's discrete strain measure.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "solver/io/scene.hpp"
#include "verification/gates/mpm_gate_util.hpp"
#include "verification/support/gate.hpp"
#include "verification/support/scene_gate.hpp"
#include "verification/support/strip_gauge.hpp"

namespace pdmpm {
namespace {

namespace mu = test::mpm_util;
const char* kProblem = "hpd";

io::Scene as_hpd_j2(io::Scene s) {
  s.model = "hpd";
  s.hpd.law = pd::HpdLaw::j2;
  return s;
}

TEST(FastHpdJ2, StripAgainstMpmJ2OnTheSameBody) {
  const auto scene = io::parse_scene(test::scene_file("plastic_strip.toml"));
  const double E = scene.material.E, nu = scene.material.nu;
  const double sy = scene.hardening.yield_stress, Et = scene.hardening.tangent_modulus;
  // Gauge: 10–30 mm along the strip, the rows at least δ from both free edges (the lps_plastic gate's).
  const double delta = scene.delta, width = 0.01;
  std::vector<test::GaugeReading> g[2];
  for (int m = 0; m < 2; ++m) {
    const auto run = test::run_for_gate(m ? test::as_mpm_j2(scene) : as_hpd_j2(scene), kProblem,
                                        m ? "j2_strip_mpm" : "j2_strip_hpd");
    g[m] = test::gauge_history(run, 0.010, 0.030, delta, width - delta);
  }
  std::vector<double> e_mpm, s_mpm, e_hpd, s_hpd, e_law, s_law;
  for (const auto& r : g[1]) e_mpm.push_back(r.strain), s_mpm.push_back(r.stress);
  // The law along the path (uniaxial stress, log strain ε, τ bilinear, σ = τ/J with
  // J = exp((1 − 2ν) τ/E): plastic flow is isochoric).
  auto law = [&](double e) {
    const double eps = std::log1p(e), tau = eps <= sy / E ? E * eps : sy + Et * (eps - sy / E);
    return tau * std::exp(-(1 - 2 * nu) * tau / E);
  };
  double worst = 0.0, worst_law = 0.0, last = 0.0;
  for (const auto& r : g[0]) {
    e_hpd.push_back(100 * r.strain), s_hpd.push_back(r.stress / 1e6);
    last = std::max(last, r.strain);
    if (r.strain < 0.25 * sy / E || r.strain > e_mpm.back())
      continue;  // below: stresses near zero; above: no MPM frame
    const double ref = test::interpolate(e_mpm, s_mpm, r.strain);
    worst = std::max(worst, std::abs(r.stress - ref) / ref);
    worst_law = std::max(worst_law, std::abs(r.stress - law(r.strain)) / law(r.strain));
  }
  ASSERT_GT(last, 10 * sy / E) << "the strip must be pulled to 10 σ_y/E for this claim";
  for (double e = 0.0; e <= last * 1.0001; e += last / 100) e_law.push_back(100 * e), s_law.push_back(law(e) / 1e6);
  for (double& e : e_mpm) e *= 100;
  for (double& s : s_mpm) s /= 1e6;
  test::record_data(kProblem, "08_j2_strip",
                    {{"kind", "plot"},
                     {"title", "HPD with the J2 law against MPM J2 on one strip: gauge stress against gauge strain"},
                     {"xlabel", "gauge strain (%)"},
                     {"ylabel", "σ_xx (MPa)"},
                     {"xscale", "linear"},
                     {"yscale", "linear"},
                     {"series",
                      {mu::series("the law (log strain, σ = τ/J)", e_law, s_law),
                       mu::series("HPD, constitutive = \"j2\"", e_hpd, s_hpd, "points"),
                       mu::series("MPM J2 (GIMP, MUSL)", e_mpm, s_mpm, "dashed")}},
                     {"caption",
                      "verification/scenes/plastic_strip.toml (40 × 10 mm, Δx = 1 mm, δ = 3.015Δx, plane stress, "
                      "grips pulled apart at ±0.48 m/s), integrated by HPD with MPM's J2 law at every bond midpoint "
                      "and by MPM J2. Gauge: 10–30 mm, rows ≥ δ from the free edges. HPD's largest deviation from "
                      "the law itself: " +
                          std::to_string(100 * worst_law).substr(0, 4) + " %."}});
  test::record_gate({.id = "hpd.j2.same_body",
                     .claim = "HPD with the J2 law and MPM J2 on the same strip: the gauge's mean σ_xx shall agree "
                              "within 2 % at every HPD frame from σ_y/(4E) to ≈ 2.4 % strain (MPM's curve "
                              "interpolated at HPD's gauge strain)",
                     .measured = worst,
                     .expected = 0.02,
                     .compare = test::Compare::at_most,
                     .tolerance_reason =
                         "the issue's bound: the same law on a homogeneous path; what remains is each "
                         "method's dynamic residue of the finite pull rate and its gauge's discrete strain",
                     .source = "[pdmpm] docs/models/hpd.md (J2 law); [noorian] material",
                     .unit = "",
                     .problem = kProblem});
}

}  // namespace
}  // namespace pdmpm
