#pragma once
// Small helpers shared by the MPM gates: lattice bodies, fitted convergence
// orders and report plots. Header-only so it stays inside the gates' folder.
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "solver/core/particle_builder.hpp"
#include "solver/core/shapes.hpp"
#include "verification/support/convergence_fit.hpp"

namespace pdmpm::test::mpm_util {

// Particles on a lattice of spacing dx with sites at lo + (i + ½) dx filling the
// box [lo, hi] (cell-centred, so the body's boundary lies on the box faces), all
// of kind mpm. `measure` = thickness (2D) or cross-section area (1D), 1 in 3D.
template <int D>
core::Particles<D> box_particles(const Vec<D>& lo, const Vec<D>& hi, double dx, double measure = 1.0) {
  core::Geometry<D> g;
  g.add(std::make_unique<core::Box<D>>(lo + Vec<D>::Constant(0.5 * dx), hi - Vec<D>::Constant(0.5 * dx)));
  core::Lattice<D> lat;
  lat.origin = lo + Vec<D>::Constant(0.5 * dx);
  lat.spacing = dx;
  core::Particles<D> p = core::fill_lattice<D>(g, lat, std::pow(dx, D) * measure);
  for (auto& k : p.kind) k = core::ParticleKind::mpm;
  return p;
}

// The observed order (least-squares slope of log(err) against log(h)).
using test::fitted_order;

inline bool monotone_decreasing(const std::vector<double>& v) {
  for (std::size_t i = 1; i < v.size(); ++i)
    if (!(v[i] < v[i - 1])) return false;
  return true;
}

inline nlohmann::json series(const std::string& label, const std::vector<double>& x, const std::vector<double>& y,
                             const std::string& style = "line") {
  return {{"label", label}, {"x", x}, {"y", y}, {"style", style}};
}

// A reference line c·h^p through the first point of a convergence series.
inline nlohmann::json slope_line(const std::string& label, const std::vector<double>& h, double e0, double p) {
  std::vector<double> y;
  for (double x : h) y.push_back(e0 * std::pow(x / h.front(), p));
  return series(label, h, y, "dashed");
}

}  // namespace pdmpm::test::mpm_util
