#pragma once
// Everything an explicit MPM run needs besides its particles, as plain data a
// scene parser can fill key by key. Each field names its key (relative to the
// scene's MPM table, e.g. "mpm"); validate() checks every value and throws
// InputError naming the key path and the allowed range.
#include <algorithm>
#include <array>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "solver/core/material.hpp"
#include "solver/core/types.hpp"

namespace pdmpm::mpm {

// Grid interpolation. linear: classic MPM tent functions (Sulsky et al. 1994);
// gimp: uGIMP, particle domains of fixed half-width Δx/2 (Bardenhagen & Kober 2004);
// bspline2: quadratic B-splines (Steffen, Kirby & Berzins 2008).
enum class ShapeFunction { linear, gimp, bspline2 };
constexpr std::array<EnumName<ShapeFunction>, 3> names(ShapeFunction) {
  return {{{ShapeFunction::linear, "linear"}, {ShapeFunction::gimp, "gimp"}, {ShapeFunction::bspline2, "bspline2"}}};
}

// GIMP particle domains: fixed half-widths Δx/2 (uGIMP), or stretched with the
// deformation, lp_a = (Δx/2)·|F_aa| capped at h/2 (cpGIMP; Wallstedt & Guilkey 2008
// show GIMP is most accurate when the domains stay contiguous).
enum class GimpDomain { fixed, stretch };
constexpr std::array<EnumName<GimpDomain>, 2> names(GimpDomain) {
  return {{{GimpDomain::fixed, "fixed"}, {GimpDomain::stretch, "stretch"}}};
}

// Update-stress-first, update-stress-last, modified USL (Bardenhagen 2002;
// Wallstedt & Guilkey 2008 describe all three).
enum class UpdateScheme { usf, usl, musl };
constexpr std::array<EnumName<UpdateScheme>, 3> names(UpdateScheme) {
  return {{{UpdateScheme::usf, "usf"}, {UpdateScheme::usl, "usl"}, {UpdateScheme::musl, "musl"}}};
}

// linear_elastic: Hooke's law between the Lagrangian logarithmic strain ln U and the
// rotated Kirchhoff stress (= small-strain elasticity to first order, objective at any
// rotation); neo_hookean: compressible neo-Hookean σ = μ/J (B − I) + λ ln J / J I;
// j2: von Mises plasticity with linear isotropic hardening on the same log strain.
enum class MaterialModel { linear_elastic, neo_hookean, j2 };
constexpr std::array<EnumName<MaterialModel>, 3> names(MaterialModel) {
  return {{{MaterialModel::linear_elastic, "linear_elastic"},
           {MaterialModel::neo_hookean, "neo_hookean"},
           {MaterialModel::j2, "j2"}}};
}

enum class BcKind {
  fixed,     // all velocity components zero on the region's nodes
  roller,    // normal component (axis) zero, tangential free
  velocity,  // prescribed components (mask) = velocity · ramp(t)
  symmetry,  // mirror plane on a grid line: nodes beyond it mirror those inside
};
constexpr std::array<EnumName<BcKind>, 4> names(BcKind) {
  return {{{BcKind::fixed, "fixed"},
           {BcKind::roller, "roller"},
           {BcKind::velocity, "velocity"},
           {BcKind::symmetry, "symmetry"}}};
}

// The material of an MPM body: its constitutive law, elastic constants and (j2) hardening.
struct Material {
  MaterialModel model = MaterialModel::linear_elastic;  // key "material.model"
  core::Elastic elastic;  // "material.E", "material.nu" (−1, 0.5), "material.rho" (all > 0 but ν)
  core::J2Hardening j2;   // j2 only: "material.yield_stress" > 0, "material.tangent_modulus" [0, E)
};

// Non-local equivalent plastic strain (after Burghardt, Brannon & Guilkey 2012):
// hardening and failure use ε̂ = (1 − m) ε̄_p + m ⟨ε̄_p⟩, where ⟨·⟩ is a Gaussian-weighted
// average over particles within 3ℓ of the current positions.
struct Nonlocal {
  bool enabled = false;  // "nonlocal.enabled"
  double length = 0.0;   // "nonlocal.length" ℓ (m), > 0 when enabled
  double m = 1.0;        // "nonlocal.m" over-nonlocal weight, [0, 4]
};

// The load factor of a boundary velocity or traction with a ramp: linear 0 → 1 over
// ramp_time (a step at t = 0 when ramp_time = 0).
inline double ramp(double t, double ramp_time) {
  return ramp_time > 0.0 ? std::min(1.0, std::max(0.0, t / ramp_time)) : 1.0;
}

template <int D>
struct GridBc {
  std::string name;             // "boundary[i].name" (for messages and reactions)
  BcKind kind = BcKind::fixed;  // "boundary[i].kind"
  // Nodes inside the closed box [min, max] (fixed, roller, velocity).
  Vec<D> min = Vec<D>::Constant(-std::numeric_limits<double>::infinity());  // "boundary[i].min"
  Vec<D> max = Vec<D>::Constant(std::numeric_limits<double>::infinity());   // "boundary[i].max"
  int axis = 0;                      // "boundary[i].axis" roller/symmetry normal, [0, D)
  double position = 0.0;             // "boundary[i].position" symmetry plane, on a grid line
  int side = +1;                     // "boundary[i].side" symmetry: +1 body at x > position, −1 below
  Vec<D> velocity = Vec<D>::Zero();  // "boundary[i].velocity" (m/s)
  std::array<bool, D> components{};  // "boundary[i].components" prescribed components (velocity)
  double ramp_time = 0.0;            // "boundary[i].ramp_time" linear ramp 0 → velocity (s), ≥ 0
  // Instead of the constant, v(x, t) at the node position x (e.g. a scene expression);
  // only the `components` flagged are imposed. The ramp still applies.
  std::function<Vec<D>(const Vec<D>& x, double t)> velocity_field;
  // false when velocity_field does not depend on x (a ramp in time, say): it is then
  // evaluated once per bc and call instead of once per node.
  bool field_depends_on_position = true;
  // "boundary[i].moving" (velocity only): the box travels with the prescribed velocity
  // (taken at its centre, prescribed components only), so the nodes it holds follow the
  // material it grips; false: a box fixed in space, which material enters as it moves.
  bool moving = false;
};

// A surface traction applied to the particles whose reference position lies in
// [min, max]: force per particle = traction · V₀ / Δx (the particle's face area
// normal to `normal_axis`; thickness/cross-section are in V₀).
template <int D>
struct Traction {
  std::string name;                  // "traction[i].name"
  Vec<D> min = Vec<D>::Zero();       // "traction[i].min"
  Vec<D> max = Vec<D>::Zero();       // "traction[i].max"
  int normal_axis = 0;               // "traction[i].normal_axis" [0, D)
  Vec<D> traction = Vec<D>::Zero();  // "traction[i].traction" (Pa)
  double ramp_time = 0.0;            // "traction[i].ramp_time" (s), ≥ 0
  // Instead of the constant, t(X, t) at the particle's reference position X (e.g. a
  // scene expression); the ramp still applies.
  std::function<Vec<D>(const Vec<D>& X, double t)> traction_field;
};

template <int D>
struct Settings {
  core::Setting setting = D == 1 ? core::Setting::bar1d
      : D == 2                   ? core::Setting::plane_stress
                                 : core::Setting::solid3d;  // "setting"

  // Background grid. Grid lines pass through `origin`; cell size is `cell_size` if > 0,
  // else cell_factor × particle spacing (Noorian et al.: 2Δx). The node box is [domain_min,
  // domain_max] snapped outward to grid lines; unset → particle bounds ± padding_cells.
  double cell_size = 0.0;                        // "grid.cell_size" (m), ≥ 0
  double cell_factor = 2.0;                      // "grid.cell_factor", [1, 16]
  Vec<D> origin = Vec<D>::Zero();                // "grid.origin"
  std::optional<Vec<D>> domain_min, domain_max;  // "grid.min", "grid.max"
  int padding_cells = 3;                         // "grid.padding_cells", [2, 100]

  ShapeFunction shape = ShapeFunction::gimp;   // "shape_function"
  GimpDomain gimp_domain = GimpDomain::fixed;  // "gimp_domain" (gimp only)
  UpdateScheme scheme = UpdateScheme::musl;    // "update_scheme"
  double flip = 1.0;                           // "flip" FLIP fraction of the particle velocity update, [0, 1]

  Material material;             // "material.*"
  Nonlocal nonlocal;             // "nonlocal.*"
  core::DuctileFailure failure;  // "failure.*"

  std::vector<GridBc<D>> boundaries;   // "boundary[i]"
  std::vector<Traction<D>> tractions;  // "traction[i]"
  Vec<D> gravity = Vec<D>::Zero();     // "gravity" body acceleration (m/s²)
  // Library users (manufactured solutions) may add a body acceleration b(X, t) of the
  // reference position X; not a scene key.
  std::function<Vec<D>(const Vec<D>& X, double t)> body_acceleration;

  double dt = 0.0;               // "dt" fixed step (s); 0 → cfl × stable step
  double cfl = 0.5;              // "cfl" (0, 1]
  double damping_viscous = 0.0;  // "damping.viscous" grid mass-proportional damping c (1/s), ≥ 0
  double damping_local = 0.0;    // "damping.local" Cundall local damping factor, [0, 1)
};

// Checks every setting; `particle_spacing` is the lattice spacing Δx of the particles.
// Throws InputError(file, prefix + "." + key, message with the allowed range).
template <int D>
void validate(const Settings<D>& s, double particle_spacing, const std::string& file = "",
              const std::string& prefix = "mpm");

}  // namespace pdmpm::mpm
