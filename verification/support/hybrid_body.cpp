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

}  // namespace pdmpm::test
