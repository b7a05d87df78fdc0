// MPM gate: generalized vortex (Kamojjala, Brannon, Sadeghirad & Guilkey 2015,
// "Verification tests in solid mechanics", Eng. Comput. 31:193–213).
//
// Ring R_i = 0.75 ≤ R ≤ R_o = 1.25 whose circles turn rigidly by
//   α(R, t) = A g(R) h(t),  g = 1 − 32(R−1)² + 256(R−1)⁴,  h = (1 − cos 2πt)/2,
// so x = Q(α) X, J = 1 and, for the neo-Hookean solid, σ = μ(B − I) with shear
// γ = R α′ in the polar frame. Balance of momentum gives the body force (current
// polar basis at angle Θ + α; derived here, ρ = ρ₀ since J = 1):
//   b_r = −R α̇² + (μ/ρ) R α′²,   b_θ = R α̈ − (μ/ρ)(3α′ + R α″).
// g and g′ vanish at R_i and R_o, so both faces are traction-free and the ring is
// a free body. Constants as in the CPDI2 vortex example of Nguyen's MPM-Matlab code
// (after Sadeghirad, Brannon & Guilkey 2013): A = 1/3, E = 1000 Pa, ν = 0.3, ρ = 1000 kg/m³;
// t ∈ [0, 1] s (one full turn-and-return; peak shear γ = R α′ ≈ 2 at t = ½).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "solver/core/error.hpp"
#include "solver/mpm/simulation.hpp"
#include "verification/gates/mpm_gate_util.hpp"
#include "verification/support/gate.hpp"

namespace pdmpm {
namespace {

using test::Compare;
using test::Gate;
namespace mu = test::mpm_util;

const char* kProblem = "mpm_vortex";
double kA = 0.1;  // set per test
constexpr double kRi = 0.75, kRo = 1.25, kE = 1000.0, kNu = 0.3, kRho = 1000.0;

double g(double R) { const double d = R - 1.0; return 1.0 - 32.0 * d * d + 256.0 * d * d * d * d; }
double dg(double R) { const double d = R - 1.0; return -64.0 * d + 1024.0 * d * d * d; }
double d2g(double R) { const double d = R - 1.0; return -64.0 + 3072.0 * d * d; }
double ht(double t) { return 0.5 * (1.0 - std::cos(2.0 * M_PI * t)); }
double dht(double t) { return M_PI * std::sin(2.0 * M_PI * t); }
double d2ht(double t) { return 2.0 * M_PI * M_PI * std::cos(2.0 * M_PI * t); }

Vec<2> exact_position(const Vec<2>& X, double t) {
  const double alpha = kA * g(X.norm()) * ht(t), c = std::cos(alpha), s = std::sin(alpha);
  return Vec<2>(c * X[0] - s * X[1], s * X[0] + c * X[1]);
}

class Annulus final : public core::Shape<2> {
 public:
  bool contains(const Vec<2>& x, double tol) const override {
    const double r = x.norm();
    return r >= kRi - tol && r <= kRo + tol;
  }
  core::Bounds<2> bounds() const override { return {Vec<2>::Constant(-kRo), Vec<2>::Constant(kRo)}; }
  std::string describe() const override { return "annulus"; }
};

struct VortexResult {
  double l2_end = 0.0, l2_max = 0.0;
};

VortexResult run_vortex(int cells_per_unit, mpm::ShapeFunction shape, mpm::GimpDomain domain, double cfl,
                        double flip = 1.0) {
  const double h = 1.0 / cells_per_unit, dx = h / 2.0;
  core::Geometry<2> geo;
  geo.add(std::make_unique<Annulus>());
  core::Lattice<2> lat;
  lat.origin = Vec<2>::Constant(0.5 * dx);
  lat.spacing = dx;
  auto particles = core::fill_lattice<2>(geo, lat, dx * dx);
  for (auto& k : particles.kind) k = core::ParticleKind::mpm;
  mpm::Settings<2> s;
  s.setting = core::Setting::plane_strain;
  s.cell_size = h;
  s.shape = shape;
  s.gimp_domain = domain;
  s.scheme = mpm::UpdateScheme::musl;
  s.material = {mpm::MaterialModel::neo_hookean, {kE, kNu, kRho}, {}};
  s.flip = flip;
  const double mu_rho = s.material.elastic.shear() / kRho;
  s.body_acceleration = [=](const Vec<2>& X, double t) {
    const double R = X.norm(), Theta = std::atan2(X[1], X[0]);
    const double a = kA * g(R) * ht(t), a1 = kA * dg(R) * ht(t), a2 = kA * d2g(R) * ht(t);
    const double adot = kA * g(R) * dht(t), addot = kA * g(R) * d2ht(t);
    const double br = -R * adot * adot + mu_rho * R * a1 * a1;
    const double bt = R * addot - mu_rho * (3.0 * a1 + R * a2);
    const double th = Theta + a;
    return Vec<2>(br * std::cos(th) - bt * std::sin(th), br * std::sin(th) + bt * std::cos(th));
  };
  s.padding_cells = 3;
  mpm::Simulation<2> sim(s, particles);
  // Step from the largest speed of the exact motion (R α̇ ≤ 1.25 A π) plus the wave speed.
  const double c = std::sqrt(s.material.elastic.wave_modulus(s.setting) / kRho) + kRo * kA * M_PI;
  const int nsteps = static_cast<int>(std::ceil(1.0 / (cfl * h / c)));
  VortexResult r;
  double vol = 0.0;
  for (Index p = 0; p < particles.n_real; ++p) vol += particles.volume[p];
  for (int n = 0; n < nsteps; ++n) {
    sim.step(1.0 / nsteps);
    if (n % 10 != 9 && n != nsteps - 1) continue;
    double e2 = 0.0;
    for (Index p = 0; p < particles.n_real; ++p)
      e2 += particles.volume[p] * (particles.position(p) - exact_position(particles.x0[p], sim.time())).squaredNorm();
    r.l2_max = std::max(r.l2_max, std::sqrt(e2 / vol));
    r.l2_end = std::sqrt(e2 / vol);
  }
  return r;
}

struct Method {
  const char* label;
  mpm::ShapeFunction shape;
  mpm::GimpDomain domain;
};
const Method kMethods[] = {{"uGIMP", mpm::ShapeFunction::gimp, mpm::GimpDomain::fixed},
                           {"cpGIMP", mpm::ShapeFunction::gimp, mpm::GimpDomain::stretch},
                           {"quadratic B-spline", mpm::ShapeFunction::bspline2, mpm::GimpDomain::fixed},
                           {"linear MPM", mpm::ShapeFunction::linear, mpm::GimpDomain::fixed}};

// A = 0.1: rotation up to 0.1 rad, peak shear γ ≈ 0.6 — large deformation that every
// interpolation here survives.
TEST(FastMpmVortex, ConvergenceAtModerateAmplitude) {
  kA = 0.1;
  const std::vector<int> cells = {10, 20, 40};
  std::vector<double> hs;
  for (int n : cells) hs.push_back(1.0 / n);
  nlohmann::json plot = nlohmann::json::array(), rows = nlohmann::json::array();
  for (const Method& m : kMethods) {
    std::vector<double> err;
    for (int n : cells) {
      const VortexResult r = run_vortex(n, m.shape, m.domain, 0.2);
      err.push_back(r.l2_max);
      rows.push_back({m.label, n, r.l2_max, r.l2_end});
    }
    const double order = mu::fitted_order(hs, err);
    plot.push_back(mu::series(std::string(m.label) + " (fitted order " + std::to_string(order).substr(0, 4) + ")", hs,
                              err, "points"));
    if (m.shape == mpm::ShapeFunction::gimp && m.domain == mpm::GimpDomain::fixed) {
      EXPECT_TRUE(mu::monotone_decreasing(err));
      test::record_gate(Gate{.id = "mpm.vortex.gimp_order",
                             .claim = "uGIMP MPM (MUSL) shall converge on the generalized vortex (A = 0.1) with observed order "
                             "≥ 1 in the L2 position error over 3 levels",
                             .measured = order, .expected = 1.0, .tolerance = 0.0, .compare = Compare::at_least,
                             .tolerance_reason = "the issue asks for the convergence to be reported; ≥ 1 is the weakest claim of "
                             "convergence (the free curved surfaces are represented by a staircase of particles, O(h))",
                             .source = "[kamojjala2015] (generalized vortex)",
                             .unit = "", .problem = kProblem});
    }
  }
  plot.push_back(mu::slope_line("slope 2", hs, 0.02, 2.0));
  test::record_data(kProblem, "01_convergence",
                    {{"kind", "plot"},
                     {"title", "Generalized vortex (A = 0.1): L2 position error vs cell size"},
                     {"xlabel", "cell size h"},
                     {"ylabel", "max over t ∈ [0, 1] of ||x − x_exact||₂ (m)"},
                     {"xscale", "log"},
                     {"yscale", "log"},
                     {"series", plot},
                     {"caption", "MUSL, CFL 0.2 (of c_p + max R α̇), two particles per cell per axis on a lattice "
                                 "clipped to the ring."}});
  test::record_data(kProblem, "02_errors",
                    {{"kind", "table"},
                     {"title", "Generalized vortex (A = 0.1) errors"},
                     {"columns", {"method", "cells per unit length", "max_t L2 error", "L2 error at t = 1"}},
                     {"rows", rows}});
}

// A = 1/3 (the amplitude of the CPDI2 example; peak shear γ ≈ 2): recorded, not gated.
TEST(FullMpmVortex, LargeAmplitudeBehaviour) {
  kA = 1.0 / 3.0;
  nlohmann::json rows = nlohmann::json::array();
  for (double flip : {1.0, 0.0})
    for (const Method& m : kMethods)
      for (int n : {10, 20, 40}) {
        std::string outcome;
        try {
          const VortexResult r = run_vortex(n, m.shape, m.domain, 0.2, flip);
          outcome = "max L2 error " + std::to_string(r.l2_max);
        } catch (const RunError& e) {
          outcome = std::string("run stopped: ") + e.what();
        }
        rows.push_back({m.label, flip == 1.0 ? "FLIP" : "PIC", n, outcome});
      }
  test::record_data(kProblem, "03_large_amplitude",
                    {{"kind", "table"},
                     {"title", "Generalized vortex at A = 1/3"},
                     {"columns", {"method", "velocity update", "cells per unit length", "outcome"}},
                     {"rows", rows},
                     {"caption", "With FLIP the finer runs eject particles at the outer surface after the peak "
                                 "shear (t ≈ 0.5–0.7 s); PIC stays stable but dissipates (≈ 6 % error that does not "
                                 "converge). Updated-Lagrangian MPM without a domain-tracking interpolation (CPDI, "
                                 "TLMPM) is known to struggle with this test."}});
}

}  // namespace
}  // namespace pdmpm
