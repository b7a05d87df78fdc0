#include "verification/support/hybrid_body.hpp"

#include "solver/sim/mpm_setup.hpp"
#include "verification/support/scene_text.hpp"

namespace pdmpm::test {

io::Scene HybridPlate::scene(const std::string& method) const {
  const bool pd = method == "pd";
  std::string keys = hardening;
  if (!pd) keys += "\nconstitutive = \"j2\"";
  for (const std::string* k : {&material_keys, pd ? &pd_material_keys : nullptr})
    if (k && !k->empty()) keys += "\n" + *k;
  return SceneText{.id = "hybrid",
                   .max = size,
                   .material_keys = keys,
                   .model = pd ? "lps_plastic" : "mpm",
                   .tables = pd ? tables + "\n" + pd_tables : tables}
      .parse("hybrid.toml");
}

HybridBody::HybridBody(const hybrid::Settings& settings, const HybridPlate& plate)
    : pd_setup(sim::build_pd<2>(plate.scene("pd"))) {
  pd = std::make_unique<pd::Simulation<2>>(sim::make_simulation(pd_setup));
  mpm = std::make_unique<mpm::Simulation<2>>(sim::build_mpm<2>(plate.scene("mpm")).settings, pd_setup.system.particles);
  hybrid = std::make_unique<hybrid::Simulation<2>>(*pd, *mpm, settings);
}

SceneText hybrid_plate_scene(const std::string& hybrid_keys, const std::string& time) {
  SceneText t;
  t.id = "hybrid_plate";
  t.plane = "strain";
  t.min = {0.0, 0.0};
  t.max = {0.03, 0.02};
  t.poissons_ratio = "0.3";
  t.model = "lps_plastic";
  t.material_keys = "yield_stress = 4e8\ntangent_modulus = 2e9\ncritical_stretch = 0.01";
  t.time = time;
  t.tables = "[mpm]\n\n[hybrid]\n" + hybrid_keys +
      "\n[[precrack]]\nfrom = [0.0, 0.0100]\nto = [0.008, 0.0100]\n"
      "\n[[boundary]]\nname = \"top\"\nkind = \"velocity\"\nvalue = [\"0\", \"2.0\"]\n"
      "region = { type = \"box\", min = [0.0, 0.018], max = [0.03, 0.02] }\n"
      "\n[[boundary]]\nname = \"bottom\"\nkind = \"velocity\"\nvalue = [\"0\", \"-2.0\"]\n"
      "region = { type = \"box\", min = [0.0, 0.0], max = [0.03, 0.002] }\n"
      "\n[[probe]]\nname = \"mid\"\npoint = [0.015, 0.01]\n"
      "\n[output]\nframes = 3\n";
  return t;
}

}  // namespace pdmpm::test
