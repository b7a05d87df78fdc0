#include "solver/mpm/settings.hpp"

#include <fmt/format.h>

#include <cmath>

#include "solver/core/error.hpp"

namespace pdmpm::mpm {

namespace {

// Collects the file and key prefix so each check is one line.
struct Checker {
  const std::string& file;
  const std::string& prefix;

  std::string key(const std::string& k) const { return prefix.empty() ? k : prefix + "." + k; }
  void fail(const std::string& k, const std::string& msg) const { throw InputError(file, key(k), msg); }
  void finite(const std::string& k, double v) const {
    if (!std::isfinite(v)) fail(k, fmt::format("must be a finite number (got {})", v));
  }
  // lo < v < hi (open) or lo ≤ v ≤ hi (closed) as requested.
  void range(const std::string& k, double v, double lo, double hi, bool lo_open, bool hi_open) const {
    finite(k, v);
    const bool ok = (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
    if (!ok)
      fail(k, fmt::format("must lie in {}{}, {}{} (got {})", lo_open ? "(" : "[", lo, hi, hi_open ? ")" : "]", v));
  }
  void positive(const std::string& k, double v) const {
    finite(k, v);
    if (!(v > 0.0)) fail(k, fmt::format("must be > 0 (got {})", v));
  }
  void non_negative(const std::string& k, double v) const {
    finite(k, v);
    if (!(v >= 0.0)) fail(k, fmt::format("must be ≥ 0 (got {})", v));
  }
};

template <int D>
std::string vec_str(const Vec<D>& v) {
  std::string s = "(";
  for (int a = 0; a < D; ++a) s += fmt::format("{}{}", a ? ", " : "", v[a]);
  return s + ")";
}

}  // namespace

template <int D>
void validate(const Settings<D>& s, double particle_spacing, const std::string& file, const std::string& prefix) {
  const Checker c{file, prefix};
  if (dimension(s.setting) != D)
    c.fail("setting",
           fmt::format("'{}' is a {}D setting but the body is {}D", name(s.setting), dimension(s.setting), D));
  c.positive("(particle spacing)", particle_spacing);

  // Grid.
  c.non_negative("grid.cell_size", s.cell_size);
  if (s.cell_size == 0.0) c.range("grid.cell_factor", s.cell_factor, 1.0, 16.0, false, false);
  const double h = s.cell_size > 0.0 ? s.cell_size : s.cell_factor * particle_spacing;
  // uGIMP particle domains (half-width Δx/2) must fit in one cell, else a particle
  // would touch 4 nodes per axis (the stencil and the scatter colouring assume ≤ 3).
  if (s.shape == ShapeFunction::gimp && particle_spacing > h * (1.0 + 1e-12))
    c.fail("grid.cell_size",
           fmt::format("must be ≥ the particle spacing Δx = {} for GIMP (got {})", particle_spacing, h));
  for (int a = 0; a < D; ++a) c.finite("grid.origin", s.origin[a]);
  if (s.domain_min.has_value() != s.domain_max.has_value())
    c.fail(s.domain_min ? "grid.max" : "grid.min", "grid.min and grid.max must be given together");
  if (s.domain_min) {
    for (int a = 0; a < D; ++a) {
      c.finite("grid.min", (*s.domain_min)[a]);
      c.finite("grid.max", (*s.domain_max)[a]);
      if (!((*s.domain_max)[a] > (*s.domain_min)[a]))
        c.fail("grid.max",
               fmt::format("must exceed grid.min on every axis (min {}, max {})", vec_str<D>(*s.domain_min),
                           vec_str<D>(*s.domain_max)));
    }
  }
  if (s.padding_cells < 2 || s.padding_cells > 100)
    c.fail("grid.padding_cells", fmt::format("must lie in [2, 100] (got {})", s.padding_cells));
  c.range("flip", s.flip, 0.0, 1.0, false, false);

  // Material.
  const Material& m = s.material;
  c.positive("material.E", m.elastic.E);
  c.range("material.nu", m.elastic.nu, -1.0, 0.5, true, true);
  c.positive("material.rho", m.elastic.rho);
  if (m.model == MaterialModel::j2) {
    c.positive("material.yield_stress", m.j2.yield_stress);
    c.range("material.tangent_modulus", m.j2.tangent_modulus, 0.0, m.elastic.E, false, true);
  }
  if (m.model == MaterialModel::neo_hookean &&
      (s.setting == core::Setting::plane_stress || s.setting == core::Setting::bar1d))
    c.fail(
        "material.model",
        fmt::format("neo_hookean is implemented for 3d, plane_strain and uniaxial_strain, not '{}'", name(s.setting)));
  if (s.nonlocal.enabled) {
    if (m.model != MaterialModel::j2) c.fail("nonlocal.enabled", "non-local plastic strain needs material.model = j2");
    c.positive("nonlocal.length", s.nonlocal.length);
    c.range("nonlocal.m", s.nonlocal.m, 0.0, 4.0, false, false);
  }
  if (s.failure.enabled) {
    if (m.model != MaterialModel::j2) c.fail("failure.enabled", "the ductile criterion needs material.model = j2");
    c.positive("failure.d0", s.failure.d0);
    c.finite("failure.c", s.failure.c);
  }

  // Boundaries.
  for (std::size_t i = 0; i < s.boundaries.size(); ++i) {
    const GridBc<D>& b = s.boundaries[i];
    const std::string k = fmt::format("boundary[{}]", i);
    if (b.kind == BcKind::roller || b.kind == BcKind::symmetry)
      if (b.axis < 0 || b.axis >= D) c.fail(k + ".axis", fmt::format("must lie in [0, {}] (got {})", D - 1, b.axis));
    if (b.kind == BcKind::symmetry) {
      c.finite(k + ".position", b.position);
      if (b.side != 1 && b.side != -1) c.fail(k + ".side", fmt::format("must be +1 or -1 (got {})", b.side));
      const double g = (b.position - s.origin[b.axis]) / h;
      if (std::abs(g - std::round(g)) > 1e-9)
        c.fail(k + ".position",
               fmt::format("a symmetry plane must lie on a grid line (origin {} + k·{}); got {}", s.origin[b.axis], h,
                           b.position));
    } else {
      for (int a = 0; a < D; ++a) {
        if (std::isnan(b.min[a]) || std::isnan(b.max[a])) c.fail(k + ".min", "region bounds must not be NaN");
        if (b.max[a] < b.min[a])
          c.fail(k + ".max",
                 fmt::format("region max must be ≥ min on every axis (min {}, max {})", vec_str<D>(b.min),
                             vec_str<D>(b.max)));
      }
    }
    if (b.kind == BcKind::velocity) {
      bool any = false;
      for (int a = 0; a < D; ++a) {
        c.finite(k + ".velocity", b.velocity[a]);
        any = any || b.components[a];
      }
      if (!any) c.fail(k + ".components", "a velocity boundary must prescribe at least one component");
    }
    c.non_negative(k + ".ramp_time", b.ramp_time);
  }
  for (std::size_t i = 0; i < s.tractions.size(); ++i) {
    const Traction<D>& t = s.tractions[i];
    const std::string k = fmt::format("traction[{}]", i);
    if (t.normal_axis < 0 || t.normal_axis >= D)
      c.fail(k + ".normal_axis", fmt::format("must lie in [0, {}] (got {})", D - 1, t.normal_axis));
    for (int a = 0; a < D; ++a) {
      c.finite(k + ".traction", t.traction[a]);
      c.finite(k + ".min", t.min[a]);
      c.finite(k + ".max", t.max[a]);
      if (t.max[a] < t.min[a]) c.fail(k + ".max", "region max must be ≥ min on every axis");
    }
    c.non_negative(k + ".ramp_time", t.ramp_time);
  }
  for (int a = 0; a < D; ++a) c.finite("gravity", s.gravity[a]);

  c.non_negative("dt", s.dt);
  c.range("cfl", s.cfl, 0.0, 1.0, true, false);
  c.non_negative("damping.viscous", s.damping_viscous);
  c.range("damping.local", s.damping_local, 0.0, 1.0, false, true);
}

template void validate(const Settings<1>&, double, const std::string&, const std::string&);
template void validate(const Settings<2>&, double, const std::string&, const std::string&);
template void validate(const Settings<3>&, double, const std::string&, const std::string&);

}  // namespace pdmpm::mpm
