// The PD parts of a scene: the PD model's keys of [model] (influence function,
// damage, break timing, weighted volume, contact).
#include <string>

#include "solver/io/scene.hpp"
#include "solver/io/toml_reader.hpp"
#include "solver/pd/model.hpp"

namespace pdmpm::io {

void read_pd_model(const TomlReader& m, Scene& s) {
  if (auto w = m.optional_enum<pd::Influence>("influence")) s.influence = *w;
  s.damage = m.boolean("damage", true);
  if (auto bt = m.optional_enum<BreakTiming>("break_timing")) s.break_after_force = *bt == BreakTiming::after_force;
  if (auto wv = m.optional_enum<WeightedVolume>("weighted_volume")) {
    if (!pd::model_info(s.model).state_based) {
      std::string state_based;
      for (const auto& info : pd::model_table())
        if (info.state_based) state_based += (state_based.empty() ? "\"" : " or \"") + info.name + "\"";
      m.fail("weighted_volume", "only for type = " + state_based);
    }
    s.continuum_weighted_volume = *wv == WeightedVolume::continuum;
  }
  if (auto iso = m.optional_enum<Isotropy>("isotropy")) {
    if (!pd::model_info(s.model).plastic) m.fail("isotropy", "only for the plastic models (type = \"lps_plastic\")");
    s.isotropic_deviatoric = *iso == Isotropy::corrected;
  } else {
    s.isotropic_deviatoric = pd::model_info(s.model).plastic;
  }
  if (auto c = m.optional_table("contact")) {
    s.contact.enabled = c->boolean("enabled", true);
    if (auto v = c->optional_number("stiffness_factor"))
      s.contact.stiffness_factor = c->positive("stiffness_factor", *v);
    if (auto v = c->optional_number("distance_factor"))
      s.contact.distance_factor = c->in_range("distance_factor", *v, 0.0, 1.0, true, false);
    if (auto v = c->optional_number("max_distance"))
      s.contact.max_distance = c->in_range("max_distance", *v, 0.0, 3.0, true, false);
    s.contact.bonded_pairs = c->boolean("bonded_pairs", false);
    c->finish();
  }
  m.finish();
}

}  // namespace pdmpm::io
