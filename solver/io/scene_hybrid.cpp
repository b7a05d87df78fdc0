// The hybrid parts of a scene: the [hybrid] table (adaptive SBPD–MPM, Noorian et
// al.), the MPM law that goes with the PD model, and what a hybrid scene refuses.
#include <string>

#include "solver/core/error.hpp"
#include "solver/io/scene.hpp"
#include "solver/io/toml_reader.hpp"
#include "solver/pd/model.hpp"

namespace pdmpm::io {
namespace {

// The MPM law a PD model's particles keep when they are handed to the grid.
mpm::MaterialModel grid_law_of(const std::string& pd_model) {
  return pd::model_info(pd_model).plastic ? mpm::MaterialModel::j2 : mpm::MaterialModel::linear_elastic;
}

}  // namespace

void start_hybrid_model(const TomlReader& m, Scene& s) {
  if (s.model != "lps_plastic" && s.model != "lps")
    m.fail("type",
           "a hybrid scene ([hybrid]) needs the PD model in [model]: \"lps_plastic\" (MPM constitutive j2) or \"lps\" "
           "(MPM constitutive linear_elastic); the [mpm] table holds the grid options; got \"" +
               s.model + "\"");
  s.method = Method::hybrid;
  s.mpm.emplace();
  s.mpm->constitutive = grid_law_of(s.model);
}

void read_hybrid_material(const TomlReader& m, Scene& s) {
  // One material for both methods: the MPM law follows from the PD model.
  if (auto c = m.optional_enum<mpm::MaterialModel>("constitutive"); c && *c != s.mpm->constitutive)
    m.fail("constitutive",
           "must be \"" + std::string(name(s.mpm->constitutive)) + "\" for the hybrid with the " + s.model +
               " model (one material for both methods: lps_plastic ↔ j2, lps ↔ linear_elastic)");
}

void read_hybrid(const TomlReader& t, Scene& s) {
  if (s.dimension < 2)
    throw InputError(s.file, "discretization.dimension",
                     "the hybrid needs dimension = 2 or 3 (got " + std::to_string(s.dimension) + ")");
  hybrid::Settings h;
  if (auto v = t.optional_enum<hybrid::Mode>("mode")) h.mode = *v;
  if (auto v = t.optional_enum<hybrid::Coupling>("coupling")) h.coupling = *v;
  if (auto v = t.optional_enum<hybrid::PlasticTransfer>("plastic_transfer")) h.plastic_transfer = *v;
  auto number = [&t](const char* key, double& field) {
    if (auto v = t.optional_number(key)) field = *v;
  };
  number("pd_radius", h.radii.pd_radius);
  number("expand_trigger", h.radii.expand_trigger);
  number("expand_radius", h.radii.expand_radius);
  number("keep_radius", h.radii.keep_radius);
  if (auto v = t.optional_integer("shrink_every")) {
    if (*v < 1 || *v > 1000000) t.fail("shrink_every", "must be an integer in [1, 1000000]");
    h.shrink_every = static_cast<int>(*v);
  }
  number("revert_residual", h.revert_residual);
  number("blend_width", h.blend_width);
  if (h.coupling == hybrid::Coupling::blended && s.model != "lps_plastic")
    t.fail("coupling", "\"blended\" needs [model] type = \"lps_plastic\" (it weights that model's force states)");
  if (h.revert_residual < 1.0 && s.model != "lps_plastic")
    t.fail("revert_residual", "needs [model] type = \"lps_plastic\" (it bounds the plastic model's elastic state)");
  if (t.has("initial_pd"))  // one shape or an array of them, as a boundary's region
    for (const auto& shape : t.table_or_tables("initial_pd")) s.initial_pd.push_back(read_shape(shape, s.dimension));
  h.precrack_starts_pd = t.boolean("precrack_starts_pd", true);
  h.audit_conversions = t.boolean("audit_conversions", false);
  if (auto tips = t.optional_table("tips")) {
    auto tip = [&tips](const char* key, double& field) {
      if (auto v = tips->optional_number(key)) field = *v;
    };
    tip("damage_threshold", h.tips.damage_threshold);
    tip("laplacian_threshold", h.tips.laplacian_threshold);
    tip("end_radius", h.tips.end_radius);
    tip("end_asymmetry", h.tips.end_asymmetry);
    tip("ridge_fraction", h.tips.ridge_fraction);
    tip("tip_offset", h.tips.tip_offset);
    tip("merge_radius", h.tips.merge_radius);
    tip("match_radius", h.tips.match_radius);
    tips->finish();
  }
  t.finish();
  h.validate(s.file);
  s.hybrid = h;
}

void check_hybrid_scene(const Scene& s) {
  auto fail = [&](const std::string& key, const std::string& why) { throw InputError(s.file, key, why); };
  if (!s.symmetries.empty())
    fail(s.symmetries.front().key,
         "symmetry planes are not supported in a hybrid scene (the PD regions are not mirrored); model the whole body");
  if (s.indenter) fail("indenter", "not supported in a hybrid scene (it would push the PD particles only)");
  if (s.contact.enabled)
    fail("model.contact", "not supported in a hybrid scene (it would act on the PD particles only)");
  if (s.crack.enabled)
    fail(s.observes.empty() ? "crack" : s.observes.front().key,
         "crack observables are not supported in a hybrid scene yet (history.csv lists the crack tips)");
  if (s.time.safety_factor > 1.0)
    fail("time.safety_factor", "is also the CFL number of the grid in a hybrid scene: must be in (0, 1]");
  check_grid_boundaries(s, "the hybrid");
}

}  // namespace pdmpm::io
