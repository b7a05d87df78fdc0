// Elastoplastic state-based PD (docs/models/lps_plastic.md): homogeneous strain
// paths of an interior particle against the classical J2 law with linear isotropic
// hardening, and a dynamic run whose energy balance includes the plastic work.
// Material: the dog-bone steel of Noorian et al. (E = 215 GPa, ν = 0.33, σ_y = 340 MPa,
// E_t = 1.45 GPa), the material the hybrid's PD region will carry.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "solver/io/scene.hpp"
#include "solver/mpm/j2_plasticity.hpp"
#include "solver/pd/stress.hpp"
#include "solver/sim/run.hpp"
#include "solver/time/stable_step.hpp"
#include "verification/gates/mpm_gate_util.hpp"
#include "verification/support/gate.hpp"
#include "verification/support/pd_fixtures.hpp"
#include "verification/support/plastic_paths.hpp"
#include "verification/support/scratch_dir.hpp"

namespace pdmpm {
namespace {

namespace mu = test::mpm_util;
using nlohmann::json;

const char* kProblem = "lps_plastic";
const core::Elastic kSteel{215e9, 0.33, 7800.0};
const core::J2Hardening kHardening{340e6, 1.45e9};
const double kYieldStrain = kHardening.yield_stress / kSteel.E;

double bilinear(double eps) {
  return eps <= kYieldStrain ? kSteel.E * eps
                             : kHardening.yield_stress + kHardening.tangent_modulus * (eps - kYieldStrain);
}

std::vector<double> scaled(const std::vector<double>& v, double f) {
  std::vector<double> out(v);
  for (double& x : out) x *= f;
  return out;
}

struct UniaxialCurve {
  std::vector<double> strain, stress, exact;
  double worst_stress = 0.0;   // max |σ − σ_J2| / σ_y
  double worst_lateral = 0.0;  // max |ε_lat − (−νσ/E − ε_p/2)| / ε
  double worst_transverse = 0.0;
  double eq_plastic_end = 0.0;
};

// Uniaxial stress along the axis R e_x to ε = 10 σ_y/E in `steps` increments (3D, or a
// plane-stress plate).
template <int D>
UniaxialCurve uniaxial_curve(const test::PlasticBlockSpec& spec, const Mat<D>& R, int steps) {
  test::PlasticBlock<D> b(spec);
  UniaxialCurve c;
  double lateral = 0.0;
  for (int k = 1; k <= steps; ++k) {
    const double eps = 10.0 * kYieldStrain * k / steps;
    const Mat<D> s = b.uniaxial(eps, lateral, R);
    b.model.accept();
    const double exact = bilinear(eps), ep = eps - exact / kSteel.E;
    c.strain.push_back(eps);
    c.stress.push_back(s(0, 0));
    c.exact.push_back(exact);
    c.worst_stress = std::max(c.worst_stress, std::abs(s(0, 0) - exact) / kHardening.yield_stress);
    c.worst_lateral = std::max(c.worst_lateral, std::abs(lateral - (-kSteel.nu * exact / kSteel.E - 0.5 * ep)) / eps);
    c.worst_transverse = std::max({c.worst_transverse, std::abs(s(0, 1)) / kHardening.yield_stress,
                                   std::abs(s(D - 1, D - 1)) / kHardening.yield_stress});
  }
  c.eq_plastic_end = b.eq_plastic_strain();
  return c;
}

const std::string kGeometricReason =
    "The issue's bound (1 % of σ_y). What separates PD from the small-strain J2 curve: the bond kinematics "
    "(deformed direction y/|y|, extension |y| − |ξ|) are geometrically exact, so at ε = 10 σ_y/E = 1.6 % the "
    "force-state stress differs from the small-strain one at O(ε σ).";

TEST(FastLpsPlastic, UniaxialStressFollowsTheBilinearJ2Curve) {
  const Mat<3> skew = Eigen::AngleAxisd(0.7, Vec<3>(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
  json plot = json::array();
  for (const bool axis : {true, false}) {
    const auto c =
        uniaxial_curve<3>({.material = kSteel, .hardening = kHardening}, axis ? Mat<3>(Mat<3>::Identity()) : skew, 40);
    const std::string dir = axis ? "axis" : "skew";
    const std::string where = axis ? "along a lattice axis" : "along a skew axis (0.7 rad about (1, 2, 3))";
    test::record_gate(
        {.id = "lps_plastic.uniaxial." + dir + ".stress",
         .claim = "Under homogeneous uniaxial stress " + where +
             " to ε = 10 σ_y/E, the interior particle's "
             "axial stress shall follow the bilinear J2 curve (measured: max |σ − σ_J2| / σ_y)",
         .measured = c.worst_stress,
         .expected = 0.01,
         .compare = test::Compare::at_most,
         .tolerance_reason = kGeometricReason,
         .source =
             "[pdmpm] docs/models/lps_plastic.md (derivation); [simo-hughes1998] (J2, linear isotropic hardening)",
         .unit = "",
         .problem = kProblem});
    test::record_gate({.id = "lps_plastic.uniaxial." + dir + ".lateral",
                       .claim = "On the same path the lateral strain shall be −νσ/E − ε_p/2 (isochoric flow) "
                                "(measured: max |ε_lat − (−νσ/E − ε_p/2)| / ε)",
                       .measured = c.worst_lateral,
                       .expected = 0.01,
                       .compare = test::Compare::at_most,
                       .tolerance_reason = "1 % of the axial strain, the precision of the stress claim; the same O(ε) "
                                           "geometric nonlinearity is the only difference expected.",
                       .source = "[simo-hughes1998] (J2 flow is deviatoric)",
                       .unit = "",
                       .problem = kProblem});
    test::record_gate({.id = "lps_plastic.uniaxial." + dir + ".eq_plastic_strain",
                       .claim = "At ε = 10 σ_y/E the model's equivalent plastic strain shall equal the J2 value "
                                "ε − σ_J2/E (measured: ratio)",
                       .measured = c.eq_plastic_end / (10.0 * kYieldStrain - bilinear(10.0 * kYieldStrain) / kSteel.E),
                       .expected = 1.0,
                       .tolerance = 0.01,
                       .compare = test::Compare::rel,
                       .tolerance_reason = "1 %, as the stress: ε̄_p is work-conjugate to σ̄ by construction.",
                       .source = "[pdmpm] docs/models/lps_plastic.md",
                       .unit = "",
                       .problem = kProblem});
    if (axis) plot.push_back(mu::series("J2 bilinear (analytic)", c.strain, scaled(c.exact, 1e-6)));
    plot.push_back(mu::series(std::string("lps_plastic, ") + (axis ? "[100]" : "skew axis"), c.strain,
                              scaled(c.stress, 1e-6), axis ? "points" : "dashed"));
  }
  test::record_data(kProblem, "01_uniaxial",
                    {{"kind", "plot"},
                     {"title", "Uniaxial stress, interior particle of a 15³ block (homogeneous path)"},
                     {"xlabel", "axial strain ε"},
                     {"ylabel", "axial stress σ (MPa)"},
                     {"xscale", "linear"},
                     {"yscale", "linear"},
                     {"series", plot},
                     {"caption",
                      "E = 215 GPa, ν = 0.33, σ_y = 340 MPa, E_t = 1.45 GPa; δ = 3.015Δx, ω = 1, isotropy "
                      "corrected; the lateral strain is solved so that σ_yy = σ_zz = 0 at the particle."}});
}

// Load to 6 ε_y, unload to zero stress, reload to 8 ε_y.
TEST(FastLpsPlastic, LoadUnloadReload) {
  test::PlasticBlock<3> b({.material = kSteel, .hardening = kHardening});
  double lateral = 0.0;
  std::vector<double> xs, ys;
  auto go = [&](double eps) {
    const double s = b.uniaxial(eps, lateral)(0, 0);
    b.model.accept();
    xs.push_back(eps);
    ys.push_back(s * 1e-6);
    return s;
  };
  const double peak = 6.0 * kYieldStrain;
  double s_peak = 0.0;
  for (int k = 1; k <= 30; ++k) s_peak = go(peak * k / 30);
  const double ep_peak = b.eq_plastic_strain();
  // Unload by ε_y: elastic, slope E.
  const double s_down = go(peak - kYieldStrain);
  const double slope = (s_peak - s_down) / kYieldStrain / kSteel.E;
  // Unload to σ = 0 (secant on ε): the residual strain.
  double e0 = peak - kYieldStrain, f0 = s_down, e1 = peak - 1.5 * kYieldStrain, f1 = go(e1);
  for (int it = 0; it < 40 && std::abs(f1) > 1e-9 * kHardening.yield_stress; ++it) {
    const double e2 = e1 - f1 * (e1 - e0) / (f1 - f0);
    e0 = e1, f0 = f1, e1 = e2;
    f1 = go(e1);
  }
  const double residual = e1, residual_j2 = peak - bilinear(peak) / kSteel.E;
  const bool no_flow_unloading = b.eq_plastic_strain() == ep_peak;
  // Reload to just below the peak: no yielding; then beyond: the curve continues.
  go(peak * 0.999);
  const bool no_flow_reload = b.eq_plastic_strain() == ep_peak;
  double worst_beyond = 0.0;
  for (int k = 1; k <= 10; ++k) {
    const double eps = peak + 2.0 * kYieldStrain * k / 10;
    worst_beyond = std::max(worst_beyond, std::abs(go(eps) - bilinear(eps)) / kHardening.yield_stress);
  }
  test::record_gate({.id = "lps_plastic.cycle.unloading_slope",
                     .claim = "Unloading from 6 ε_y shall be elastic with slope E (measured: slope / E)",
                     .measured = slope,
                     .expected = 1.0,
                     .tolerance = 0.01,
                     .compare = test::Compare::rel,
                     .tolerance_reason =
                         "The issue's 1 %; the isotropy-corrected lattice has E exactly for an interior "
                         "particle, up to the O(ε) geometric nonlinearity.",
                     .source = "[simo-hughes1998] (elastic unloading)",
                     .unit = "",
                     .problem = kProblem});
  test::record_gate(
      {.id = "lps_plastic.cycle.residual_strain",
       .claim = "The strain left at zero stress after unloading from 6 ε_y shall be the J2 plastic strain "
                "ε_peak − σ_J2(ε_peak)/E (measured: ratio)",
       .measured = residual / residual_j2,
       .expected = 1.0,
       .tolerance = 0.01,
       .compare = test::Compare::rel,
       .tolerance_reason = "1 % of the plastic strain: the stress error at the peak (≲ 1 % σ_y) over E is "
                           "≲ 1e-2 ε_y, below 1 % of the 4.9 ε_y residual.",
       .source = "[simo-hughes1998]",
       .unit = "",
       .problem = kProblem});
  test::record_gate({.id = "lps_plastic.cycle.elastic_reload",
                     .claim = "Unloading and reloading to 0.999 × the previous peak strain shall not change the "
                              "equivalent plastic strain (measured: 1 if it did not)",
                     .measured = no_flow_unloading && no_flow_reload ? 1.0 : 0.0,
                     .expected = 1.0,
                     .tolerance = 0.0,
                     .compare = test::Compare::abs,
                     .tolerance_reason = "A yes/no property (bitwise: no return at all).",
                     .source = "[simo-hughes1998] (isotropic hardening)",
                     .unit = "",
                     .problem = kProblem});
  test::record_gate({.id = "lps_plastic.cycle.reload_curve",
                     .claim = "Reloaded beyond the previous peak (to 8 ε_y) the stress shall rejoin the bilinear curve "
                              "(measured: max |σ − σ_J2| / σ_y)",
                     .measured = worst_beyond,
                     .expected = 0.01,
                     .compare = test::Compare::at_most,
                     .tolerance_reason = kGeometricReason,
                     .source = "[simo-hughes1998]",
                     .unit = "",
                     .problem = kProblem});
  test::record_data(kProblem, "02_cycle",
                    {{"kind", "plot"},
                     {"title", "Load – unload – reload (interior particle, uniaxial stress)"},
                     {"xlabel", "axial strain ε"},
                     {"ylabel", "axial stress σ (MPa)"},
                     {"xscale", "linear"},
                     {"yscale", "linear"},
                     {"series", {mu::series("lps_plastic", xs, ys, "points")}},
                     {"caption",
                      "Loaded to 6 ε_y, unloaded to σ = 0 (residual strain " + std::to_string(residual) +
                          ", J2: " + std::to_string(residual_j2) + "), reloaded to 8 ε_y."}});
}

TEST(FastLpsPlastic, PureShearYieldsAtSigmaYOverRootThree) {
  test::PlasticBlock<3> b({.material = kSteel, .hardening = kHardening});
  const double G = kSteel.shear(), tau_y = kHardening.yield_stress / std::sqrt(3.0), gamma_y = tau_y / G;
  // Bisection on γ for the first yield (trial states only: nothing is committed).
  double lo = 0.5 * gamma_y, hi = 1.5 * gamma_y, tau_at_yield = 0.0;
  for (int it = 0; it < 40; ++it) {
    const double mid = 0.5 * (lo + hi);
    const double tau = b.shear(mid);
    if (b.eq_plastic_strain() > 0.0)
      hi = mid;
    else
      lo = mid, tau_at_yield = tau;
    b.model.reject();
  }
  test::record_gate({.id = "lps_plastic.shear.yield",
                     .claim = "Under homogeneous simple shear the interior particle shall first yield at τ = σ_y/√3 "
                              "(measured: τ at first yield / (σ_y/√3))",
                     .measured = tau_at_yield / tau_y,
                     .expected = 1.0,
                     .tolerance = 0.01,
                     .compare = test::Compare::rel,
                     .tolerance_reason = "The issue's 1 %; the bisection resolves γ to 1e-12 γ_y, and at γ_y = 2.4e-3 "
                                         "the geometric nonlinearity is O(γ) of τ.",
                     .source = "[simo-hughes1998] (von Mises: τ_y = σ_y/√3)",
                     .unit = "",
                     .problem = kProblem});
}

// Isochoric flow: θ stays the elastic volume change, tr σ = 3Kθ.
TEST(FastLpsPlastic, PlasticFlowIsIsochoric) {
  test::PlasticBlock<3> b({.material = kSteel, .hardening = kHardening});
  double lateral = 0.0, worst = 0.0;
  const double K = kSteel.bulk();
  for (int k = 1; k <= 20; ++k) {
    const Mat<3> s = b.uniaxial(10.0 * kYieldStrain * k / 20, lateral);
    b.model.accept();
    worst = std::max(worst, std::abs(s.trace() - 3.0 * K * b.dilatation()) / kHardening.yield_stress);
  }
  test::record_gate({.id = "lps_plastic.isochoric",
                     .claim = "Along the uniaxial path to 10 ε_y the mean stress shall stay K θ: the dilatation is the "
                              "elastic volume change and plastic flow adds none (measured: max |tr σ − 3Kθ| / σ_y)",
                     .measured = worst,
                     .expected = 1e-3,
                     .compare = test::Compare::at_most,
                     .tolerance_reason = "The second bond moments of the lattice are isotropic, so a traceless plastic "
                                         "extension adds nothing to θ exactly; what remains is the difference between "
                                         "the bond kinematics of σ (deformed direction) and of θ (extension), O(ε²) "
                                         "relative at ε = 1.6 %.",
                     .source = "[pdmpm] docs/models/lps_plastic.md (isochoric flow)",
                     .unit = "",
                     .problem = kProblem});
}

// Below yield the plastic model is elastic LPS (same sums, another order).
template <int D>
double below_yield_difference(core::Setting s) {
  test::PlasticBlock<D> b({.material = kSteel, .hardening = kHardening, .isotropic = false, .setting = s});
  for (Index i = 0; i < b.sys.n_real(); ++i) {
    const Vec<D> x = b.sys.particles.x0[i];
    Vec<D> u;
    u[0] = 1e-7 * std::sin(x[1] * 700.0);
    u[1] = 2e-7 * std::cos(x[D - 1] * 500.0) + (D == 2 ? 1e-4 * x[0] * x[1] : 0.0);
    if constexpr (D == 3) u[2] = 1e-4 * x[0] * x[1];
    b.sys.particles.u[i] = u;
  }
  const double difference = b.difference_from_elastic_lps();
  const auto& ep = *b.model.eq_plastic_strain();
  EXPECT_EQ(*std::max_element(ep.begin(), ep.end()), 0.0) << "the field must stay elastic for this claim";
  return difference;
}

TEST(FastLpsPlastic, BelowYieldItIsElasticLps) {
  const double worst = std::max({below_yield_difference<3>(core::Setting::solid3d),
                                 below_yield_difference<2>(core::Setting::plane_stress),
                                 below_yield_difference<2>(core::Setting::plane_strain)});
  test::record_gate(
      {.id = "lps_plastic.below_yield",
       .claim = "Below yield (a non-uniform field, strains ≤ 1e-4) the plastic model's forces shall equal "
                "elastic LPS's (isotropy correction off) in 3D, plane stress and plane strain "
                "(measured: max |f − f_LPS| / max |f_LPS|, worst setting)",
       .measured = worst,
       .expected = 1e-12,
       .compare = test::Compare::at_most,
       .tolerance_reason = "Round-off: the same sums in another order (the LPS kernel sums in SIMD lanes).",
       .source = "[pdmpm] docs/models/lps_plastic.md (with p = 0 the force state is LPS's)",
       .unit = "",
       .problem = kProblem});
}

// The response of a homogeneous state does not depend on the horizon ratio.
TEST(FastLpsPlastic, HomogeneousResponseIndependentOfHorizonRatio) {
  std::vector<double> stress;
  json rows = json::array();
  for (double m : {2.015, 3.015, 4.015}) {
    test::PlasticBlock<3> b({.material = kSteel, .hardening = kHardening, .horizon_ratio = m});
    double lateral = 0.0, s = 0.0;
    for (int k = 1; k <= 10; ++k) {
      s = b.uniaxial(5.0 * kYieldStrain * k / 10, lateral)(0, 0);
      b.model.accept();
    }
    stress.push_back(s);
    rows.push_back({m, s * 1e-6, bilinear(5.0 * kYieldStrain) * 1e-6, b.eq_plastic_strain()});
  }
  const auto [lo, hi] = std::minmax_element(stress.begin(), stress.end());
  test::record_gate({.id = "lps_plastic.horizon_independence",
                     .claim = "The axial stress at 5 ε_y on the uniaxial path shall not depend on the horizon ratio "
                              "m = 2.015, 3.015, 4.015 (measured: (max − min) / σ_y)",
                     .measured = (*hi - *lo) / kHardening.yield_stress,
                     .expected = 0.01,
                     .compare = test::Compare::at_most,
                     .tolerance_reason =
                         "The issue's 1 %: with the isotropy correction every interior particle answers "
                         "a homogeneous state with the continuum moments, whatever m.",
                     .source = "[pdmpm] docs/models/lps_plastic.md (isotropy correction)",
                     .unit = "",
                     .problem = kProblem});
  test::record_data(kProblem, "03_horizon",
                    {{"kind", "table"},
                     {"title", "Uniaxial stress at ε = 5 σ_y/E vs horizon ratio"},
                     {"columns", {"m = δ/Δx", "σ (MPa)", "J2 (MPa)", "ε̄_p"}},
                     {"rows", rows}});
}

// The 2D settings (docs/models/lps_plastic.md, "2D"): the out-of-plane strain is not a PD
// degree of freedom; each particle carries the axial deviator that holds it.
const char* kPlanarReason =
    "The issue's 1 % of σ_y. The reference integrates the same J2 law independently (MPM's Simo–Taylor plane-stress "
    "return / 3D radial return on the same in-plane strain, ε_zz = 0 in plane strain); the geometric O(ε σ) of the "
    "bond kinematics at ε ≤ 1.6 % separates them.";

TEST(FastLpsPlastic, PlaneStressUniaxialFollowsTheBilinearJ2Curve) {
  json plot = json::array();
  const Mat<2> skew = Eigen::Rotation2Dd(0.45).toRotationMatrix();
  for (const bool axis : {true, false}) {
    const auto c =
        uniaxial_curve<2>({.material = kSteel, .hardening = kHardening, .setting = core::Setting::plane_stress},
                          axis ? Mat<2>(Mat<2>::Identity()) : skew, 40);
    const std::string dir = axis ? "axis" : "skew";
    test::record_gate({.id = "lps_plastic.plane_stress.uniaxial." + dir,
                       .claim = std::string("In plane stress, uniaxial stress ") +
                           (axis ? "along a lattice axis" : "at 0.45 rad to it") +
                           " to ε = 10 σ_y/E shall follow the bilinear J2 curve; σ_zz = 0 holds through the model's "
                           "own out-of-plane strain (measured: max |σ − σ_J2| / σ_y)",
                       .measured = c.worst_stress,
                       .expected = 0.01,
                       .compare = test::Compare::at_most,
                       .tolerance_reason = kGeometricReason,
                       .source = "[pdmpm] docs/models/lps_plastic.md (2D); [simo-hughes1998] (J2 in plane stress)",
                       .unit = "",
                       .problem = kProblem});
    if (axis) plot.push_back(mu::series("J2 bilinear (analytic)", c.strain, scaled(c.exact, 1e-6)));
    plot.push_back(mu::series(std::string("plane stress, ") + (axis ? "[10]" : "0.45 rad"), c.strain,
                              scaled(c.stress, 1e-6), axis ? "points" : "dashed"));
  }
  test::record_data(kProblem, "04_plane_stress",
                    {{"kind", "plot"},
                     {"title", "Plane stress: uniaxial stress, interior particle of a 2D block (homogeneous path)"},
                     {"xlabel", "axial strain ε"},
                     {"ylabel", "axial stress σ (MPa)"},
                     {"xscale", "linear"},
                     {"yscale", "linear"},
                     {"series", plot},
                     {"caption",
                      "Same steel and horizon as the 3D curve; the in-plane lateral strain is solved for σ_yy = 0, "
                      "σ_zz = 0 by the model's own ε_zz."}});
}

// A general in-plane path — stretch with shear to 10 ε_y, unloading to 6 ε_y — against an
// independent J2 integration of the same strain history. Max deviations over the steps:
// stress components (σ_zz included) / σ_n and ε̄_p / ε_n, with ε_n = σ_n/E the path's scale.
struct PlanarPathResult {
  double stress = 0.0, plastic_strain = 0.0;
  std::vector<double> step, pd_vm, ref_vm;
};

PlanarPathResult planar_path(core::Setting s, const core::J2Hardening& hardening, double sigma_n) {
  Mat<2> direction;
  direction << 1.0, 0.3, 0.3, -0.2;
  const double ey = sigma_n / kSteel.E;
  test::PlasticBlock<2> b({.material = kSteel, .hardening = hardening, .setting = s});
  mpm::PointHistory h;
  PlanarPathResult r;
  for (int k = 1; k <= 40; ++k) {
    const double load = k <= 30 ? 10.0 * k / 30 : 10.0 - 0.4 * (k - 30);
    const Mat<2> e = load * ey * direction;
    const Mat<2> sigma = b.stress_under(e);
    b.model.accept();
    Mat<3> e3 = Mat<3>::Zero();
    e3.topLeftCorner<2, 2>() = e;
    const auto ref = s == core::Setting::plane_stress ? mpm::j2_return_plane_stress(kSteel, hardening, e3, h, 0.0)
                                                      : mpm::j2_return_3d(kSteel, hardening, e3, h, 0.0);
    const double szz = b.model.out_of_plane_stress(b.centre);
    r.stress = std::max({r.stress, (sigma - ref.T.topLeftCorner<2, 2>()).cwiseAbs().maxCoeff() / sigma_n,
                         std::abs(szz - ref.T(2, 2)) / sigma_n});
    r.plastic_strain = std::max(r.plastic_strain, std::abs(b.eq_plastic_strain() - h.eq_plastic_strain) / ey);
    r.step.push_back(k);
    r.pd_vm.push_back(pd::von_mises({sigma(0, 0), sigma(1, 1), szz, sigma(0, 1), 0.0, 0.0}) / sigma_n);
    r.ref_vm.push_back(pd::von_mises({ref.T(0, 0), ref.T(1, 1), ref.T(2, 2), ref.T(0, 1), 0.0, 0.0}) / sigma_n);
  }
  return r;
}

// The return is verified where the bond kinematics are linear to 1e-4 (σ_y = 1e-5 E); at the
// steel's own strains the same path is shown beside the purely elastic deviation, which is
// the bond kinematics' geometric nonlinearity under the path's large mean stress.
TEST(FastLpsPlastic, PlanarPathsMatchAnIndependentJ2Return) {
  const core::J2Hardening small_strain{kSteel.E * 1e-5, 20e9};
  const core::J2Hardening elastic{1e30, 0.0};
  json rows = json::array();
  for (core::Setting s : {core::Setting::plane_stress, core::Setting::plane_strain}) {
    const auto r = planar_path(s, small_strain, small_strain.yield_stress);
    const std::string setting(name(s));
    test::record_gate(
        {.id = "lps_plastic." + setting + ".general_path",
         .claim = "In " + setting +
             ", the path ε = λ ε_y [[1, 0.3], [0.3, −0.2]] with λ to 10 and back to 6 "
             "(σ_y = 1e-5 E) shall give the J2 stress of an independent return map on the same strain, "
             "σ_zz included (measured: max |σ_PD − σ_J2| / σ_y over components and steps)",
         .measured = r.stress,
         .expected = 0.01,
         .compare = test::Compare::at_most,
         .tolerance_reason = kPlanarReason,
         .source = "[pdmpm] docs/models/lps_plastic.md (2D); [simo-hughes1998] (§3.4 plane-stress return)",
         .unit = "",
         .problem = kProblem});
    test::record_gate(
        {.id = "lps_plastic." + setting + ".general_path_plastic_strain",
         .claim = "On the same path the model's ε̄_p shall equal the J2 one (measured: max |ε̄_p − ε̄_p,J2| / ε_y)",
         .measured = r.plastic_strain,
         .expected = 0.01,
         .compare = test::Compare::at_most,
         .tolerance_reason = kPlanarReason,
         .source = "[simo-hughes1998]",
         .unit = "",
         .problem = kProblem});
    const auto steel = planar_path(s, kHardening, kHardening.yield_stress);
    // The elastic deviation on the steel's strains: the same path with a yield stress never reached.
    const auto geometric = planar_path(s, elastic, kHardening.yield_stress);
    rows.push_back({setting, r.stress, steel.stress, geometric.stress, steel.plastic_strain});
    test::record_data(
        kProblem, "05_" + setting + "_path",
        {{"kind", "plot"},
         {"title", "Von Mises stress on a general " + setting + " path (σ_y = 1e-5 E): PD vs an independent J2 return"},
         {"xlabel", "load step (to 10 ε_y at 30, unloading to 6 ε_y at 40)"},
         {"ylabel", "σ_eq / σ_y"},
         {"xscale", "linear"},
         {"yscale", "linear"},
         {"series",
          {mu::series("J2 return (MPM's)", r.step, r.ref_vm), mu::series("lps_plastic", r.step, r.pd_vm, "points")}}});
  }
  test::record_data(kProblem, "06_planar_scale",
                    {{"kind", "table"},
                     {"title", "General planar path: the return at small strain, and the steel's strains"},
                     {"columns",
                      {"setting", "max |Δσ|/σ_y, σ_y = 1e-5 E", "max |Δσ|/σ_y, steel (ε to 1.6 %)",
                       "elastic only, steel strains, / σ_y", "max |Δε̄_p|/ε_y, steel"}},
                     {"rows", rows},
                     {"caption",
                      "At the steel's strains the path's mean stress reaches GPa in plane strain; the bond "
                      "kinematics (stretch |y| − |ξ|, deformed direction) are geometrically exact, so PD and "
                      "the small-strain reference differ at O(ε²K) — the elastic column measures that part "
                      "alone, with no yield surface in the way."}});
}

// Equibiaxial plane stress: no in-plane deviator, yet J2 yields at σ = σ_y.
TEST(FastLpsPlastic, EquibiaxialPlaneStressYields) {
  test::PlasticBlock<2> b({.material = kSteel, .hardening = kHardening, .setting = core::Setting::plane_stress});
  const double e_y = kHardening.yield_stress * (1.0 - kSteel.nu) / kSteel.E;
  double lo = 0.5 * e_y, hi = 1.5 * e_y, sigma_at_yield = 0.0;
  for (int it = 0; it < 40; ++it) {  // bisection on the first yield; trial states only
    const double mid = 0.5 * (lo + hi);
    const double sigma = b.stress_under(mid * Mat<2>::Identity())(0, 0);
    if (b.eq_plastic_strain() > 0.0)
      hi = mid;
    else
      lo = mid, sigma_at_yield = sigma;
    b.model.reject();
  }
  test::record_gate({.id = "lps_plastic.plane_stress.equibiaxial_yield",
                     .claim =
                         "Equibiaxial plane stress (no in-plane deviator: a return on the bonds alone never yields) "
                         "shall first yield at σ = σ_y (measured: σ at first yield / σ_y)",
                     .measured = sigma_at_yield / kHardening.yield_stress,
                     .expected = 1.0,
                     .tolerance = 0.01,
                     .compare = test::Compare::rel,
                     .tolerance_reason = "The issue's 1 %; bisection to 1e-12 ε_y, the geometric O(ε) remains.",
                     .source = "[simo-hughes1998] (von Mises: σ_eq = σ under equibiaxial stress)",
                     .unit = "",
                     .problem = kProblem});
}

// Ductile failure (Noorian et al. eqs 8–9, the form of Hooputra et al.): the interior particle of
// the steel block under homogeneous uniaxial stress (η ≈ 1/3) and simple shear (η = 0), d₀ = 0.02,
// c = −1.5 (illustrative values of the criterion's usual sign; the paper gives none).
TEST(FastLpsPlastic, DuctileFailureOnset) {
  const double d0 = 0.02, c = -1.5;
  auto block = [&] {
    test::PlasticBlock<3> b(
        {.material = kSteel, .hardening = kHardening, .failure = {true, d0, c, core::FailureRule::strain}});
    b.request.break_bonds = true;
    b.request.critical_stretch = std::numeric_limits<double>::infinity();  // the ductile rule alone
    return b;
  };
  const std::function<Mat<3>(double)> tension = [](double eps) {
    const double sigma = bilinear(eps), lateral = -kSteel.nu * sigma / kSteel.E - 0.5 * (eps - sigma / kSteel.E);
    return Mat<3>(Vec<3>(eps, lateral, lateral).asDiagonal());
  };
  const std::function<Mat<3>(double)> shear = [](double gamma) {
    Mat<3> H = Mat<3>::Zero();
    H(0, 1) = H(1, 0) = 0.5 * gamma;
    return H;
  };
  int mismatches = 0, failures = 0;
  for (const auto* path : {&tension, &shear}) {
    auto b = block();
    const auto r = b.load_until_failure(*path, 0.25 * kYieldStrain, 120);  // to 30 ε_y: past ε_f on both paths
    mismatches += r.mismatches, failures += r.failures;
  }
  ASSERT_GT(failures, 0) << "particles must fail for this claim";
  test::record_gate(
      {.id = "lps_plastic.ductile_failure.rule",
       .claim = "Along tension and shear paths to 30 ε_y, every particle shall fail in "
                "exactly the step where ε̄_p ≥ d₀ exp(cη) for its own state, lose every bond on both sides, "
                "and no other bond shall break (" +
           std::to_string(failures) + " particle failures; measured: particles whose fate differs from the rule)",
       .measured = static_cast<double>(mismatches),
       .expected = 0.0,
       .tolerance = 0.0,
       .compare = test::Compare::abs,
       .tolerance_reason = "A count: any difference is a defect.",
       .source = "[noorian] eqs 8–9; [pdmpm] docs/models/lps_plastic.md (ductile failure)",
       .unit = "",
       .problem = kProblem});
  // With c < 0 the fracture strain falls with triaxiality: shear fails at d₀, tension at d₀ exp(c/3).
  // At the steel's strains simple shear is not at η = 0 for PD (the exact bond kinematics give it a
  // second-order mean stress, K γ²/4 ≈ 70 MPa at γ = 3.6 %), so the criterion's dependence on η is
  // verified at σ_y = 1e-5 E, where the kinematics are linear; the steel-scale ratio is reported beside it.
  auto onset_ratio = [&](const core::J2Hardening& hardening, double d0_here) {
    const double ey = hardening.yield_stress / kSteel.E;
    const std::function<Mat<3>(double)> uniaxial = [&](double eps) {  // J2's lateral strain for this hardening
      const double sigma = eps <= ey ? kSteel.E * eps : hardening.yield_stress + hardening.tangent_modulus * (eps - ey);
      const double lateral = -kSteel.nu * sigma / kSteel.E - 0.5 * (eps - sigma / kSteel.E);
      return Mat<3>(Vec<3>(eps, lateral, lateral).asDiagonal());
    };
    auto onset = [&](const std::function<Mat<3>(double)>& path) {
      test::PlasticBlock<3> b(
          {.material = kSteel, .hardening = hardening, .failure = {true, d0_here, c, core::FailureRule::strain}});
      return b.homogeneous_onset(path, 0.1 * ey, 800);
    };
    return onset(shear) / onset(uniaxial) / std::exp(-c / 3.0);
  };
  const double small_yield = 1e-5 * kSteel.E;
  const double ratio = onset_ratio({small_yield, 20e9}, 20.0 * small_yield / kSteel.E);
  const double steel_ratio = onset_ratio(kHardening, d0);
  test::record_gate(
      {.id = "lps_plastic.ductile_failure.triaxiality",
       .claim = "On homogeneous paths (σ_y = 1e-5 E, d₀ = 20 ε_y) the equivalent plastic strain at failure in "
                "simple shear (η = 0) over that in uniaxial tension (η = 1/3) shall be exp(−c/3) (measured: "
                "ratio / exp(−c/3); with the steel's σ_y and d₀ = 0.02 the same ratio is " +
           std::to_string(steel_ratio) +
           ": simple shear at γ ≈ 3.6 % carries a second-order mean stress "
           "in PD's exact bond kinematics)",
       .measured = ratio,
       .expected = 1.0,
       .tolerance = 0.02,
       .compare = test::Compare::rel,
       .tolerance_reason = "2 %: the path's step (0.1 ε_y of strain, ≤ 1 % of ε̄_p at failure); η is "
                           "exact to O(ε) = 1e-4 at these strains.",
       .source = "[noorian] eqs 8–9; [hooputra2004] (c < 0)",
       .unit = "",
       .problem = kProblem});
}

// Deviatoric hold (the test that exposed the divergence of LAMMPS' peri/eps under
// sustained flow): a cube whose outer 2δ layer follows the isochoric strain
// λ(t)·diag(e, −e, 0), λ ramped to 1 and then held, its interior free and damped
// (velocity Verlet with v ← v(1 − c Δt) after each step, c Δt = 2e-3). e puts the
// equivalent strain ε̄ = √(2/3 ε:ε) at 2.2 times its first-yield value σ_y/(3G); along
// this proportional path J2 gives ε̄_p = (3G ε̄ − σ_y)/(3G + H), σ̄ = σ_y + H ε̄_p.
TEST(FastLpsPlastic, DeviatoricHoldKeepsTheJ2Plateau) {
  test::PlasticBlockSpec spec;
  spec.material = kSteel;
  spec.hardening = kHardening;
  spec.horizon_ratio = 2.0;  // m = 2 keeps 10⁴ steps of a 11³ cube cheap; the response is m-independent (gate above)
  spec.sites = 11;
  test::PlasticBlock<3> block(spec);
  auto& p = block.sys.particles;
  const Index n = block.sys.n_real();
  std::vector<bool> free(n);
  for (Index i = 0; i < n; ++i) free[i] = test::distance_to_boundary(block.sys, i) > 2.0 * block.sys.delta;
  const double G = kSteel.E / (2 * (1 + kSteel.nu)), H = kHardening.hardening_modulus(kSteel.E);
  const double eq_strain = 2.2 * kHardening.yield_stress / (3 * G), e = std::sqrt(3.0) / 2.0 * eq_strain;
  const double ep_exact = (3 * G * eq_strain - kHardening.yield_stress) / (3 * G + H);
  const double plateau = kHardening.yield_stress + H * ep_exact;
  Mat<3> strain = Mat<3>::Zero();
  strain(0, 0) = e, strain(1, 1) = -e;

  const double dt = 0.8 * time::silling_askari_step(block.sys, block.model), rho = kSteel.rho, damping = 2e-3 / dt;
  const int ramp = 2000, hold = 10000;
  std::vector<double> energy;
  auto evaluate = [&](bool with_energy) {
    block.request.energy = with_energy ? &energy : nullptr;
    block.model.compute_forces(block.sys, block.request);
    block.model.accept();
  };
  for (Index i = 0; i < n; ++i) p.v[i].setZero(), p.u[i].setZero();
  evaluate(false);
  double lowest = 1e300, highest = 0.0, kinetic = 0.0, stored = 0.0;
  bool finite = true;
  for (int step = 1; step <= ramp + hold; ++step) {
    const double load = std::min(1.0, static_cast<double>(step) / ramp);
    for (Index i = 0; i < n; ++i) {
      if (!free[i]) {
        p.u[i] = load * strain * p.x0[i];
        continue;
      }
      p.v[i] += 0.5 * dt * p.f[i] / rho;
      p.u[i] += dt * p.v[i];
    }
    const bool last = step == ramp + hold;
    evaluate(last);
    kinetic = 0.0;
    for (Index i = 0; i < n; ++i)
      if (free[i]) {
        p.v[i] = (p.v[i] + 0.5 * dt * p.f[i] / rho) * (1.0 - damping * dt);
        kinetic += 0.5 * rho * p.volume[i] * p.v[i].squaredNorm();
        finite = finite && p.u[i].allFinite() && p.v[i].allFinite();
      }
    if (step > ramp) {
      const double s = pd::von_mises(block.model.own_stress(block.sys, block.centre));
      lowest = std::min(lowest, s), highest = std::max(highest, s);
    }
  }
  for (Index i = 0; i < n; ++i) stored += energy[i] * p.volume[i];
  const double worst = std::max(std::abs(highest - plateau), std::abs(lowest - plateau)) / plateau;
  std::cout << "hold: plateau " << plateau << " range [" << lowest << ", " << highest << "] ε̄_p "
            << block.eq_plastic_strain() << " exact " << ep_exact << " K/U " << kinetic / stored << "\n";
  ASSERT_TRUE(finite) << "NaN or infinity in the held block";
  test::record_gate({.id = "lps_plastic.deviatoric_hold.plateau",
                     .claim = "A cube strained at constant volume to 2.2× the yield strain (outer 2δ layer prescribed) "
                              "and held for 10⁴ damped steps: the centre's σ̄ shall stay at the J2 plateau σ_y + H ε̄_p "
                              "within 1 % throughout the hold",
                     .measured = worst,
                     .expected = 0.01,
                     .compare = test::Compare::at_most,
                     .tolerance_reason = "The issue's bound: the interior lags the ramped layer dynamically, so its "
                                         "path is proportional only up to the damped vibration",
                     .source = "[mitchell2011] deviatoric return; [simo-hughes1998] J2 along a proportional path",
                     .unit = "",
                     .problem = kProblem});
  test::record_gate({.id = "lps_plastic.deviatoric_hold.kinetic",
                     .claim = "At the end of the hold the kinetic energy of the free interior shall be ≤ 1e-10 of the "
                              "stored elastic energy (no sustained flow feeds motion)",
                     .measured = kinetic / stored,
                     .expected = 1e-10,
                     .compare = test::Compare::at_most,
                     .tolerance_reason = "The issue's bound; 10⁴ steps of c Δt = 2e-3 damp a free vibration by e⁻²⁰",
                     .source = "[pdmpm] the committed plastic state does not return again at a held strain",
                     .unit = "",
                     .problem = kProblem});
}

// A 3D bar pulled dynamically far into the plastic range: the energy balance closes
// with the plastic work (history.csv, summary.json).
TEST(FastLpsPlastic, EnergyBalanceIncludesPlasticWork) {
  const test::ScratchDir dir("lps_plastic_energy");
  const std::string text = R"TOML([scene]
id = "lps_plastic_energy"
[discretization]
dimension = 3
spacing = 1e-3
horizon_ratio = 3.015
[[shape]]
type = "box"
min = [0, 0, 0]
max = [0.024, 0.008, 0.008]
[material]
density = 7800
youngs_modulus = 215e9
poissons_ratio = 0.33
yield_stress = 340e6
tangent_modulus = 1.45e9
[model]
type = "lps_plastic"
damage = false
[time]
end_time = 2e-5
[[boundary]]
name = "left"
kind = "fixed"
region = { type = "box", min = [0, 0, 0], max = [0.0015, 0.008, 0.008] }
[[boundary]]
name = "right"
kind = "velocity"
value = ["20 * min(t / 5e-6, 1)", "free", "free"]
region = { type = "box", min = [0.0225, 0, 0], max = [0.024, 0.008, 0.008] }
[output]
frames = 2
fields = ["eq_plastic_strain", "stress", "triaxiality"]
)TOML";
  const auto scene = io::parse_scene_text(text, "lps_plastic_energy.toml");
  sim::RunOptions opt;
  opt.out_dir = dir.path() / "out";
  opt.progress = false;
  const auto r = sim::run_scene(scene, opt);
  ASSERT_EQ(r.status, "completed") << r.message;
  const auto& m = r.summary["metrics"];
  const double work = m["external_work"].get<double>(), plastic = m["plastic_work"].get<double>();
  ASSERT_GT(plastic, 0.1 * work) << "the bar must flow for this claim";
  test::record_gate({.id = "lps_plastic.energy_balance",
                     .claim = "A 3D bar pulled at 20 m/s to " +
                         std::to_string(m["max_eq_plastic_strain"].get<double>()) +
                         " equivalent plastic strain shall satisfy external work = kinetic + stored + plastic "
                         "work (measured: |K + U + W_p − W_ext| / W_ext at the end)",
                     .measured = std::abs(m["energy_error"].get<double>()) / work,
                     .expected = 1e-3,
                     .compare = test::Compare::at_most,
                     .tolerance_reason = "The issue's bound. Verlet is not exactly energy-conserving; its O(Δt²) "
                                         "shadow-energy error and the trapezoidal booking of the boundary work remain.",
                     .source = "[pdmpm] docs/models/lps_plastic.md (plastic work booked with the committed state)",
                     .unit = "",
                     .problem = kProblem});
}

}  // namespace
}  // namespace pdmpm
