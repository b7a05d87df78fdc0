// MPM gates: J2 plasticity with linear isotropic hardening under uniaxial stress
// (the dog-bone steel of Noorian et al.: E = 215 GPa, ν = 0.33, σ_y = 340 MPa, E_t = 1.45 GPa).
//
// Bilinear law (uniaxial stress): σ = E ε below yield, σ = σ_y + E_t (ε − σ_y/E)
// beyond; the lateral strain is ε_lat = −ν σ/E − ε_p/2 (elastic Poisson contraction
// plus isochoric plastic flow), ε_p = ε − σ/E. The model works with the logarithmic
// strain and the rotated Kirchhoff stress, so these are the strain and stress
// compared; along a uniaxial (radial) path backward-Euler return mapping with linear
// hardening is exact, hence the 1e-10 tolerance.
//
//  (1) one material point, plane stress (Simo–Taylor return), 3D and 1D bar, ε to 5 %;
//  (2) the same point cycled ±1 % three times: isotropic hardening, each reversal
//      yields at minus the stress reached before it;
//  (3) an MPM plate in plane stress pulled slowly reproduces the curve.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "solver/mpm/constitutive.hpp"
#include "solver/mpm/simulation.hpp"
#include "verification/gates/mpm_gate_util.hpp"
#include "verification/support/gate.hpp"

namespace pdmpm {
namespace {

using test::Compare;
using test::Gate;
namespace mu = test::mpm_util;

const char* kProblem = "mpm_uniaxial_j2";
const char* kSource = "[simo-hughes1998] bilinear uniaxial law σ_y + E_t(ε − σ_y/E); [noorian] dog-bone material";
const mpm::Material kSteel{mpm::MaterialModel::j2, {215e9, 0.33, 7800.0}, {340e6, 1.45e9}};

// Exact uniaxial response to a strain path with linear isotropic hardening, built
// from the bilinear branches (not from a return map): elastic slope E between ±κ,
// plastic slope E_t along |σ| = κ(α), κ = σ_y + H α.
struct BilinearExact {
  double E, Et, H, sigma = 0.0, eps = 0.0, alpha = 0.0, sy;
  explicit BilinearExact(const mpm::Material& m)
      : E(m.elastic.E), Et(m.j2.tangent_modulus), H(m.j2.hardening_modulus(m.elastic.E)), sy(m.j2.yield_stress) {}
  // Advance to strain e (monotone within the call).
  void go_to(double e) {
    const double de = e - eps, dir = de > 0 ? 1.0 : -1.0;
    const double kappa = sy + H * alpha;
    const double elastic_room = (dir * kappa - sigma) / E;  // strain to reach the yield surface
    if (std::abs(de) <= std::abs(elastic_room)) {
      sigma += E * de;
    } else {
      const double plastic = de - elastic_room;  // strain beyond yield, along the E_t branch
      sigma = dir * kappa + Et * plastic;
      alpha += std::abs(plastic) * (1.0 - Et / E);  // ε_p increment = Δε − Δσ/E
    }
    eps = e;
  }
};

// Drive one point of `setting` along ε₁₁ with the lateral stresses zero (solved by
// secant iteration on the lateral strain). Returns (τ₁₁, lateral strain, ε̄_p).
template <int D>
struct UniaxialDriver {
  mpm::Constitutive<D> law;
  mpm::PointHistory history;
  double lateral = 0.0;  // current lateral log strain (ε₂₂, = ε₃₃ in 3D)
  UniaxialDriver(const mpm::Material& m, core::Setting s) : law(m, s) {}

  Mat<D> F_of(double e11, double elat) const {
    Mat<D> F = Mat<D>::Identity();
    F(0, 0) = std::exp(e11);
    for (int a = 1; a < D; ++a) F(a, a) = std::exp(elat);
    return F;
  }
  double lateral_stress(double e11, double elat) const {
    mpm::PointHistory h = history;
    const mpm::StressResult r = law.update(F_of(e11, elat), h);
    return D == 1 ? 0.0 : r.kirchhoff(1, 1);
  }
  mpm::StressResult step(double e11) {
    if constexpr (D > 1) {
      // Secant iteration from the last lateral strain and an elastic guess.
      double x0 = lateral, x1 = lateral - law.material().elastic.nu * 1e-6;
      double f0 = lateral_stress(e11, x0), f1 = lateral_stress(e11, x1);
      for (int it = 0; it < 100 && std::abs(f1) > 1e-15 * law.material().j2.yield_stress && f1 != f0; ++it) {
        const double x2 = x1 - f1 * (x1 - x0) / (f1 - f0);
        x0 = x1;
        f0 = f1;
        x1 = x2;
        f1 = lateral_stress(e11, x1);
      }
      lateral = x1;
    }
    mpm::StressResult r = law.update(F_of(e11, lateral), history);
    if constexpr (D == 1) lateral = r.out_of_plane_strain;
    return r;
  }
};

template <int D>
void monotone_curve(core::Setting setting, const std::string& tag, double& worst_stress, double& worst_lateral,
                    nlohmann::json* plot) {
  UniaxialDriver<D> drv(kSteel, setting);
  const double E = kSteel.elastic.E, sy = kSteel.j2.yield_stress, Et = kSteel.j2.tangent_modulus;
  std::vector<double> es, ss, exact;
  for (int n = 1; n <= 500; ++n) {
    const double e = 0.05 * n / 500.0;
    const mpm::StressResult r = drv.step(e);
    const double s = r.kirchhoff(0, 0);
    const double s_exact = e <= sy / E ? E * e : sy + Et * (e - sy / E);
    const double ep = e - s_exact / E;
    const double lat_exact = -kSteel.elastic.nu * s_exact / E - 0.5 * ep;
    worst_stress = std::max(worst_stress, std::abs(s - s_exact) / std::abs(s_exact));
    worst_lateral = std::max(worst_lateral, std::abs(drv.lateral - lat_exact) / std::abs(lat_exact));
    if (setting == core::Setting::plane_stress) {
      // Plane stress also reports ε₃₃, which must equal the lateral strain in uniaxial stress.
      worst_lateral = std::max(worst_lateral, std::abs(r.out_of_plane_strain - lat_exact) / std::abs(lat_exact));
    }
    es.push_back(e);
    ss.push_back(s / 1e6);
    exact.push_back(s_exact / 1e6);
  }
  if (plot) {
    plot->push_back(mu::series("bilinear law", es, exact));
    plot->push_back(mu::series("material point, " + tag, es, ss, "points"));
  }
}

TEST(FastMpmUniaxialJ2, SinglePointFollowsBilinearCurve) {
  double ws = 0.0, wl = 0.0;
  nlohmann::json plot = nlohmann::json::array();
  monotone_curve<2>(core::Setting::plane_stress, "plane stress", ws, wl, &plot);
  const double ws_ps = ws, wl_ps = wl;
  monotone_curve<3>(core::Setting::solid3d, "3D", ws, wl, nullptr);
  monotone_curve<1>(core::Setting::bar1d, "1D bar", ws, wl, nullptr);
  std::cout << "plane stress: stress " << ws_ps << " lateral " << wl_ps << "; all: " << ws << " " << wl << "\n";
  test::record_gate(Gate{
      .id = "mpm.uniaxial_j2.point.stress",
      .claim = "a J2 material point in uniaxial stress (plane-stress, 3D and 1D return maps) shall follow "
               "σ = σ_y + E_t(ε − σ_y/E) beyond yield and E ε below it, to 1e-10 relative, up to ε = 5 %",
      .measured = ws,
      .expected = 1e-10,
      .tolerance = 0.0,
      .compare = Compare::at_most,
      .tolerance_reason = "backward-Euler return mapping with linear hardening is exact along a radial stress path; "
                          "the residue is the secant solve of σ₂₂ = 0 (to 1e-15 σ_y) and rounding",
      .source = kSource,
      .unit = "",
      .problem = kProblem});
  test::record_gate(
      Gate{.id = "mpm.uniaxial_j2.point.lateral",
           .claim = "the lateral (and plane-stress thickness) strain shall equal −νσ/E − ε_p/2 to 1e-10 relative",
           .measured = wl,
           .expected = 1e-10,
           .tolerance = 0.0,
           .compare = Compare::at_most,
           .tolerance_reason = "exact for the radial path (isochoric plastic flow, Hooke's law for the elastic part)",
           .source = "[simo-hughes1998] J2 flow rule: ε_p,lat = −ε_p/2; Hooke: ε_e,lat = −νσ/E",
           .unit = "",
           .problem = kProblem});
  test::record_data(
      kProblem, "01_stress_strain",
      {{"kind", "plot"},
       {"title", "Uniaxial stress–strain curve, one plane-stress material point"},
       {"xlabel", "log strain ε"},
       {"ylabel", "Kirchhoff stress τ₁₁ (MPa)"},
       {"xscale", "linear"},
       {"yscale", "linear"},
       {"series", plot},
       {"caption", "E = 215 GPa, ν = 0.33, σ_y = 340 MPa, E_t = 1.45 GPa (H = E E_t/(E − E_t) = 1.46 GPa)."}});
}

TEST(FastMpmUniaxialJ2, CyclicLoadingHardensIsotropically) {
  UniaxialDriver<2> drv(kSteel, core::Setting::plane_stress);
  BilinearExact exact(kSteel);
  // ε path: 0 → +1 % → −1 % → +1 % → −1 % → +1 % → −1 %, 400 increments per leg.
  std::vector<double> targets = {0.01, -0.01, 0.01, -0.01, 0.01, -0.01};
  double e = 0.0, worst = 0.0;
  std::vector<double> es, ss, xs;
  for (double target : targets) {
    const double start = e;
    for (int n = 1; n <= 400; ++n) {
      e = start + (target - start) * n / 400.0;
      const double s = drv.step(e).kirchhoff(0, 0);
      exact.go_to(e);
      worst = std::max(worst, std::abs(s - exact.sigma) / kSteel.j2.yield_stress);
      es.push_back(e);
      ss.push_back(s / 1e6);
      xs.push_back(exact.sigma / 1e6);
    }
  }
  // Isotropic hardening: the peak stress grows every cycle by E_t times the plastic strain range.
  EXPECT_GT(std::abs(exact.sigma), 340e6 + 1.45e9 * 0.01);
  std::cout << "cyclic worst " << worst << " final alpha " << drv.history.eq_plastic_strain << " vs " << exact.alpha
            << "\n";
  test::record_gate(Gate{
      .id = "mpm.uniaxial_j2.point.cyclic",
      .claim = "under ±1 % strain cycles (three full cycles, plane stress) the J2 point shall follow the "
               "exact isotropic-hardening response (elastic slope E between ±κ(ε̄_p), slope E_t on yield) "
               "to 1e-10 σ_y",
      .measured = worst,
      .expected = 1e-10,
      .tolerance = 0.0,
      .compare = Compare::at_most,
      .tolerance_reason = "each increment is either elastic or plastic along a fixed uniaxial direction, where the "
                          "return map is exact; increments straddling yield are split exactly by both",
      .source = "linear isotropic hardening, κ = σ_y + H ε̄_p ([simo-hughes1998] §2.3)",
      .unit = "",
      .problem = kProblem});
  test::record_gate(Gate{.id = "mpm.uniaxial_j2.point.cyclic_eq_plastic",
                         .claim =
                             "the accumulated equivalent plastic strain after three cycles shall match the exact value "
                             "to 1e-10 relative",
                         .measured = std::abs(drv.history.eq_plastic_strain - exact.alpha) / exact.alpha,
                         .expected = 1e-10,
                         .tolerance = 0.0,
                         .compare = Compare::at_most,
                         .tolerance_reason = "exact along radial paths (see above)",
                         .source = "[simo-hughes1998] ε̄_p = ∫|dε_p| in uniaxial stress",
                         .unit = "",
                         .problem = kProblem});
  test::record_data(
      kProblem, "02_cyclic",
      {{"kind", "plot"},
       {"title", "Cyclic uniaxial loading, ±1 % (plane-stress point)"},
       {"xlabel", "log strain ε"},
       {"ylabel", "τ₁₁ (MPa)"},
       {"xscale", "linear"},
       {"yscale", "linear"},
       {"series", {mu::series("exact (isotropic hardening)", es, xs), mu::series("material point", es, ss, "dashed")}},
       {"caption",
        "Each reversal yields at minus the stress reached before it: the elastic range grows "
        "as 2κ(ε̄_p)."}});
}

// A plane-stress plate (quarter model: symmetry planes at x = 0 and y = 0) pulled at
// x = L with a velocity ramped up over 20 wave transits and held for 200 transits.
TEST(FastMpmUniaxialJ2, PlateInTensionReproducesTheCurve) {
  const double L = 20e-3, W = 10e-3, thickness = 3e-3, dx = 0.5e-3;
  auto particles = mu::box_particles<2>(Vec<2>(0, 0), Vec<2>(L, W), dx, thickness);
  mpm::Settings<2> s;
  s.setting = core::Setting::plane_stress;
  s.shape = mpm::ShapeFunction::gimp;
  s.scheme = mpm::UpdateScheme::musl;
  s.material = kSteel;
  const double c = std::sqrt(kSteel.elastic.wave_modulus(core::Setting::plane_stress) / kSteel.elastic.rho);
  const double transit = L / c, t_end = 220 * transit, eps_end = 0.02;
  const double V = eps_end * L / (t_end - 10 * transit);  // ramp: average speed over the run ≈ V
  for (int axis : {0, 1}) {
    mpm::GridBc<2> sym;
    sym.kind = mpm::BcKind::symmetry;
    sym.axis = axis;
    sym.position = 0.0;
    s.boundaries.push_back(sym);
  }
  mpm::GridBc<2> pull;
  pull.name = "pulled end";
  pull.kind = mpm::BcKind::velocity;
  pull.min = Vec<2>(L, -1.0);
  pull.velocity = Vec<2>(V, 0.0);
  pull.components = {true, false};
  pull.ramp_time = 20 * transit;
  s.boundaries.push_back(pull);
  mpm::Simulation<2> sim(s, particles);
  const double dt = 0.5 * sim.stable_dt();
  const int nsteps = static_cast<int>(std::ceil(t_end / dt));
  std::vector<double> es, ss, rs, xs;
  double worst = 0.0, worst_reaction = 0.0, worst_lateral = 0.0;
  const double E = kSteel.elastic.E, sy = kSteel.j2.yield_stress, Et = kSteel.j2.tangent_modulus;
  auto bilinear = [&](double e) { return e <= sy / E ? E * e : sy + Et * (e - sy / E); };
  for (int n = 0; n < nsteps; ++n) {
    sim.step(t_end / nsteps);
    if (n % 50 != 0 && n != nsteps - 1) continue;
    double e = 0.0, tau = 0.0, lat = 0.0;
    for (Index p = 0; p < particles.n_real; ++p) {
      e += std::log(sim.state().F.get(p)(0, 0));
      lat += std::log(sim.state().F.get(p)(1, 1));
      tau += sim.state().kirchhoff.get(p)(0, 0);
    }
    e /= particles.n_real;
    lat /= particles.n_real;
    tau /= particles.n_real;
    // Engineering stress from the reaction at the pulled end over the reference section.
    const double reaction = sim.reactions()[2][0] / (W * thickness);
    const double s_exact = bilinear(e);
    if (e > 0.25 * sy / E) {
      worst = std::max(worst, std::abs(tau - s_exact) / sy);
      // Reaction: nominal stress τ / λ₁ (λ₁ = eᵉ), times the lateral stretches' area change.
      worst_reaction = std::max(worst_reaction, std::abs(reaction - tau * std::exp(-e)) / sy);
      const double ep = e - s_exact / E;
      worst_lateral =
          std::max(worst_lateral, std::abs(lat - (-kSteel.elastic.nu * s_exact / E - 0.5 * ep)) / std::abs(e));
    }
    es.push_back(e);
    ss.push_back(tau / 1e6);
    rs.push_back(reaction / 1e6);
    xs.push_back(s_exact / 1e6);
  }
  std::cout << "plate: worst " << worst << " reaction " << worst_reaction << " lateral " << worst_lateral << " final e "
            << es.back() << " steps " << nsteps << "\n";
  test::record_gate(Gate{
      .id = "mpm.uniaxial_j2.plate.stress",
      .claim = "an MPM plate in plane stress (GIMP, MUSL, cell 2Δx) pulled quasi-statically to 2 % shall "
               "reproduce the bilinear curve: mean τ₁₁ within 1 % of σ_y of σ(ε̄₁₁) beyond ε = σ_y/(4E)",
      .measured = worst,
      .expected = 0.01,
      .tolerance = 0.0,
      .compare = Compare::at_most,
      .tolerance_reason = "dynamic residue of the finite loading rate (ramp over 20 wave transits, then ε̇ ≈ 1.3/s·…): "
                          "stress waves of amplitude ≲ ρ c ΔV; the material response itself is exact",
      .source = kSource,
      .unit = "",
      .problem = kProblem});
  test::record_gate(
      Gate{.id = "mpm.uniaxial_j2.plate.lateral",
           .claim = "the plate's mean lateral log strain shall equal −νσ/E − ε_p/2 to within 1 % of ε₁₁",
           .measured = worst_lateral,
           .expected = 0.01,
           .tolerance = 0.0,
           .compare = Compare::at_most,
           .tolerance_reason =
               "same dynamic residue as the stress; the plate contracts freely (top edge free, mirror at y = 0)",
           .source = "[simo-hughes1998] J2 flow rule and Hooke's law in uniaxial stress",
           .unit = "",
           .problem = kProblem});
  test::record_data(kProblem, "03_plate_curve",
                    {{"kind", "plot"},
                     {"title", "Plate in uniaxial tension (plane stress MPM) vs bilinear law"},
                     {"xlabel", "mean log strain ε̄₁₁"},
                     {"ylabel", "stress (MPa)"},
                     {"xscale", "linear"},
                     {"yscale", "linear"},
                     {"series",
                      {mu::series("bilinear law", es, xs), mu::series("mean particle τ₁₁", es, ss, "points"),
                       mu::series("end reaction / reference area", es, rs, "dashed")}},
                     {"caption",
                      "20 × 10 mm quarter plate, 3 mm thick, Δx = 0.5 mm, cell 1 mm, GIMP, MUSL; pulled "
                      "end velocity ramped over 20 transits L/c. The reaction is a nominal (first "
                      "Piola) stress, τ e^{−ε}."}});
  test::record_gate(Gate{
      .id = "mpm.uniaxial_j2.plate.reaction",
      .claim = "the force the pulled boundary exerts, over the reference section, shall equal the nominal "
               "stress τ₁₁ e^(−ε) of the particles to within 1 % of σ_y",
      .measured = worst_reaction,
      .expected = 0.01,
      .tolerance = 0.0,
      .compare = Compare::at_most,
      .tolerance_reason = "dynamic residue and the inertia of the boundary nodes; nodes on the symmetry plane count "
                          "half (their mirror image carries the other half)",
      .source = "[simo-hughes1998] equilibrium of the plate: P₁₁ = τ₁₁/λ₁ on the reference section",
      .unit = "",
      .problem = kProblem});
}

}  // namespace
}  // namespace pdmpm
