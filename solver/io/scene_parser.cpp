#include <algorithm>
#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>

#include "solver/bc/analytic_field.hpp"
#include "solver/bc/expression.hpp"
#include "solver/io/scene.hpp"
#include "solver/io/toml_reader.hpp"
#include "solver/pd/model.hpp"

namespace pdmpm::io {
namespace {

int axis_index(const TomlReader& r, const std::string& key, int dim) {
  const std::string a = r.string(key);
  const std::string names = dim == 1 ? "x" : dim == 2 ? "x, y" : "x, y, z";
  if (a.size() == 1 && a[0] >= 'x' && a[0] < 'x' + dim) return a[0] - 'x';
  r.fail(key, "must be one of " + names + ", got \"" + a + "\"");
}

}  // namespace

// Declared in scene.hpp: [hybrid] initial_pd reads shapes too.
ShapeSpec read_shape(const TomlReader& r, int dim) {
  ShapeSpec s;
  s.key = r.path();
  s.type = r.string("type");
  if (s.type == "rectangle" || s.type == "segment") s.type = "box";
  if (s.type == "disk" || s.type == "sphere" || s.type == "circle") s.type = "ball";
  const std::string op = r.optional_string("operation").value_or("add");
  if (op != "add" && op != "subtract") r.fail("operation", "must be \"add\" or \"subtract\", got \"" + op + "\"");
  s.subtract = op == "subtract";
  if (s.type == "box") {
    s.min = r.numbers("min", dim);
    s.max = r.numbers("max", dim);
    for (int a = 0; a < dim; ++a)
      if (!(s.max[a] >= s.min[a]))
        r.fail("max", "must be ≥ min in every component (component " + std::to_string(a) + ")");
  } else if (s.type == "ball") {
    s.center = r.numbers("center", dim);
    s.radius = r.positive("radius", r.number("radius"));
  } else if (s.type == "cylinder") {
    if (dim != 3) r.fail("type", "cylinder needs dimension = 3 (use \"disk\" in 2D)");
    s.center = r.numbers("center", dim);
    s.radius = r.positive("radius", r.number("radius"));
    s.height = r.positive("height", r.number("height"));
    s.axis = r.has("axis") ? axis_index(r, "axis", dim) : 2;
  } else {
    r.fail("type", "must be one of box (rectangle), ball (disk, sphere), cylinder; got \"" + s.type + "\"");
  }
  r.finish();
  return s;
}

namespace {

void check_expression(const TomlReader& r, const std::string& key, const std::string& text) {
  if (text == "free") return;
  try {
    (void)bc::Expression::parse(text);
  } catch (const bc::ExpressionError& e) {
    r.fail(key, e.what());
  }
}

core::Setting read_setting(const TomlReader& d, int dim) {
  if (dim == 1) return core::Setting::bar1d;
  if (dim == 3) {
    if (d.has("plane")) d.fail("plane", "only for dimension = 2");
    return core::Setting::solid3d;
  }
  const std::string plane = d.string("plane");
  if (plane == "stress") return core::Setting::plane_stress;
  if (plane == "strain") return core::Setting::plane_strain;
  d.fail("plane", "must be \"stress\" or \"strain\", got \"" + plane + "\"");
}

void read_discretization(const TomlReader& d, Scene& s) {
  s.dimension = static_cast<int>(d.integer("dimension"));
  if (s.dimension < 1 || s.dimension > 3) d.fail("dimension", "must be 1, 2 or 3, got " + std::to_string(s.dimension));
  s.setting = read_setting(d, s.dimension);
  s.spacing = d.positive("spacing", d.number("spacing"));
  const auto ratio = d.optional_number("horizon_ratio");
  const auto delta = d.optional_number("horizon");
  if (ratio.has_value() && delta.has_value())
    d.fail("horizon_ratio", "give exactly one of horizon_ratio (m = δ/Δx) and horizon (δ in metres)");
  if (!ratio && !delta && s.method != Method::mpm)
    d.fail("horizon_ratio", "give exactly one of horizon_ratio (m = δ/Δx) and horizon (δ in metres)");
  if (ratio || delta) {  // MPM alone needs no horizon
    s.delta = ratio ? *ratio * s.spacing : *delta;
    if (ratio) d.in_range("horizon_ratio", *ratio, 1.0, 20.0, false, false);
    if (s.delta < s.spacing * (1.0 - 1e-12))
      d.fail(delta ? "horizon" : "horizon_ratio", "the horizon δ must be ≥ the spacing Δx (δ/Δx ≥ 1)");
    if (s.delta > 20.0 * s.spacing) d.fail("horizon", "δ/Δx must be ≤ 20 (families would exceed the bond table)");
  }
  if (s.dimension == 2) {
    s.measure = d.positive("thickness", d.number("thickness"));
    if (d.has("area")) d.fail("area", "only for dimension = 1 (2D uses thickness)");
  } else if (s.dimension == 1) {
    s.measure = d.positive("area", d.number("area"));
    if (d.has("thickness")) d.fail("thickness", "only for dimension = 2 (1D uses area)");
  } else {
    if (d.has("thickness")) d.fail("thickness", "only for dimension = 2");
    if (d.has("area")) d.fail("area", "only for dimension = 1");
  }
  if (auto pv = d.optional_enum<pd::PartialVolume>("partial_volume")) s.partial_volume = *pv;
  s.lattice_origin = d.optional_numbers("lattice_origin", s.dimension);
  if (ratio || delta) check_hpd_horizon(d, s, ratio ? "horizon_ratio" : "horizon");
  d.finish();
}

void read_model(const TomlReader& m, Scene& s, bool hybrid) {
  s.model = m.string("type");
  std::string names;
  for (const auto& n : pd::model_names()) names += n + ", ";
  if (s.model == "mpm" && hybrid)
    m.fail("type",
           "a hybrid scene ([hybrid]) needs the PD model in [model]: \"lps_plastic\" (MPM constitutive j2) or \"lps\" "
           "(MPM constitutive linear_elastic); the [mpm] table holds the grid options");
  if (s.model == "mpm") {
    s.method = Method::mpm;
    s.mpm.emplace();  // defaults; [material] and [mpm] fill it
    for (const char* pd_only : {"influence", "damage", "contact"})
      if (m.has(pd_only))
        m.fail(pd_only, "only for the peridynamic models (" + names.substr(0, names.size() - 2) + ")");
    m.finish();
    return;
  }
  if (!pd::find_model(s.model)) m.fail("type", "must be one of " + names + "mpm; got \"" + s.model + "\"");
  s.method = Method::pd;
  read_pd_model(m, s);
  if (hybrid) start_hybrid_model(m, s);
}

// A PD model with a plastic state: the plastic models of the table, and hpd with its J2 law.
bool plastic_pd_model(const Scene& s) {
  if (s.method == Method::mpm) return false;
  return pd::model_info(s.model).plastic || (s.model == "hpd" && s.hpd.law == pd::HpdLaw::j2);
}

void read_material(const TomlReader& m, Scene& s) {
  s.material.rho = m.positive("density", m.number("density"));
  const auto E = m.optional_number("youngs_modulus");
  const auto K = m.optional_number("bulk_modulus");
  if (E.has_value() == K.has_value()) m.fail("youngs_modulus", "give exactly one of youngs_modulus and bulk_modulus");
  // MPM materials take any ν in (−1, ½); the PD models state their own range.
  // hpd with the 1D law is bond-based: ν is PMB's (the Cauchy relation), not a free choice.
  const bool bond_based = s.model == "hpd" && s.hpd.law == pd::HpdLaw::axial_1d;
  if (bond_based && m.has("poissons_ratio") && s.setting != core::Setting::bar1d)
    m.fail("poissons_ratio",
           "the hpd model with constitutive = \"axial_1d\" is bond-based: ν is fixed (¼, ⅓ in plane stress); remove "
           "poissons_ratio or use constitutive = \"linear_elastic\"");
  const auto [lo, hi] = s.method == Method::mpm ? std::pair{-1.0, 0.5}
      : bond_based                              ? pd::model_info("pmb").poisson_range(s.setting)
                                                : pd::model_info(s.model).poisson_range(s.setting);
  const auto nu = m.optional_number("poissons_ratio");
  std::ostringstream fixed;
  fixed << lo;
  if (lo == hi) {
    // The model fixes ν; a given value must agree with it.
    if (nu && std::abs(*nu - lo) > 1e-9)
      m.fail("poissons_ratio",
             "the " + s.model + " model in " + std::string(name(s.setting)) + " has ν = " + fixed.str() +
                 " only; got " + std::to_string(*nu));
    s.material.nu = lo;
  } else if (s.setting == core::Setting::bar1d) {
    s.material.nu = nu.value_or(0.25);
  } else {
    if (!nu) m.fail("poissons_ratio", "missing (required for the " + s.model + " model)");
    s.material.nu = m.in_range("poissons_ratio", *nu, lo, hi, true, true);
  }
  if (E)
    s.material.E = m.positive("youngs_modulus", *E);
  else
    s.material.E = 3.0 * m.positive("bulk_modulus", *K) * (1.0 - 2.0 * s.material.nu);
  if (!(s.material.E > 0.0)) m.fail("bulk_modulus", "gives E ≤ 0 with this Poisson's ratio");
  if (s.method == Method::mpm) {
    for (const char* pd_only : {"critical_stretch", "fracture_energy"})
      if (m.has(pd_only))
        m.fail(pd_only, "only for the peridynamic models (MPM fails particles by [material.failure])");
    read_mpm_material(m, s);
    m.finish();
    return;
  }
  if (plastic_pd_model(s)) {
    read_hardening(m, s);
  } else {
    for (const char* key : {"yield_stress", "tangent_modulus"})
      if (m.has(key))
        m.fail(key,
               "only for the plastic models (type = \"lps_plastic\", \"hpd\" with constitutive = \"j2\", or "
               "\"mpm\" with constitutive = \"j2\")");
  }
  if (m.has("failure")) {
    if (!pd::model_info(s.model).plastic)
      m.fail("failure",
             "the ductile criterion acts on the equivalent plastic strain: type = \"lps_plastic\", or \"mpm\" with "
             "constitutive = \"j2\"; the elastic PD models fail bonds by critical_stretch or fracture_energy");
    read_ductile_failure(m, s);
  }
  s.critical_stretch = m.optional_number("critical_stretch");
  s.fracture_energy = m.optional_number("fracture_energy");
  if (s.critical_stretch && s.fracture_energy)
    m.fail("critical_stretch", "give at most one of critical_stretch and fracture_energy");
  if (s.critical_stretch) m.positive("critical_stretch", *s.critical_stretch);
  if (s.fracture_energy) m.positive("fracture_energy", *s.fracture_energy);
  if (s.method == Method::hybrid) read_hybrid_material(m, s);
  m.finish();
}

void read_time(const TomlReader& t, Scene& s) {
  s.time.integrator = t.optional_enum<Integrator>("integrator").value_or(Integrator::verlet);
  if (s.method == Method::mpm) {
    // MPM is explicit with its own grid-based stable step ([mpm] damping for quasi-static runs).
    if (s.time.integrator != Integrator::verlet)
      t.fail("integrator", "the mpm model steps explicitly; use [mpm] damping_* for quasi-static runs");
    for (const char* pd_only : {"stable_step", "tolerance", "max_steps", "load_steps"})
      if (t.has(pd_only)) t.fail(pd_only, "only for the peridynamic models");
  }
  if (s.method == Method::hybrid) {
    // One explicit step for both methods; stable_step picks the PD estimate.
    if (s.time.integrator != Integrator::verlet)
      t.fail("integrator", "the hybrid steps explicitly (velocity Verlet around the grid step)");
    for (const char* adr_only : {"tolerance", "max_steps", "load_steps"})
      if (t.has(adr_only)) t.fail(adr_only, "only for integrator = \"adr\" (the hybrid steps explicitly)");
  }
  s.time.end_time = t.optional_number("end_time");
  s.time.steps = t.optional_integer("steps");
  if (s.time.integrator == Integrator::verlet) {
    if (s.time.end_time.has_value() == s.time.steps.has_value())
      t.fail("end_time", "give exactly one of end_time and steps");
    if (s.time.end_time) t.positive("end_time", *s.time.end_time);
    if (s.time.steps && *s.time.steps <= 0) t.fail("steps", "must be ≥ 1");
  } else {
    if (s.time.end_time) t.fail("end_time", "not used by the adr integrator (use max_steps and tolerance)");
    if (s.time.steps) t.fail("steps", "not used by the adr integrator (use max_steps)");
  }
  s.time.dt = t.optional_number("dt");
  if (s.time.dt) t.positive("dt", *s.time.dt);
  if (auto f = t.optional_number("safety_factor"))
    s.time.safety_factor = t.in_range("safety_factor", *f, 0.0, 2.0, true, false);
  if (s.time.dt && t.has("safety_factor")) t.fail("safety_factor", "give either dt or safety_factor, not both");
  if (auto e = t.optional_enum<StableStepEstimate>("stable_step")) s.time.estimate = *e;
  if (auto v = t.optional_number("tolerance")) s.time.tolerance = t.in_range("tolerance", *v, 0.0, 1.0, true, true);
  if (auto v = t.optional_integer("max_steps")) {
    if (*v <= 0) t.fail("max_steps", "must be ≥ 1");
    s.time.max_steps = *v;
  }
  if (auto v = t.optional_integer("load_steps")) {
    if (s.time.integrator != Integrator::adr) t.fail("load_steps", "only for integrator = \"adr\"");
    if (*v < 1) t.fail("load_steps", "must be ≥ 1");
    s.time.load_steps = *v;
  }
  if (auto v = t.optional_number("energy_growth_limit"))
    s.time.energy_growth_limit = t.in_range("energy_growth_limit", *v, 1.0, 1e12, true, false);
  t.finish();
}

void read_boundaries(const TomlReader& root, Scene& s) {
  const auto list = root.tables("boundary");
  for (std::size_t k = 0; k < list.size(); ++k) {
    const TomlReader& b = list[k];
    BoundarySpec spec;
    spec.key = b.path();
    spec.name = b.optional_string("name").value_or("boundary" + std::to_string(k));
    if (!std::regex_match(spec.name, std::regex("[A-Za-z0-9_]+")))
      b.fail("name", "must be letters, digits and _ only (it names history.csv columns)");
    const std::string kind = b.string("kind");
    spec.kind = parse_enum<BoundaryKind>(kind, b.file(), b.path("kind"));
    for (const auto& shape : b.table_or_tables("region")) spec.region.push_back(read_shape(shape, s.dimension));
    const auto value = b.optional_expressions("value", s.dimension);
    const bool needs_value = spec.kind == BoundaryKind::displacement || spec.kind == BoundaryKind::velocity ||
        spec.kind == BoundaryKind::traction;
    if (needs_value && !value)
      b.fail("value", "missing (required for kind = \"" + kind + "\"): one expression per component");
    if (!needs_value && value) b.fail("value", "not used by kind = \"" + kind + "\"");
    if (value) {
      if (value->size() != static_cast<std::size_t>(s.dimension))
        b.fail("value", "must be a list of " + std::to_string(s.dimension) + " components");
      for (const auto& v : *value) check_expression(b, "value", v);
      spec.value = *value;
    }
    if (auto layer = b.optional_number("layer")) {
      if (spec.kind != BoundaryKind::traction) b.fail("layer", "only for kind = \"traction\"");
      spec.layer = b.positive("layer", *layer);
    }
    if (spec.kind == BoundaryKind::analytic) {
      spec.callback = b.string("callback");
      const auto names = bc::analytic_field_names();
      if (std::find(names.begin(), names.end(), spec.callback) == names.end()) {
        std::string all;
        for (const auto& n : names) all += (all.empty() ? "" : ", ") + n;
        b.fail("callback", "must be one of " + all + "; got \"" + spec.callback + "\"");
      }
      if (auto p = b.optional_table("parameters")) {
        for (const auto& key : p->keys()) spec.parameters[key] = p->number(key);
        p->finish();
      }
      try {
        bc::check_analytic_parameters(spec.callback, spec.parameters);
      } catch (const std::invalid_argument& e) {
        b.fail("parameters", e.what());
      }
    } else if (b.has("callback") || b.has("parameters")) {
      b.fail(b.has("callback") ? "callback" : "parameters", "only for kind = \"analytic\"");
    }
    if (b.has("moving")) {
      if (spec.kind != BoundaryKind::velocity) b.fail("moving", "only for kind = \"velocity\"");
      if (s.method == Method::pd)
        b.fail("moving",
               "only for MPM and hybrid scenes (it moves the grid-node box; a PD boundary holds its particles "
               "wherever they go)");
      spec.moving = b.boolean("moving", false);
    }
    b.finish();
    s.boundaries.push_back(std::move(spec));
  }
}

// An [[initial]] value: one number or expression of x, y, z per component
// ("free" leaves it alone); empty when the key is absent.
std::vector<std::string> read_initial_values(const TomlReader& r, const std::string& key, int dim) {
  const auto value = r.optional_expressions(key, static_cast<std::size_t>(dim));
  if (!value) return {};
  if (value->size() != static_cast<std::size_t>(dim))
    r.fail(key, "must be a list of " + std::to_string(dim) + " components");
  for (const auto& v : *value) {
    check_expression(r, key, v);
    if (v != "free" && bc::Expression::parse(v).depends_on_time())
      r.fail(key, "\"" + v + "\" uses t: initial values are at t = 0 (functions of x, y, z)");
  }
  return *value;
}

void read_initials(const TomlReader& root, Scene& s) {
  for (const auto& t : root.tables("initial")) {
    InitialSpec spec;
    spec.key = t.path();
    if (t.has("region"))  // no region: the whole body
      for (const auto& shape : t.table_or_tables("region")) spec.region.push_back(read_shape(shape, s.dimension));
    spec.velocity = read_initial_values(t, "velocity", s.dimension);
    spec.displacement = read_initial_values(t, "displacement", s.dimension);
    t.finish();
    if (spec.velocity.empty() && spec.displacement.empty())
      t.fail("", "needs velocity, displacement or both (one expression per component)");
    auto sets = [](const std::vector<std::string>& v) {
      return std::any_of(v.begin(), v.end(), [](const std::string& e) { return e != "free"; });
    };
    if (!sets(spec.velocity) && !sets(spec.displacement))
      t.fail(spec.velocity.empty() ? "displacement" : "velocity",
             "every component is \"free\": the table sets nothing");
    // ADR relaxes to rest with its own fictitious velocities: a given one would be ignored.
    if (!spec.velocity.empty() && s.time.integrator == Integrator::adr)
      t.fail("velocity", "not used by integrator = \"adr\" (quasi-static); give a displacement only");
    s.initials.push_back(std::move(spec));
  }
}

void read_geometry(const TomlReader& root, Scene& s) {
  for (const auto& t : root.tables("shape")) s.shapes.push_back(read_shape(t, s.dimension));
  if (s.shapes.empty()) root.fail("shape", "missing: at least one [[shape]] is required");
  if (s.shapes.front().subtract) root.fail("shape[0].operation", "the first shape must add material");

  for (const auto& t : root.tables("symmetry")) {
    if (s.method == Method::pd && !pd::model_info(s.model).symmetry_planes)
      t.fail("",
             "symmetry planes are not supported by the " + s.model +
                 " model yet (a ghost has no family of its own: lps_plastic keeps its plastic state on bond "
                 "sides, hpd builds each bond's sub-horizon from both ends' families); model the whole body");
    SymmetrySpec sym{t.path(), axis_index(t, "axis", s.dimension), t.number("position")};
    t.finish();
    s.symmetries.push_back(sym);
  }
  for (const auto& t : root.tables("precrack")) {
    PrecrackSpec pc;
    pc.key = t.path();
    if (s.dimension == 2) {
      pc.points = {t.numbers("from", 2), t.numbers("to", 2)};
      if (pc.points[0] == pc.points[1]) t.fail("to", "must differ from 'from' (a crack needs a length)");
    } else if (s.dimension == 3) {
      const std::vector<std::string> keys{"corner0", "corner1", "corner2"};
      for (const auto& k : keys) pc.points.push_back(t.numbers(k, 3));
    } else {
      t.fail("", "pre-cracks need dimension 2 (segment) or 3 (parallelogram)");
    }
    t.finish();
    s.precracks.push_back(pc);
  }
}

void read_loads(const TomlReader& root, Scene& s) {
  if (auto bf = root.optional_table("body_force")) {
    auto v = bf->optional_expressions("density", s.dimension);
    if (!v || v->size() != static_cast<std::size_t>(s.dimension))
      bf->fail("density", "missing: a list of " + std::to_string(s.dimension) + " force densities (N/m³)");
    for (const auto& e : *v) {
      if (e == "free") bf->fail("density", "\"free\" is not a force");
      check_expression(*bf, "density", e);
    }
    s.body_force = *v;
    bf->finish();
  }
  if (auto ind = root.optional_table("indenter")) {
    IndenterSpec spec;
    spec.center = ind->numbers("center", s.dimension);
    spec.velocity = ind->numbers("velocity", s.dimension);
    spec.radius = ind->positive("radius", ind->number("radius"));
    spec.stiffness = ind->positive("stiffness", ind->number("stiffness"));
    const std::string law = ind->optional_string("law").value_or("force");
    if (law != "force" && law != "force_density")
      ind->fail("law",
                "must be \"force\" (k (R − r)² in N per particle) or \"force_density\" (in N/m³); got \"" + law + "\"");
    spec.force_density = law == "force_density";
    ind->finish();
    s.indenter = spec;
  }
  for (const auto& t : root.tables("probe")) {
    ProbeSpec p{t.string("name"), t.numbers("point", s.dimension)};
    if (!std::regex_match(p.name, std::regex("[A-Za-z0-9_]+"))) t.fail("name", "must be letters, digits and _ only");
    t.finish();
    s.probes.push_back(p);
  }
}

void read_j_integrals(const TomlReader& root, Scene& s) {
  const auto tables = root.tables("j_integral");
  for (std::size_t k = 0; k < tables.size(); ++k) {
    const TomlReader& t = tables[k];
    if (s.dimension != 2) t.fail("tip", "the J-integral is for 2D scenes only");
    if (s.method == Method::pd && plastic_pd_model(s))
      t.fail("name",
             "not for the plastic PD models yet (their stress is not Hooke's law of the strain); MPM and the hybrid "
             "read plastic particles through MPM's law");
    JIntegralSpec j;
    j.key = "j_integral[" + std::to_string(k) + "]";
    j.name = t.string("name");
    if (!std::regex_match(j.name, std::regex("[A-Za-z0-9_]+"))) t.fail("name", "must be letters, digits and _ only");
    for (const JIntegralSpec& other : s.j_integrals)
      if (other.name == j.name) t.fail("name", "\"" + j.name + "\" is already the name of an earlier [[j_integral]]");
    j.tip = t.numbers("tip", 2);
    if (auto d = t.optional_numbers("direction", 2)) {
      const double n = std::hypot((*d)[0], (*d)[1]);
      if (!(n > 0.0) || !std::isfinite(n)) t.fail("direction", "must be a non-zero vector");
      j.direction = {(*d)[0] / n, (*d)[1] / n};
    }
    j.r_inner = t.in_range("r_inner", t.number("r_inner"), 0.0, 1e300, false, false);
    j.r_outer = t.positive("r_outer", t.number("r_outer"));
    if (!(j.r_outer > j.r_inner)) t.fail("r_outer", "must exceed r_inner (the ring r_inner < |x − tip| < r_outer)");
    t.finish();
    s.j_integrals.push_back(j);
  }
}

void read_crack(const TomlReader& root, Scene& s) {
  if (auto c = root.optional_table("crack")) {
    s.crack.enabled = true;
    if (auto v = c->optional_number("threshold"))
      s.crack.threshold = c->in_range("threshold", *v, 0.0, 1.0, true, false);
    if (auto v = c->optional_number("path_threshold"))
      s.crack.path_threshold = c->in_range("path_threshold", *v, 0.0, 1.0, true, false);
    if (auto v = c->optional_number("min_piece_fraction"))
      s.crack.min_piece_fraction = c->in_range("min_piece_fraction", *v, 0.0, 0.5, true, false);
    if (auto v = c->optional_number("speed_window")) s.crack.speed_window = c->positive("speed_window", *v);
    if (c->has("exclude"))
      for (const auto& shape : c->table_or_tables("exclude")) s.crack.exclude.push_back(read_shape(shape, s.dimension));
    c->finish();
  }
  for (const auto& t : root.tables("observe")) {
    ObserveSpec o;
    o.key = t.path();
    o.name = t.string("name");
    if (!std::regex_match(o.name, std::regex("[A-Za-z0-9_]+")))
      t.fail("name", "must be letters, digits and _ only (it names history.csv columns)");
    for (const auto& other : s.observes)
      if (other.name == o.name) t.fail("name", "\"" + o.name + "\" is used by another [[observe]]");
    o.point = t.numbers("point", s.dimension);
    if (auto r = t.optional_number("radius")) o.radius = t.positive("radius", *r);
    t.finish();
    s.observes.push_back(o);
    s.crack.enabled = true;
  }
}

void read_output(const TomlReader& o, Scene& s) {
  s.output.frames = o.optional_integer("frames");
  s.output.every = o.optional_integer("every");
  if (s.output.frames && s.output.every) o.fail("frames", "give at most one of frames and every");
  if (auto times = o.optional_numbers("frame_times", 0)) {
    if (s.output.frames || s.output.every) o.fail("frame_times", "give at most one of frames, every and frame_times");
    for (double t : *times)
      if (t < 0.0) o.fail("frame_times", "must be ≥ 0 (times in seconds)");
    s.output.frame_times = *times;
  }
  if (s.output.frames && *s.output.frames < 1) o.fail("frames", "must be ≥ 1");
  if (s.output.every && *s.output.every < 1) o.fail("every", "must be ≥ 1");
  s.output.history_every = o.optional_integer("history_every");
  if (s.output.history_every && *s.output.history_every < 1) o.fail("history_every", "must be ≥ 1");
  const auto allowed = output_field_names(s);
  s.output.fields = allowed;
  if (o.has("fields")) {
    s.output.fields = o.strings("fields");
    std::string list;
    for (const auto& f : allowed) list += (list.empty() ? "" : ", ") + f;
    for (const auto& f : s.output.fields)
      if (std::find(allowed.begin(), allowed.end(), f) == allowed.end())
        o.fail("fields", "unknown field \"" + f + "\" for the " + s.model + " model; allowed: " + list);
  }
  o.finish();
}

}  // namespace

void read_ductile_failure(const TomlReader& m, Scene& s) {
  const TomlReader f = m.table("failure");
  s.failure.enabled = f.boolean("enabled", true);
  s.failure.d0 = f.positive("d0", f.number("d0"));
  s.failure.c = f.number("c");
  if (auto r = f.optional_enum<core::FailureRule>("rule")) s.failure.rule = *r;
  f.finish();
}

void read_hardening(const TomlReader& m, Scene& s) {
  s.hardening.yield_stress = m.positive("yield_stress", m.number("yield_stress"));
  s.hardening.tangent_modulus =
      m.in_range("tangent_modulus", m.number("tangent_modulus"), 0.0, s.material.E, false, true);
}

std::vector<std::string> output_field_names(const Scene& s) {
  if (s.method == Method::mpm) return mpm_field_names();
  // hybrid: method 0 pd, 1 mpm, 2 transition, 3 removed; the stress measures and ε̄_p from PD
  // or the grid, by method (hybrid_run.cpp).
  std::vector<std::string> names = s.method == Method::hybrid
      ? std::vector<std::string>{"method", "displacement", "velocity", "damage", "stress", "von_mises"}
      : std::vector<std::string>{"displacement", "velocity", "damage", "dilatation", "stress", "von_mises"};
  if (plastic_pd_model(s)) names.insert(names.end(), {"triaxiality", "eq_plastic_strain"});
  return names;
}

Scene parse_scene_text(const std::string& text, const std::string& file_label) {
  toml::table raw;
  try {
    raw = toml::parse(text, file_label);
  } catch (const toml::parse_error& e) {
    std::ostringstream msg;
    msg << "not valid TOML at line " << e.source().begin.line << ", column " << e.source().begin.column << ": "
        << e.description();
    throw InputError(file_label, "", msg.str());
  }
  TomlReader root(raw, file_label, "");
  Scene s;
  s.file = file_label;
  s.text = text;

  const TomlReader head = root.table("scene");
  s.id = head.string("id");
  if (!std::regex_match(s.id, std::regex("[A-Za-z0-9_.-]+")))
    head.fail("id", "must be letters, digits, '_', '-' or '.' only");
  s.description = head.optional_string("description").value_or("");
  head.finish();

  read_model(root.table("model"), s, root.has("hybrid"));
  read_discretization(root.table("discretization"), s);
  read_material(root.table("material"), s);
  if (s.method == Method::mpm) {
    if (auto t = root.optional_table("mpm")) read_mpm_options(*t, s);
  } else if (s.method == Method::hybrid) {
    if (!root.has("mpm"))
      root.fail("mpm", "missing: a hybrid scene needs the [mpm] table (the grid options; it may be empty)");
    read_mpm_options(root.table("mpm"), s);
    read_hybrid(root.table("hybrid"), s);
  } else if (root.has("mpm")) {
    root.fail("mpm", "only for model type = \"mpm\" or a hybrid scene ([hybrid])");
  }
  const bool any_failure = s.critical_stretch || s.fracture_energy || (s.method != Method::mpm && s.failure.enabled);
  if (s.damage && !any_failure && root.table("model").has("damage"))
    root.fail("model.damage",
              "damage = true needs material.critical_stretch, material.fracture_energy or [material.failure]");
  if (!s.damage && s.method != Method::mpm && s.failure.enabled)
    root.fail("material.failure", "model.damage = false switches every failure rule off; remove one of the two");
  s.damage = s.damage && any_failure;
  read_geometry(root, s);
  read_time(root.table("time"), s);
  read_boundaries(root, s);
  read_initials(root, s);
  read_loads(root, s);
  read_crack(root, s);
  read_j_integrals(root, s);
  if (auto o = root.optional_table("output"))
    read_output(*o, s);
  else
    s.output.fields = output_field_names(s);
  root.finish();
  if (s.method == Method::mpm) check_mpm_scene(s);
  if (s.method == Method::hybrid) check_hybrid_scene(s);
  return s;
}

Scene parse_scene(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open the scene file");
  std::ostringstream buf;
  buf << in.rdbuf();
  return parse_scene_text(buf.str(), path);
}

}  // namespace pdmpm::io
