// The PD parts of a scene: the PD model's keys of [model] (influence function,
// damage, break timing, weighted volume, contact, the hybrid model's law).
#include <sstream>
#include <string>

#include "solver/core/error.hpp"
#include "solver/io/scene.hpp"
#include "solver/io/toml_reader.hpp"
#include "solver/pd/model.hpp"
#include "solver/pd/sub_horizon.hpp"

namespace pdmpm::io {
namespace {

template <int D>
std::string hpd_shortfall(const Scene& s, double delta) {
  const double ratio = pd::family_ratio(s.partial_volume, delta, s.spacing);
  return pd::sub_horizon_shortfall(core::Stencil<D>::build(ratio), s.hpd.min_points(D));
}

std::string hpd_shortfall(const Scene& s, double delta) {
  if (s.dimension == 1) return hpd_shortfall<1>(s, delta);
  return s.dimension == 2 ? hpd_shortfall<2>(s, delta) : hpd_shortfall<3>(s, delta);
}

}  // namespace

void check_hpd_horizon(const TomlReader& d, const Scene& s, const std::string& horizon_key) {
  if (s.model != "hpd" || s.hpd.law == pd::HpdLaw::axial_1d) return;
  const int lo = s.dimension + 1;
  if (s.hpd.min_overlap != 0 && s.hpd.min_overlap < lo)
    throw InputError(s.file, "model.overlap_min_points",
                     "must be ≥ " + std::to_string(lo) + " (dimension + 1 points determine an affine field) in " +
                         std::to_string(s.dimension) + "D; got " + std::to_string(s.hpd.min_overlap));
  const std::string why = hpd_shortfall(s, s.delta);
  if (why.empty()) return;
  // The smallest horizon ratio (in steps of 0.05 Δx) whose interior sub-horizons all suffice.
  double ratio = s.delta / s.spacing;
  while (ratio <= 20.0 && !hpd_shortfall(s, ratio * s.spacing).empty()) ratio += 0.05;
  std::ostringstream hint;
  if (ratio <= 20.0)
    hint << "; the hpd model (constitutive = \"" << name(s.hpd.law) << "\") needs δ/Δx ≥ " << ratio;
  else
    hint << "; no δ/Δx ≤ 20 suffices";
  hint << " (or a smaller overlap_min_points, ≥ " << lo << ")";
  d.fail(horizon_key, "too few overlap points for this horizon: " + why + hint.str());
}

void read_pd_model(const TomlReader& m, Scene& s) {
  if (auto w = m.optional_enum<pd::Influence>("influence")) s.influence = *w;
  s.damage = m.boolean("damage", true);
  if (auto bt = m.optional_enum<BreakTiming>("break_timing")) s.break_after_force = *bt == BreakTiming::after_force;
  if (auto wv = m.optional_enum<WeightedVolume>("weighted_volume")) {
    if (s.model == "hpd")
      m.fail("weighted_volume", "not for type = \"hpd\" (its bond weights are normalised per particle)");
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
  if (auto dy = m.optional_enum<DamagedYield>("damaged_yield")) {
    if (!pd::model_info(s.model).plastic)
      m.fail("damaged_yield", "only for the plastic models (type = \"lps_plastic\")");
    s.yield_on_live_bonds = *dy == DamagedYield::live_bonds;
  }
  if (s.model == "hpd") {
    if (auto law = m.optional_enum<pd::HpdLaw>("constitutive")) s.hpd.law = *law;
    if (auto k = m.optional_integer("overlap_min_points")) {
      if (*k < 2 || *k > 1000)
        m.fail("overlap_min_points", "must be an integer in [dimension + 1, 1000]; got " + std::to_string(*k));
      if (s.hpd.law == pd::HpdLaw::axial_1d)
        m.fail("overlap_min_points", "only for the nD laws (linear_elastic, j2; axial_1d uses no sub-horizon)");
      s.hpd.min_overlap = static_cast<int>(*k);
    }
    if (auto w = m.optional_number("overlap_end_weight")) {
      if (s.hpd.law == pd::HpdLaw::axial_1d)
        m.fail("overlap_end_weight", "only for the nD laws (linear_elastic, j2; axial_1d uses no sub-horizon)");
      s.hpd.end_weight = m.in_range("overlap_end_weight", *w, 1.0, 1e4, false, false);
    }
    if (auto g = m.optional_number("stabilization")) {
      if (s.hpd.law == pd::HpdLaw::axial_1d)
        m.fail("stabilization", "only for the nD laws (linear_elastic, j2; axial_1d uses no sub-horizon)");
      s.hpd.stabilization = m.in_range("stabilization", *g, 0.0, 10.0, false, false);
    }
  } else {
    for (const char* key : {"constitutive", "overlap_min_points", "overlap_end_weight", "stabilization"})
      if (m.has(key)) m.fail(key, "only for type = \"hpd\" (MPM's law is [material] constitutive)");
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
