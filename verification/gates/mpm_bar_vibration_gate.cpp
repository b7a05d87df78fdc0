// MPM gate: axial vibration of a fixed–free elastic bar in its first mode.
//
// Bar 0 ≤ x ≤ L fixed at x = 0, free at x = L, started with v(x, 0) = v₀ sin(βx),
// β = π/(2L). The exact solution is the first mode,
//   v(x, t) = v₀ cos(ωt) sin(βx),  u(x, t) = (v₀/ω) sin(ωt) sin(βx),  ω = β sqrt(E/ρ),
// so the centre of mass moves with v_cm = (2v₀/π) cos ωt and u_cm = (2v₀/(πω)) sin ωt
// (e.g. Bardenhagen 2002; the standard MPM vibrating-bar test). The amplitude is
// small (strain 1e-5) so the finite-strain kinematics do not matter at the
// errors measured here.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <tuple>

#include "solver/mpm/simulation.hpp"
#include "verification/gates/mpm_gate_util.hpp"
#include "verification/support/gate.hpp"

namespace pdmpm {
namespace {

using test::Compare;
using test::Gate;
namespace mu = test::mpm_util;

constexpr double kL = 25.0, kE = 100.0, kRho = 1.0, kV0 = 1e-4;  // c = 10 m/s, strain amplitude 1e-5
const double kBeta = M_PI / (2.0 * kL);
const double kOmega = kBeta * std::sqrt(kE / kRho);

struct BarResult {
  double err_v = 0.0;       // max_t |v_cm − exact| / (2v₀/π)
  double err_u = 0.0;       // max_t |u_cm − exact| / (2v₀/(πω))
  double energy_drift = 0;  // max_t |E(t) − E(0)| / E(0)
  std::vector<double> t, v_cm, v_exact, energy;
};

BarResult run_bar(int cells, mpm::ShapeFunction shape, mpm::UpdateScheme scheme, double cfl, bool mirror_end,
                  double periods = 1.0) {
  const double h = kL / cells, dx = h / 2.0;  // two particles per cell (Noorian et al.: cell = 2Δx)
  auto particles = mu::box_particles<1>(Vec<1>(0.0), Vec<1>(kL), dx);
  for (Index p = 0; p < particles.n_real; ++p) particles.v[p][0] = kV0 * std::sin(kBeta * particles.x0[p][0]);
  mpm::Settings<1> s;
  s.setting = core::Setting::bar1d;
  s.cell_size = h;
  s.shape = shape;
  s.scheme = scheme;
  s.material = {mpm::MaterialModel::linear_elastic, {kE, 0.0, kRho}, {}};
  mpm::GridBc<1> fixed;
  fixed.name = "fixed end";
  fixed.kind = mirror_end ? mpm::BcKind::symmetry : mpm::BcKind::fixed;
  fixed.max = Vec<1>(0.0);
  fixed.position = 0.0;
  s.boundaries.push_back(fixed);
  mpm::Simulation<1> sim(s, particles);
  const double dt = cfl * sim.stable_dt();
  const double T = periods * 2.0 * M_PI / kOmega;
  const int nsteps = static_cast<int>(std::ceil(T / dt));
  const double mass = sim.total_mass();
  const double e0 = sim.energies().balance();
  const double v_amp = 2.0 * kV0 / M_PI, u_amp = v_amp / kOmega;
  BarResult r;
  for (int n = 0; n < nsteps; ++n) {
    sim.step(T / nsteps);
    const double t = sim.time();
    double mu_sum = 0.0;
    for (Index p = 0; p < particles.n_real; ++p) mu_sum += sim.state().mass[p] * particles.u[p][0];
    const double v_cm = sim.momentum()[0] / mass, u_cm = mu_sum / mass;
    // USL/MUSL are leapfrog: the velocity after a step belongs to the half step.
    const double tv = scheme == mpm::UpdateScheme::usf ? t : t - 0.5 * (T / nsteps);
    r.err_v = std::max(r.err_v, std::abs(v_cm - v_amp * std::cos(kOmega * tv)) / v_amp);
    r.err_u = std::max(r.err_u, std::abs(u_cm - u_amp * std::sin(kOmega * t)) / u_amp);
    const double e = sim.energies().balance();
    r.energy_drift = std::max(r.energy_drift, std::abs(e - e0) / e0);
    if (n % std::max(1, nsteps / 200) == 0) {
      r.t.push_back(t);
      r.v_cm.push_back(v_cm);
      r.v_exact.push_back(v_amp * std::cos(kOmega * t));
      r.energy.push_back(e / e0);
    }
  }
  return r;
}

const char* kProblem = "mpm_bar_vibration";
const char* kSource =
    "[sulsky-zhou-schreyer1995]; first-mode solution of the fixed-free bar, v = v0 cos(wt) sin(pi x / 2L)";

// Convergence in the cell size h (two particles per cell, CFL 0.1 so dt ∝ h).
TEST(FastMpmBarVibration, ConvergesAtSecondOrderForLinearAndGimp) {
  const std::vector<int> cells = {8, 16, 32, 64};
  std::vector<double> hs;
  for (int n : cells) hs.push_back(kL / n);
  nlohmann::json plot_series = nlohmann::json::array();
  nlohmann::json rows = nlohmann::json::array();
  struct Case {
    mpm::ShapeFunction shape;
    bool mirror;
    bool gated;
  };
  for (const Case c : {Case{mpm::ShapeFunction::linear, false, true}, Case{mpm::ShapeFunction::gimp, false, true},
                       Case{mpm::ShapeFunction::bspline2, true, false}}) {
    std::vector<double> eu, ev;
    for (int n : cells) {
      const BarResult r = run_bar(n, c.shape, mpm::UpdateScheme::musl, 0.1, c.mirror);
      eu.push_back(r.err_u);
      ev.push_back(r.err_v);
      rows.push_back({std::string(name(c.shape)) + (c.mirror ? " (mirror end)" : ""), "musl", n, r.err_u, r.err_v,
                      r.energy_drift});
    }
    const double pu = mu::fitted_order(hs, eu), pv = mu::fitted_order(hs, ev);
    const std::string label = std::string(name(c.shape));
    plot_series.push_back(
        mu::series(label + " u_cm (order " + std::to_string(pu).substr(0, 4) + ")", hs, eu, "points"));
    plot_series.push_back(
        mu::series(label + " v_cm (order " + std::to_string(pv).substr(0, 4) + ")", hs, ev, "points"));
    if (!c.gated) continue;
    for (auto [what, order, errs] : {std::tuple{"u", pu, eu}, std::tuple{"v", pv, ev}}) {
      test::record_gate(
          Gate{.id = "mpm.bar_vibration." + label + ".order_" + what,
               .claim = std::string("MUSL ") + label + " MPM shall converge in the centre-of-mass " +
                   (std::string(what) == "u" ? "displacement" : "velocity (half-step)") +
                   " of the vibrating bar at observed order ≥ 1.8 over 4 levels (h = L/8 … L/64)",
               .measured = order,
               .expected = 1.8,
               .tolerance = 0.0,
               .compare = Compare::at_least,
               .tolerance_reason =
                   "second order expected (leapfrog in time with dt ∝ h, consistent mass-lumped linear interpolation "
                   "in space); 0.2 below for the pre-asymptotic coarse level",
               .source = kSource,
               .unit = "",
               .problem = kProblem});
      EXPECT_TRUE(mu::monotone_decreasing(errs)) << label << " " << what;
    }
    test::record_gate(
        Gate{.id = "mpm.bar_vibration." + label + ".error_u_64",
             .claim = "MUSL " + label +
                 " MPM with 64 cells shall match the exact centre-of-mass displacement to "
                 "within 0.1 % of its amplitude over one period",
             .measured = eu.back(),
             .expected = 1e-3,
             .tolerance = 0.0,
             .compare = Compare::at_most,
             .tolerance_reason = "0.1 % of the amplitude: the second-order trend from the coarse levels predicts 5e-4",
             .source = kSource,
             .unit = "",
             .problem = kProblem});
  }
  plot_series.push_back(mu::slope_line("slope 2", hs, 0.03, 2.0));
  test::record_data(kProblem, "01_convergence",
                    {{"kind", "plot"},
                     {"title", "Vibrating bar: centre-of-mass error vs cell size"},
                     {"xlabel", "cell size h (m)"},
                     {"ylabel", "max over one period of |error| / amplitude"},
                     {"xscale", "log"},
                     {"yscale", "log"},
                     {"series", plot_series},
                     {"caption",
                      "MUSL, two particles per cell, CFL 0.1. The B-spline runs use a mirror (symmetry) "
                      "boundary at the fixed end; with plain fixed nodes the quadratic B-spline is first "
                      "order (its support crosses the wall), see the table."}});
  // The other update schemes and the B-spline with fixed nodes, for the record.
  for (auto scheme : {mpm::UpdateScheme::usl, mpm::UpdateScheme::usf})
    for (auto shape : {mpm::ShapeFunction::linear, mpm::ShapeFunction::gimp})
      for (int n : {16, 32, 64}) {
        const BarResult r = run_bar(n, shape, scheme, 0.1, false);
        rows.push_back({std::string(name(shape)), std::string(name(scheme)), n, r.err_u, r.err_v, r.energy_drift});
      }
  for (int n : {16, 32, 64}) {
    const BarResult r = run_bar(n, mpm::ShapeFunction::bspline2, mpm::UpdateScheme::musl, 0.1, false);
    rows.push_back({"bspline2 (fixed nodes)", "musl", n, r.err_u, r.err_v, r.energy_drift});
  }
  test::record_data(kProblem, "02_errors",
                    {{"kind", "table"},
                     {"title", "Vibrating bar errors (one period)"},
                     {"columns", {"shape", "scheme", "cells", "u_cm error", "v_cm error", "max |E/E0 - 1|"}},
                     {"rows", rows},
                     {"caption",
                      "Errors relative to the amplitude. USF updates the stress with the velocity of "
                      "the previous step and is first order in dt (its error falls towards the USL value "
                      "as the CFL number is reduced). Velocities of USL/MUSL are compared at the half step."}});
}

// Energy: leapfrog conserves a modified energy; the plain kinetic + strain energy
// oscillates by at most ½ ω dt relative (ω the first-mode frequency) and must not drift.
TEST(FastMpmBarVibration, EnergyStaysWithinLeapfrogBound) {
  const int cells = 32;
  const BarResult r = run_bar(cells, mpm::ShapeFunction::gimp, mpm::UpdateScheme::musl, 0.1, false, 4.0);
  const double h = kL / cells, dt = 0.1 * h / std::sqrt(kE / kRho);
  test::record_gate(Gate{
      .id = "mpm.bar_vibration.energy",
      .claim = "GIMP/MUSL MPM shall keep the total energy of the vibrating bar within ω·dt (relative) of "
               "its initial value over four periods",
      .measured = r.energy_drift,
      .expected = kOmega * dt,
      .tolerance = 0.0,
      .compare = Compare::at_most,
      .tolerance_reason = "leapfrog's energy error for a mode of frequency ω is ≤ ½ω dt (modified-energy argument); "
                          "factor 2 for the MPM transfers",
      .source = "[hairer2006] ch. IX",
      .unit = "",
      .problem = kProblem});
  test::record_data(kProblem, "04_energy",
                    {{"kind", "plot"},
                     {"title", "Vibrating bar: total energy / initial (GIMP, MUSL, 32 cells)"},
                     {"xlabel", "t (s)"},
                     {"ylabel", "E(t) / E(0)"},
                     {"xscale", "linear"},
                     {"yscale", "linear"},
                     {"series", {mu::series("E/E0", r.t, r.energy)}},
                     {"caption", "Bounded oscillation of order ω dt, no secular drift over four periods."}});
  const BarResult c = run_bar(16, mpm::ShapeFunction::gimp, mpm::UpdateScheme::musl, 0.1, false);
  test::record_data(kProblem, "03_velocity_history",
                    {{"kind", "plot"},
                     {"title", "Vibrating bar: centre-of-mass velocity (GIMP, MUSL, 16 cells)"},
                     {"xlabel", "t (s)"},
                     {"ylabel", "v_cm (m/s)"},
                     {"xscale", "linear"},
                     {"yscale", "linear"},
                     {"series", {mu::series("MPM", c.t, c.v_cm, "points"), mu::series("exact", c.t, c.v_exact)}},
                     {"caption", "One period T = 4L/c = 10 s."}});
}

}  // namespace
}  // namespace pdmpm
