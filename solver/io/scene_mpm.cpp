// The MPM parts of a scene: constitutive keys of [material] and the [mpm] table.
#include "solver/core/error.hpp"
#include "solver/io/scene.hpp"
#include "solver/io/toml_reader.hpp"

namespace pdmpm::io {

void read_mpm_material(const TomlReader& m, Scene& s) {
  MpmSpec& spec = *s.mpm;
  if (auto c = m.optional_enum<mpm::MaterialModel>("constitutive")) spec.constitutive = *c;
  const bool j2 = spec.constitutive == mpm::MaterialModel::j2;
  if (j2) {
    read_hardening(m, s);
  } else {
    for (const char* key : {"yield_stress", "tangent_modulus"})
      if (m.has(key)) m.fail(key, "only for constitutive = \"j2\"");
  }
  if (m.has("failure")) {
    if (!j2)
      m.fail("failure", "the ductile criterion needs constitutive = \"j2\" (it acts on the equivalent plastic strain)");
    read_ductile_failure(m, s);
  }
}

void read_mpm_options(const TomlReader& t, Scene& s) {
  MpmSpec& spec = *s.mpm;
  if (auto v = t.optional_enum<mpm::ShapeFunction>("shape_function")) spec.shape = *v;
  if (auto v = t.optional_enum<mpm::GimpDomain>("gimp_domain")) spec.gimp_domain = *v;
  if (auto v = t.optional_enum<mpm::UpdateScheme>("update_scheme")) spec.scheme = *v;
  if (auto v = t.optional_number("flip")) spec.flip = t.in_range("flip", *v, 0.0, 1.0, false, false);
  if (auto v = t.optional_number("cell_size")) spec.cell_size = t.positive("cell_size", *v);
  if (auto v = t.optional_number("cell_factor"))
    spec.cell_factor = t.in_range("cell_factor", *v, 1.0, 16.0, false, false);
  if (t.has("cell_size") && t.has("cell_factor"))
    t.fail("cell_factor", "give at most one of cell_size and cell_factor");
  if (auto v = t.optional_integer("padding_cells")) {
    if (*v < 2 || *v > 100) t.fail("padding_cells", "must be in [2, 100]");
    spec.padding_cells = static_cast<int>(*v);
  }
  // An explicit node box, for bodies that move far in one direction (padding grows all sides).
  if (auto v = t.optional_numbers("domain_min", static_cast<std::size_t>(s.dimension))) spec.domain_min = *v;
  if (auto v = t.optional_numbers("domain_max", static_cast<std::size_t>(s.dimension))) spec.domain_max = *v;
  if (spec.domain_min.empty() != spec.domain_max.empty())
    t.fail(spec.domain_min.empty() ? "domain_min" : "domain_max", "give both domain_min and domain_max, or neither");
  for (std::size_t a = 0; a < spec.domain_min.size(); ++a)
    if (!(spec.domain_min[a] < spec.domain_max[a])) t.fail("domain_max", "must exceed domain_min in every component");
  if (t.has("domain_min") && t.has("padding_cells"))
    t.fail("padding_cells", "give at most one of padding_cells and domain_min/domain_max");
  if (auto v = t.optional_number("damping_viscous"))
    spec.damping_viscous = t.in_range("damping_viscous", *v, 0.0, 1e12, false, false);
  if (auto v = t.optional_number("damping_local"))
    spec.damping_local = t.in_range("damping_local", *v, 0.0, 1.0, false, true);
  if (auto n = t.optional_table("nonlocal")) {
    spec.nonlocal.enabled = n->boolean("enabled", true);
    spec.nonlocal.length = n->positive("length", n->number("length"));
    if (auto v = n->optional_number("m")) spec.nonlocal.m = n->in_range("m", *v, 0.0, 4.0, false, false);
    n->finish();
  }
  t.finish();
}

void check_mpm_scene(const Scene& s) {
  auto fail = [&](const std::string& key, const std::string& why) { throw InputError(s.file, key, why); };
  if (!s.precracks.empty())
    fail("precrack[0]", "pre-cracks cut PD bonds; the mpm model has none (model a notch as a subtracted shape)");
  if (s.indenter) fail("indenter", "only for the peridynamic models");
  if (s.crack.enabled)
    fail(s.observes.empty() ? "crack" : s.observes.front().key, "crack observables need PD bonds (pmb, lps)");
  if (s.time.safety_factor > 1.0) fail("time.safety_factor", "is the CFL number of the mpm model: must be in (0, 1]");
  check_grid_boundaries(s, "the mpm model");
}

void check_grid_boundaries(const Scene& s, const std::string& who) {
  auto fail = [&](const std::string& key, const std::string& why) { throw InputError(s.file, key, why); };
  // Grid boundary conditions select the grid nodes inside a box; tractions the particles in it.
  for (const auto& b : s.boundaries) {
    if (b.kind == BoundaryKind::displacement || b.kind == BoundaryKind::analytic)
      fail(b.key + ".kind", who + " constrains grid velocities: use kind = \"fixed\", \"velocity\" or \"traction\"");
    for (std::size_t k = 0; k < b.region.size(); ++k)
      if (b.region[k].type != "box" || b.region[k].subtract)
        fail(b.region[k].key, who + " takes boundary regions as boxes (type = \"box\"/\"rectangle\", added)");
  }
}

const std::vector<std::string>& mpm_field_names() {
  static const std::vector<std::string> names{"displacement", "velocity",          "stress", "von_mises",
                                              "triaxiality",  "eq_plastic_strain", "failed"};
  return names;
}

}  // namespace pdmpm::io
