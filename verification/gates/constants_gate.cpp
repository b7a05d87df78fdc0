// Bond constants (docs/models/pmb.md and docs/models/lps.md). The closed forms of solver/pd/constants.* are
// checked against (1) GSL adaptive quadrature of the integrals that define them
// (solver/pd/constants_quadrature.*), (2) Deryugin et al. 2023 table 4.2 typed as printed,
// (3) the closed form's constant-ω forms, and (4) the LPS model against Madenci & Oterkus'
// form of the same model.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "solver/pd/constants.hpp"
#include "solver/pd/constants_quadrature.hpp"
#include "verification/support/gate.hpp"

namespace pdmpm {
namespace {

using core::Setting;
using nlohmann::json;
using pd::Influence;
namespace quad = pd::quadrature;

constexpr double pi = std::numbers::pi;
constexpr double e_const = std::numbers::e;
constexpr double eps = std::numeric_limits<double>::epsilon();

// One representative configuration: steel-like E, Δx = 1 mm and the seeds' δ = 3.015 Δx.
constexpr double E = 200e9;
constexpr double delta = 3.015e-3;
constexpr double thickness = 1e-3;  // 2D plate thickness h
constexpr double area = 1e-6;       // 1D bar cross-section A
constexpr double G0 = 1000.0;       // fracture energy for the s₀ table (J/m²)

const core::Setting all_settings[] = {core::Setting::bar1d, core::Setting::plane_stress, core::Setting::plane_strain,
                                      core::Setting::solid3d};

double measure_of(core::Setting s) {
  switch (s) {
    case core::Setting::bar1d:
      return area;
    case core::Setting::plane_stress:
    case core::Setting::plane_strain:
      return thickness;
    case core::Setting::solid3d:
    case core::Setting::uniaxial_strain:  // MPM only (all_settings holds PD's four)
      return 1.0;
  }
  return 1.0;
}

// PMB's Poisson's ratio per setting (Cauchy relation; Deryugin et al. 2023 §3, docs/models/pmb.md). ν
// plays no role in a bar; 1/4 is used there so every setting has a value.
core::Elastic pmb_material(core::Setting s) { return {E, s == core::Setting::plane_stress ? 1.0 / 3.0 : 0.25, 7850.0}; }

double rel_diff(double a, double b) { return std::abs(a - b) / std::abs(b); }
std::string str(std::string_view v) { return std::string(v); }

// Tolerance for closed form vs quadrature: the integrals are requested to
// epsrel = 1e-12 per nesting level (3 levels at most), the closed forms round at
// ~1e-14, so 1e-10 is ≥ 30× above what either side can contribute while any wrong
// factor, moment or measure would show as an O(1) difference.
constexpr double quadrature_tolerance = 1e-10;
std::string quadrature_reason(double worst_estimate) {
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "GSL QAGS requested epsrel = 1e-12 (epsabs = 0) at every nesting level, at most 3 levels; the largest "
                "error estimate GSL returned here was %.1e relative. 1e-10 leaves a margin of ≥ 30x over that while a "
                "wrong factor or moment would be O(1).",
                worst_estimate);
  return buf;
}

// ---------------------------------------------------------------------------
// 1. Closed form vs quadrature: c, m and s₀ for every ω and setting.

TEST(FastConstants, MicromodulusClosedFormEqualsQuadrature) {
  json rows = json::array();
  for (core::Setting s : all_settings) {
    const auto mat = pmb_material(s);
    const double meas = measure_of(s);
    double worst = 0.0, worst_est = 0.0;
    std::string worst_w;
    for (Influence w : pd::all_influences) {
      const double closed = pd::pmb_micromodulus(w, s, mat, delta, meas);
      const auto q = quad::pmb_micromodulus(w, s, mat, delta, meas);
      const double d = rel_diff(q.value, closed);
      if (d >= worst) worst = d, worst_w = str(name(w));
      worst_est = std::max(worst_est, q.relerr());
      rows.push_back({str(name(s)), str(name(w)), mat.nu, closed, q.value, d, q.relerr()});
    }
    test::record_gate({.id = "constants.pmb_c.quadrature." + str(name(s)),
                       .claim = "The closed-form PMB micromodulus c shall equal c solved from the quadrature of W_PD = "
                                "W_classical over the horizon for all 7 influence functions in setting " +
                           str(name(s)) + " (measured: worst relative difference, at ω = " + worst_w + ")",
                       .measured = worst,
                       .expected = 0.0,
                       .tolerance = quadrature_tolerance,
                       .compare = test::Compare::abs,
                       .tolerance_reason = quadrature_reason(worst_est),
                       .source = "docs/models/pmb.md; [deryugin2023] eq 4.2–4.5 (energy matching); constants.hpp",
                       .unit = "",
                       .problem = "constants"});
  }
  test::record_data(
      "constants", "micromodulus",
      {{"kind", "table"},
       {"title", "PMB micromodulus c: closed form vs adaptive quadrature"},
       {"columns",
        {"setting", "ω", "ν", "c closed form", "c quadrature", "rel. difference", "GSL rel. error estimate"}},
       {"rows", rows},
       {"caption",
        "E = 200 GPa, δ = 3.015 mm, h = 1 mm (2D), A = 1 mm² (1D); c in N/m⁶ in every "
        "setting (the measure h or A is inside c). ω = inverse_distance is δ/r."}});
}

TEST(FastConstants, WeightedVolumeClosedFormEqualsQuadrature) {
  json rows = json::array();
  for (core::Setting s : all_settings) {
    const double meas = measure_of(s);
    double worst = 0.0, worst_est = 0.0;
    std::string worst_w;
    for (Influence w : pd::all_influences) {
      const double closed = pd::lps_weighted_volume(w, s, delta, meas);
      const auto q = quad::lps_weighted_volume(w, s, delta, meas);
      const double d = rel_diff(q.value, closed);
      if (d >= worst) worst = d, worst_w = str(name(w));
      worst_est = std::max(worst_est, q.relerr());
      rows.push_back({str(name(s)), str(name(w)), closed, q.value, d, q.relerr()});
    }
    test::record_gate(
        {.id = "constants.lps_m.quadrature." + str(name(s)),
         .claim = "The closed-form continuum LPS weighted volume m shall equal the quadrature of ∫_H ω|ξ|² dV "
                  "for all 7 influence functions in setting " +
             str(name(s)) + " (measured: worst relative difference, at ω = " + worst_w + ")",
         .measured = worst,
         .expected = 0.0,
         .tolerance = quadrature_tolerance,
         .compare = test::Compare::abs,
         .tolerance_reason = quadrature_reason(worst_est),
         .source = "docs/models/lps.md; [silling2007] (m = ∫ ω|ξ|² dV); constants.hpp",
         .unit = "",
         .problem = "constants"});
  }
  test::record_data(
      "constants", "weighted_volume",
      {{"kind", "table"},
       {"title", "LPS continuum weighted volume m: closed form vs adaptive quadrature"},
       {"columns", {"setting", "ω", "m closed form", "m quadrature", "rel. difference", "GSL rel. error estimate"}},
       {"rows", rows},
       {"caption",
        "δ = 3.015 mm, h = 1 mm (2D), A = 1 mm² (1D); m in m⁵ in every setting (2D includes h, 1D "
        "includes A)."}});
}

TEST(FastConstants, CriticalStretchClosedFormEqualsFractureEnergyQuadrature) {
  json rows = json::array();
  for (core::Setting s : all_settings) {
    const auto mat = pmb_material(s);
    const double meas = measure_of(s);
    double worst = 0.0, worst_est = 0.0;
    std::string worst_w;
    for (Influence w : pd::all_influences) {
      const double closed = pd::critical_stretch(w, s, mat, G0, delta, meas);
      const auto q = quad::critical_stretch(w, s, mat, G0, delta, meas);
      const double d = rel_diff(q.value, closed);
      if (d >= worst) worst = d, worst_w = str(name(w));
      worst_est = std::max(worst_est, q.relerr());
      rows.push_back({str(name(s)), str(name(w)), mat.nu, closed, q.value, d, q.relerr()});
    }
    test::record_gate(
        {.id = "constants.s0.quadrature." + str(name(s)),
         .claim = "The closed-form critical stretch s₀(G₀) shall equal s₀ solved from the nested quadrature of "
                  "the energy of all bonds crossing a unit crack area, for all 7 influence functions in setting " +
             str(name(s)) + " (measured: worst relative difference, at ω = " + worst_w + ")",
         .measured = worst,
         .expected = 0.0,
         .tolerance = quadrature_tolerance,
         .compare = test::Compare::abs,
         .tolerance_reason = quadrature_reason(worst_est),
         .source = "docs/models/pmb.md; [silling-askari2005] §4 (G₀ as the work to break the bonds across a crack), "
                   "ω(ξ) kept inside the integral; constants.hpp",
         .unit = "",
         .problem = "constants"});
  }
  test::record_data(
      "constants", "critical_stretch",
      {{"kind", "table"},
       {"title", "Critical stretch s₀ from G₀: closed form vs fracture-energy quadrature"},
       {"columns",
        {"setting", "ω", "ν", "s₀ closed form", "s₀ quadrature", "rel. difference", "GSL rel. error estimate"}},
       {"rows", rows},
       {"caption",
        "G₀ = 1000 J/m², E = 200 GPa, δ = 3.015 mm, h = 1 mm, A = 1 mm²; c from the "
        "energy matching of the same setting (quadrature side: c also by quadrature)."}});
}

// ---------------------------------------------------------------------------
// 2. Deryugin et al. 2023 table 4.2, typed as printed, against the general 3D formula
//    c = 3E / (2π(1−2ν) I₃).

// Rounding bound for one side vs the other, in units of ε (= 2u, u the unit
// roundoff). Each side is ~10 correctly rounded operations plus pow/exp (glibc:
// < 1 ulp), ≤ 12u per side. On top comes cancellation in the moments:
//   triangular 1/4 − 1/5, quadratic 1/4 − 2/6 + 1/8, semi-elliptical 1/4 − 1/6
//   amplify the rounding of their terms by ≤ 17 (quadratic: Σ|terms| / result);
//   Gaussian: e − 2 (table) and ½(1 − e⁻¹) − ½e⁻¹ (ours) amplify by e/(e−2) ≈ 3.8;
//   exponential: 3e − 8 (table) and 1 − (8/3)e⁻¹ (ours) both amplify the
//   rounding of e (and of 8/3·e⁻¹) by 3e/(3e − 8) ≈ 53.
double table42_tolerance_eps(Influence w) {
  switch (w) {
    case Influence::exponential:
      return 256.0;  // 24u + 2·53·(≈4u) ≈ 450u ≈ 225ε, rounded up
    case Influence::gaussian:
      return 32.0;  // 24u + 3.8·(≈6u) ≈ 47u ≈ 24ε
    default:
      return 16.0;  // 24u + 17·(½u) ≈ 33u ≈ 16ε
  }
}

TEST(FastConstants, Seed001Table42ReproducedExactly) {
  const double nu = 0.25;  // Deryugin et al. 2023 §3: PMB has ν = 1/4
  const core::Elastic mat{E, nu, 7850.0};
  const double d4 = delta * delta * delta * delta;
  const double base = E / ((1.0 - 2.0 * nu) * pi * d4);
  struct Printed {
    Influence w;
    const char* form;
    double value;
  };
  const Printed table[] = {
      {Influence::constant, "6E/((1−2ν)πδ⁴)", 6.0 * base},
      {Influence::triangular, "30E/((1−2ν)πδ⁴)", 30.0 * base},
      {Influence::quadratic, "36E/((1−2ν)πδ⁴)", 36.0 * base},
      {Influence::semi_elliptical, "18E/((1−2ν)πδ⁴)", 18.0 * base},
      {Influence::exponential, "3eE/(4(1−2ν)πδ⁴(3e−8))",
       3.0 * e_const * E / (4.0 * (1.0 - 2.0 * nu) * pi * d4 * (3.0 * e_const - 8.0))},
      {Influence::gaussian, "3eE/((1−2ν)πδ⁴(e−2))", 3.0 * e_const * E / ((1.0 - 2.0 * nu) * pi * d4 * (e_const - 2.0))},
  };
  json rows = json::array();
  for (const auto& t : table) {
    const double ours = pd::pmb_micromodulus(t.w, core::Setting::solid3d, mat, delta, 1.0);
    const double d = rel_diff(ours, t.value);
    const double tol = table42_tolerance_eps(t.w) * eps;
    rows.push_back({str(name(t.w)), t.form, t.value, ours, d, d / eps, tol});
    test::record_gate({.id = "constants.seed001_table42." + str(name(t.w)),
                       .claim = "Deryugin et al. 2023 table 4.2's 3D micromodulus for ω = " + str(name(t.w)) + ", " +
                           t.form + ", shall equal our general formula c = 3E/(2π(1−2ν)I₃) to rounding",
                       .measured = d,
                       .expected = 0.0,
                       .tolerance = tol,
                       .compare = test::Compare::abs,
                       .tolerance_reason =
                           "Both sides are exact expressions evaluated in double; the bound is their rounding: ≤ 12 "
                           "unit roundoffs per side plus the cancellation in the moments (polynomial ω ≤ 17×, Gaussian "
                           "e/(e−2) ≈ 3.8×, exponential 3e/(3e−8) ≈ 53× on each side), see table42_tolerance_eps.",
                       .source = "[deryugin2023] §4 eqs 4.6–4.17 and table 4.2",
                       .unit = "",
                       .problem = "constants"});
  }
  test::record_data(
      "constants", "seed001_table42",
      {{"kind", "table"},
       {"title", "Deryugin et al. 2023 table 4.2 (3D PMB micromodulus) reproduced"},
       {"columns",
        {"ω", "printed form", "printed form value", "our formula", "rel. difference", "difference / ε", "tolerance"}},
       {"rows", rows},
       {"caption", "E = 200 GPa, ν = 1/4, δ = 3.015 mm; ε = 2.22e−16 (double machine epsilon)."}});
}

// ---------------------------------------------------------------------------
// 3. the closed form's constant-ω forms.

TEST(FastConstants, SpecConstantInfluenceForms) {
  constexpr double tol = 16.0 * eps;
  const std::string reason =
      "Exact identities evaluated in double: ≤ 12 unit roundoffs per side (ν = 1/3 itself is rounded), so the "
      "difference is ≤ 16ε; a wrong constant would be O(1).";
  json rows = json::array();
  {
    const auto mat = pmb_material(core::Setting::plane_stress);  // ν = 1/3
    const double spec = 9.0 * E / (pi * thickness * delta * delta * delta);
    const double ours = pd::pmb_micromodulus(Influence::constant, core::Setting::plane_stress, mat, delta, thickness);
    rows.push_back({"c, plane stress (ν = 1/3)", "9E/(πhδ³)", spec, ours, rel_diff(ours, spec)});
    test::record_gate(
        {.id = "constants.spec.c_plane_stress_constant",
         .claim = "The plane-stress constant-ω micromodulus shall equal the closed form's 9E/(πhδ³) (ν = 1/3)",
         .measured = rel_diff(ours, spec),
         .expected = 0.0,
         .tolerance = tol,
         .compare = test::Compare::abs,
         .tolerance_reason = reason,
         .source = "[deryugin2023] §4; docs/models/pmb.md",
         .unit = "",
         .problem = "constants"});
  }
  {
    const auto mat = pmb_material(core::Setting::bar1d);
    const double spec = 2.0 * E / (area * delta * delta);
    const double ours = pd::pmb_micromodulus(Influence::constant, core::Setting::bar1d, mat, delta, area);
    rows.push_back({"c, 1D bar", "2E/(Aδ²)", spec, ours, rel_diff(ours, spec)});
    test::record_gate({.id = "constants.spec.c_1d_constant",
                       .claim = "The 1D constant-ω micromodulus shall equal the closed form's 2E/(Aδ²)",
                       .measured = rel_diff(ours, spec),
                       .expected = 0.0,
                       .tolerance = tol,
                       .compare = test::Compare::abs,
                       .tolerance_reason = reason,
                       .source = "[deryugin2023] §4; docs/models/pmb.md",
                       .unit = "",
                       .problem = "constants"});
  }
  {
    const auto mat = pmb_material(core::Setting::solid3d);
    const double spec = std::sqrt(5.0 * G0 / (9.0 * mat.bulk() * delta));
    const double ours = pd::critical_stretch(Influence::constant, core::Setting::solid3d, mat, G0, delta, 1.0);
    rows.push_back({"s₀, 3D", "sqrt(5G₀/(9Kδ))", spec, ours, rel_diff(ours, spec)});
    test::record_gate({.id = "constants.spec.s0_3d_constant",
                       .claim = "The 3D constant-ω critical stretch shall equal the closed form's sqrt(5G₀/(9Kδ))",
                       .measured = rel_diff(ours, spec),
                       .expected = 0.0,
                       .tolerance = tol,
                       .compare = test::Compare::abs,
                       .tolerance_reason = reason,
                       .source = "docs/models/pmb.md; [silling-askari2005] §4 (G₀ = πc s₀² δ⁵/10)",
                       .unit = "",
                       .problem = "constants"});
  }
  {
    const auto mat = pmb_material(core::Setting::plane_stress);
    const double spec = std::sqrt(4.0 * pi * G0 / (9.0 * E * delta));
    const double ours =
        pd::critical_stretch(Influence::constant, core::Setting::plane_stress, mat, G0, delta, thickness);
    rows.push_back({"s₀, plane stress (ν = 1/3)", "sqrt(4πG₀/(9Eδ))", spec, ours, rel_diff(ours, spec)});
    test::record_gate(
        {.id = "constants.spec.s0_plane_stress_constant",
         .claim =
             "The plane-stress constant-ω critical stretch shall equal the closed form's sqrt(4πG₀/(9Eδ)) (ν = 1/3)",
         .measured = rel_diff(ours, spec),
         .expected = 0.0,
         .tolerance = tol,
         .compare = test::Compare::abs,
         .tolerance_reason = reason,
         .source = "[deryugin2023] §4; docs/models/pmb.md",
         .unit = "",
         .problem = "constants"});
  }
  test::record_data(
      "constants", "spec_constant_forms",
      {{"kind", "table"},
       {"title", "Closed constant-ω forms vs the general formulas"},
       {"columns", {"quantity", "closed form", "closed-form value", "general formula", "rel. difference"}},
       {"rows", rows},
       {"caption", "E = 200 GPa, δ = 3.015 mm, h = 1 mm, A = 1 mm², G₀ = 1000 J/m²."}});
}

// ---------------------------------------------------------------------------
// 4. Madenci & Oterkus' form of the LPS model vs ours.
//
// Madenci & Oterkus (2014, "Peridynamic Theory and Its Applications", Springer,
// ch. 4; 2016, JMPS 86:192, eqs 2–8; Noorian et al. eqs 3–7) write the ordinary
// state-based elastic solid with the influence function w = δ/|ξ| as
//   W = a θ² + b Σ_j w (|y_j − y_i| − |x_j − x_i|)² V_j,
//   θ = d Σ_j w Λ_ij (|y_j − y_i| − |x_j − x_i|) V_j,  Λ = (y/|y|)·(x/|x|),
// whose derivative with respect to the extension is their force
// t = 2δ(a d Λ θ/|ξ| + b s) (the form Noorian et al. eq 3 and MOOSE's
// ComputeSmallStrainConstantHorizonMaterialOSPD use). Their constants (docs/models/lps.md):
//   3D a = ½(κ − 5μ/3), b = 15μ/(2πδ⁵), d = 9/(4πδ⁴)
//   2D a = ½(κ − 2μ),   b = 6μ/(πhδ⁴),  d = 2/(πhδ³)   (κ the 2D bulk modulus)
//   1D a = 0,           b = E/(2Aδ³),   d = 1/(2Aδ²).
// In the continuum and at small strain, Λ = 1 and the extension is
// e = |ξ| n·ε·n, so W is the integral below. Ours: lps_coefficients with the
// continuum m and ω = δ/|ξ| (quadrature::lps_energy_density).
struct MoConstants {
  double a, b, d;
};

MoConstants madenci_oterkus_typed(core::Setting s, const core::Elastic& mat) {
  const double mu = mat.shear();
  switch (s) {
    case core::Setting::bar1d:
      return {0.0, E / (2.0 * area * std::pow(delta, 3)), 1.0 / (2.0 * area * delta * delta)};
    case core::Setting::plane_stress:
    case core::Setting::plane_strain:
      return {0.5 * (mat.bulk_2d(s) - 2.0 * mu), 6.0 * mu / (pi * thickness * std::pow(delta, 4)),
              2.0 / (pi * thickness * std::pow(delta, 3))};
    case core::Setting::solid3d:
      return {0.5 * (mat.bulk() - 5.0 * mu / 3.0), 15.0 * mu / (2.0 * pi * std::pow(delta, 5)),
              9.0 / (4.0 * pi * std::pow(delta, 4))};
    case core::Setting::uniaxial_strain:
      break;  // MPM only
  }
  return {};
}

double madenci_oterkus_energy(core::Setting s, const core::Elastic& mat, const quad::Strain& eps_t, double* abserr) {
  const MoConstants k = madenci_oterkus_typed(s, mat);
  const double meas = measure_of(s);
  auto w = [](double r) { return delta / r; };
  // θ may vanish by cancellation (pure shear): its accuracy is set against
  // ‖ε‖·∫ w |ξ| dV, the size of its integrand.
  const auto scale =
      quad::integrate_horizon(s, delta, meas, [&](double r, const Eigen::Vector3d&) { return w(r) * r; });
  quad::Options theta_opt;
  theta_opt.epsabs = theta_opt.epsrel * eps_t.norm() * scale.value;
  const auto sum_theta = quad::integrate_horizon(
      s, delta, meas, [&](double r, const Eigen::Vector3d& n) { return w(r) * r * n.dot(eps_t * n); }, theta_opt);
  const auto sum_e2 = quad::integrate_horizon(s, delta, meas,
                                              [&](double r, const Eigen::Vector3d& n) {
                                                const double e = r * n.dot(eps_t * n);
                                                return w(r) * e * e;
                                              },
                                              {});
  const double theta = k.d * sum_theta.value;
  *abserr = 2.0 * std::abs(k.a * theta) * k.d * sum_theta.abserr + k.b * sum_e2.abserr;
  return k.a * theta * theta + k.b * sum_e2.value;
}

double classical_energy(core::Setting s, const core::Elastic& mat, const quad::Strain& eps_t) {
  const double lam = mat.lame(), G = mat.shear();
  switch (s) {
    case core::Setting::bar1d:
      return 0.5 * E * eps_t(0, 0) * eps_t(0, 0);
    case core::Setting::plane_stress: {
      // In-plane strains with σ_zz = 0: λ* = 2λG/(λ + 2G).
      const Eigen::Matrix2d e2 = eps_t.topLeftCorner<2, 2>();
      const double lam_ps = 2.0 * lam * G / (lam + 2.0 * G);
      return 0.5 * lam_ps * e2.trace() * e2.trace() + G * (e2.array() * e2.array()).sum();
    }
    case core::Setting::plane_strain:
    case core::Setting::solid3d:
      return 0.5 * lam * eps_t.trace() * eps_t.trace() + G * (eps_t.array() * eps_t.array()).sum();
    case core::Setting::uniaxial_strain:
      break;  // MPM only
  }
  return 0.0;
}

TEST(FastConstants, MadenciOterkusFormEqualsOurs) {
  // Any admissible ν: the state-based model is not tied to PMB's 1/4 or 1/3.
  const core::Elastic mat{E, 0.3, 7850.0};
  const double strain = 1e-3;
  json rows = json::array();
  for (core::Setting s : all_settings) {
    const double meas = measure_of(s);
    const double m = pd::lps_weighted_volume(Influence::inverse_distance, s, delta, meas);
    struct Load {
      const char* name;
      quad::Strain eps_t;
    };
    std::vector<Load> loads = {{"isotropic expansion", quad::isotropic_strain(s, strain)}};
    if (s != core::Setting::bar1d) {
      quad::Strain shear = quad::Strain::Zero();
      shear(0, 1) = shear(1, 0) = 0.5 * strain;  // engineering shear γ = strain
      loads.push_back({"pure shear", shear});
    }
    for (const auto& load : loads) {
      double mo_err = 0.0;
      const double W_mo = madenci_oterkus_energy(s, mat, load.eps_t, &mo_err);
      const auto W_ours = quad::lps_energy_density(Influence::inverse_distance, s, mat, m, load.eps_t, delta, meas);
      const double W_cl = classical_energy(s, mat, load.eps_t);
      const double d = rel_diff(W_ours.value, W_mo);
      rows.push_back({str(name(s)), load.name, W_mo, W_ours.value, W_cl, d, rel_diff(W_ours.value, W_cl)});
      const std::string load_id = load.name[0] == 'i' ? "isotropic" : "shear";
      test::record_gate({.id = "constants.madenci_oterkus." + str(name(s)) + "." + load_id,
                         .claim = "Madenci & Oterkus' LPS form (w = δ/|ξ|, their a, b, d) and ours (lps_coefficients, "
                                  "continuum m, ω = δ/|ξ|) shall give the same continuum energy density for " +
                             std::string(load.name) + " in setting " + str(name(s)),
                         .measured = d,
                         .expected = 0.0,
                         .tolerance = quadrature_tolerance,
                         .compare = test::Compare::abs,
                         .tolerance_reason = quadrature_reason(std::max(mo_err / std::abs(W_mo), W_ours.relerr())),
                         .source = "[madenci-oterkus2014] ch. 4 and [madenci-oterkus2016] (JMPS "
                                   "86:192); [noorian] eqs 3–7; docs/models/lps.md",
                         .unit = "",
                         .problem = "constants"});
    }
  }
  test::record_data("constants", "madenci_oterkus",
                    {{"kind", "table"},
                     {"title", "LPS energy density: Madenci & Oterkus form vs ours (continuum, quadrature)"},
                     {"columns",
                      {"setting", "load", "W M&O (J/m³)", "W ours (J/m³)", "W classical (J/m³)",
                       "rel. difference M&O vs ours", "rel. difference ours vs classical"}},
                     {"rows", rows},
                     {"caption",
                      "E = 200 GPa, ν = 0.3, δ = 3.015 mm, strain 1e−3 (isotropic: ε = s·1 in the "
                      "setting's dimensions; pure shear: ε_xy = ε_yx = γ/2 with γ = 1e−3)."}});
}

}  // namespace
}  // namespace pdmpm
