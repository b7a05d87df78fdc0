// MPM gates: manufactured solutions for large deformation (neo-Hookean).
//
// 1D: u = A sin(πX) sin(cπt) on 0 ≤ X ≤ 1 (uniaxial strain, ν = 0 so λ = 0).
// 2D: the axis-aligned displacement of Wallstedt & Guilkey (2008, J. Comput. Phys.
//     227:9628), u_x = A sin(2πX) sin(cπt), u_y = A sin(2πY) sin(cπt + π) on the
//     unit square, plane strain.
// The body force that makes each field exact is b = ü − (1/ρ₀) ∇₀·P with the
// neo-Hookean P = μ(F − F⁻ᵀ) + λ ln J F⁻ᵀ; F is diagonal, so
//   ∂P_xx/∂X = F_xx′ [μ(1 + F_xx⁻²) + λ(1 − ln J) F_xx⁻²].
// Both fields vanish on the faces normal to their component and have zero shear
// there, so the faces are mirror-symmetry planes of the grid.
// Measured: max over the run of the volume-weighted L2 norm of the particle
// displacement error, relative to A.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>

#include "solver/mpm/simulation.hpp"
#include "verification/gates/mpm_gate_util.hpp"
#include "verification/support/gate.hpp"

namespace pdmpm {
namespace {

using test::Compare;
using test::Gate;
namespace mu = test::mpm_util;

constexpr double kE = 1e7, kRho = 1000.0;
const double kC = std::sqrt(kE / kRho);  // 100 m/s: the time scale of the manufactured fields

// One axis of a separable field u = A sin(kX) s(t), s(t) = sin(cπt + phase).
struct Axis {
  double A, k, phase;
  double s(double t) const { return std::sin(kC * M_PI * t + phase); }
  double u(double X, double t) const { return A * std::sin(k * X) * s(t); }
  double v(double X, double t) const { return A * std::sin(k * X) * kC * M_PI * std::cos(kC * M_PI * t + phase); }
  double a(double X, double t) const { return -A * std::sin(k * X) * std::pow(kC * M_PI, 2) * s(t); }
  double F(double X, double t) const { return 1.0 + A * k * std::cos(k * X) * s(t); }
  double dF(double X, double t) const { return -A * k * k * std::sin(k * X) * s(t); }
};

template <int D>
struct MmsResult {
  double l2 = 0.0;  // max_t L2 error / A
};

template <int D>
MmsResult<D> run_mms(const std::array<Axis, D>& axes, double nu, int cells, mpm::ShapeFunction shape,
                     mpm::UpdateScheme scheme, double cfl, double t_end, bool cpgimp = false) {
  const double h = 1.0 / cells;
  auto particles = mu::box_particles<D>(Vec<D>::Zero(), Vec<D>::Ones(), h / 2.0);
  for (Index p = 0; p < particles.n_real; ++p)
    for (int a = 0; a < D; ++a) particles.v[p][a] = axes[a].v(particles.x0[p][a], 0.0);
  mpm::Settings<D> s;
  s.setting = D == 1 ? core::Setting::uniaxial_strain : core::Setting::plane_strain;
  s.cell_size = h;
  s.shape = shape;
  s.gimp_domain = cpgimp ? mpm::GimpDomain::stretch : mpm::GimpDomain::fixed;
  s.scheme = scheme;
  s.material = {mpm::MaterialModel::neo_hookean, {kE, nu, kRho}, {}};
  const double mu_ = s.material.elastic.shear(), lambda = s.material.elastic.lame();
  s.body_acceleration = [=](const Vec<D>& X, double t) {
    double J = 1.0;
    for (int a = 0; a < D; ++a) J *= axes[a].F(X[a], t);
    Vec<D> b;
    for (int a = 0; a < D; ++a) {
      const double F = axes[a].F(X[a], t);
      const double dP = axes[a].dF(X[a], t) * (mu_ * (1.0 + 1.0 / (F * F)) + lambda * (1.0 - std::log(J)) / (F * F));
      b[a] = axes[a].a(X[a], t) - dP / kRho;
    }
    return b;
  };
  for (int a = 0; a < D; ++a)
    for (int side : {+1, -1}) {
      mpm::GridBc<D> sym;
      sym.kind = mpm::BcKind::symmetry;
      sym.axis = a;
      sym.side = side;
      sym.position = side > 0 ? 0.0 : 1.0;
      s.boundaries.push_back(sym);
    }
  mpm::Simulation<D> sim(s, particles);
  // Fixed step from the initial wave speed, the same for the whole run.
  const int nsteps = static_cast<int>(std::ceil(t_end / (cfl * sim.stable_dt())));
  const double dt = t_end / nsteps;
  double vol = 0.0;
  for (Index p = 0; p < particles.n_real; ++p) vol += particles.volume[p];
  MmsResult<D> r;
  for (int n = 0; n < nsteps; ++n) {
    sim.step(dt);
    double e2 = 0.0;
    for (Index p = 0; p < particles.n_real; ++p)
      for (int a = 0; a < D; ++a) {
        const double d = particles.u[p][a] - axes[a].u(particles.x0[p][a], sim.time());
        e2 += particles.volume[p] * d * d;
      }
    r.l2 = std::max(r.l2, std::sqrt(e2 / vol) / axes[0].A);
  }
  return r;
}

const char* kProblem = "mpm_manufactured";

struct Variant {
  const char* label;
  mpm::ShapeFunction shape;
  bool cpgimp;
};
const Variant kVariants[] = {{"cpGIMP (stretched domains)", mpm::ShapeFunction::gimp, true},
                             {"uGIMP (fixed domains)", mpm::ShapeFunction::gimp, false},
                             {"quadratic B-spline", mpm::ShapeFunction::bspline2, false},
                             {"linear MPM", mpm::ShapeFunction::linear, false}};

template <int D>
void convergence_study(const std::array<Axis, D>& axes, double nu, const std::vector<int>& gated_cells,
                       const std::vector<int>& other_cells, const std::string& tag, const std::string& title,
                       const std::string& source) {
  nlohmann::json plot = nlohmann::json::array(), rows = nlohmann::json::array();
  double order_cp = 0.0;
  for (const Variant& v : kVariants) {
    const std::vector<int>& cells = v.cpgimp ? gated_cells : other_cells;
    std::vector<double> hs, err;
    for (int n : cells) {
      const auto r = run_mms<D>(axes, nu, n, v.shape, mpm::UpdateScheme::musl, 0.1, 2.0 / kC, v.cpgimp);
      hs.push_back(1.0 / n);
      err.push_back(r.l2);
      rows.push_back({v.label, n, r.l2});
    }
    const double order = mu::fitted_order(hs, err);
    plot.push_back(mu::series(std::string(v.label) + " (fitted order " + std::to_string(order).substr(0, 5) + ")", hs,
                              err, "points"));
    if (v.cpgimp) {
      order_cp = order;
      plot.push_back(mu::slope_line("slope 2", hs, err.front(), 2.0));
      EXPECT_TRUE(mu::monotone_decreasing(err)) << tag;
      test::record_gate(
          Gate{.id = "mpm.manufactured." + tag + ".gimp_order",
               .claim = "GIMP MPM (MUSL, domains stretched with F) shall converge in the L2 displacement error of "
                        "the " +
                   title + " at observed order ≥ 1.7 over " + std::to_string(cells.size()) + " levels (h = 1/" +
                   std::to_string(cells.front()) + " … 1/" + std::to_string(cells.back()) + ")",
               .measured = order,
               .expected = 1.7,
               .tolerance = 0.0,
               .compare = Compare::at_least,
               .tolerance_reason =
                   "second order expected (exact quadrature of contiguous particle domains, leapfrog in time "
                   "with dt ∝ h); the issue asks for ≥ 1.7",
               .source = source,
               .unit = "",
               .problem = kProblem});
      test::record_gate(Gate{
          .id = "mpm.manufactured." + tag + ".gimp_error_finest",
          .claim = "GIMP MPM shall reproduce the " + title +
              " to an L2 displacement error below 1 % of the "
              "amplitude at h = 1/" +
              std::to_string(cells.back()),
          .measured = err.back(),
          .expected = 1e-2,
          .tolerance = 0.0,
          .compare = Compare::at_most,
          .tolerance_reason = "1 % of the amplitude; the measured second-order trend puts the finest level well below",
          .source = source,
          .unit = "",
          .problem = kProblem});
    }
  }
  (void)order_cp;
  test::record_data(kProblem, tag + "_convergence",
                    {{"kind", "plot"},
                     {"title", title + ": L2 displacement error vs cell size"},
                     {"xlabel", "cell size h"},
                     {"ylabel", "max over one period of ||u − u_exact||₂ / A"},
                     {"xscale", "log"},
                     {"yscale", "log"},
                     {"series", plot},
                     {"caption",
                      "MUSL, CFL 0.1, two particles per cell per axis, one period 2/c. Linear MPM does "
                      "not converge: particles cross cell boundaries (the displacement amplitude is "
                      "several cells on the finer grids) and the jump of ∇S at a cell face makes the "
                      "internal force noisy (cell-crossing error), growing as h shrinks. uGIMP and the "
                      "B-spline remove the jump but not the quadrature error of particles that overlap "
                      "or leave gaps under ±30 % strain (in 1D their error stalls after h = 1/32 and then "
                      "grows); stretching the GIMP domains with F keeps them contiguous and restores "
                      "second order (Wallstedt & Guilkey 2008; Steffen, Kirby & Berzins 2008)."}});
  test::record_data(kProblem, tag + "_errors",
                    {{"kind", "table"},
                     {"title", title + ": L2 displacement errors"},
                     {"columns", {"method", "cells per unit length", "max_t L2 error / A"}},
                     {"rows", rows}});
}

TEST(FastMpmManufactured, OneDimensionalNeoHookean) {
  // A = 0.1: F = 1 ± 0.31 (large deformation); ν = 0 (λ = 0), uniaxial strain.
  const std::array<Axis, 1> ax{Axis{0.1, M_PI, 0.0}};
  convergence_study<1>(
      ax, 0.0, {8, 16, 32, 64, 128}, {8, 16, 32, 64, 128}, "1d", "1D manufactured solution u = A sin(πX) sin(cπt)",
      "[pdmpm] manufactured solution; neo-Hookean body force derived in the file header; [kamojjala2015]");
}

TEST(FastMpmManufactured, AxisAlignedTwoDimensional) {
  // A = 0.05: F_xx, F_yy = 1 ± 0.31; E = 1e7 Pa, ν = 0.3, ρ₀ = 1000 kg/m³, plane strain.
  const std::array<Axis, 2> ax{Axis{0.05, 2 * M_PI, 0.0}, Axis{0.05, 2 * M_PI, M_PI}};
  convergence_study<2>(ax, 0.3, {8, 16, 32}, {8, 16, 32}, "2d", "2D axis-aligned manufactured solution",
                       "[wallstedt-guilkey2008] axis-aligned displacement MMS");
}

TEST(FullMpmManufactured, AxisAlignedTwoDimensionalFourLevels) {
  const std::array<Axis, 2> ax{Axis{0.05, 2 * M_PI, 0.0}, Axis{0.05, 2 * M_PI, M_PI}};
  convergence_study<2>(ax, 0.3, {8, 16, 32, 64}, {8, 16, 32, 64}, "2d_full",
                       "2D axis-aligned manufactured solution (four levels)",
                       "[wallstedt-guilkey2008] axis-aligned displacement MMS");
}

}  // namespace
}  // namespace pdmpm
