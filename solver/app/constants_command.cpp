#include <fmt/format.h>

#include <iostream>
#include <nlohmann/json.hpp>

#include "solver/app/commands.hpp"
#include "solver/pd/constants.hpp"

namespace pdmpm::app {

int constants_command(const ConstantsArgs& a) {
  using namespace pdmpm::pd;
  const core::Setting settings[] = {core::Setting::bar1d, core::Setting::plane_stress, core::Setting::plane_strain, core::Setting::solid3d};
  auto measure = [&](core::Setting s) { return s == core::Setting::bar1d ? a.area : s == core::Setting::solid3d ? 1.0 : a.thickness; };
  const core::Elastic mat{a.E, a.nu, 1.0};

  nlohmann::json j;
  j["input"] = {{"E", a.E}, {"nu", a.nu}, {"delta", a.delta}, {"thickness", a.thickness}, {"area", a.area}, {"G0", a.G0}};
  j["note"] = "PMB constants are computed for the given nu; the PMB model itself admits only nu = 1/4 (3D, plane strain) or 1/3 (plane stress).";
  for (core::Setting s : settings) {
    nlohmann::json js;
    const auto k = lps_coefficients(s, mat);
    js["lps"] = {{"A", k.A}, {"B", k.B}, {"kappa", k.kappa}};
    const auto mo = madenci_oterkus(s, mat, a.delta, measure(s));
    js["madenci_oterkus"] = {{"a", mo.a}, {"b", mo.b}, {"d", mo.d}};
    for (Influence w : all_influences) {
      nlohmann::json e = {{"pmb_micromodulus_c", pmb_micromodulus(w, s, mat, a.delta, measure(s))},
                          {"lps_weighted_volume_m", lps_weighted_volume(w, s, a.delta, measure(s))}};
      if (a.G0 > 0) e["critical_stretch_s0"] = critical_stretch(w, s, mat, a.G0, a.delta, measure(s));
      js["influence"][std::string(name(w))] = e;
    }
    j["settings"][std::string(name(s))] = js;
  }
  if (a.format == "json") {
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  std::cout << fmt::format("Bond constants for E = {:.6g} Pa, ν = {:.6g}, δ = {:.6g} m, h = {:.6g} m, A = {:.6g} m²{}\n",
                           a.E, a.nu, a.delta, a.thickness, a.area, a.G0 > 0 ? fmt::format(", G₀ = {:.6g} J/m²", a.G0) : "");
  std::cout << "(PMB admits only ν = 1/4 in 3D and plane strain, 1/3 in plane stress; values for other ν are formal.)\n";
  for (core::Setting s : settings) {
    std::cout << fmt::format("\n[{}]\n", name(s));
    std::cout << fmt::format("  {:<18} {:>22} {:>22}{}\n", "influence ω", "PMB c", "LPS m (continuum)", a.G0 > 0 ? fmt::format(" {:>16}", "s₀ from G₀") : "");
    for (Influence w : all_influences) {
      std::cout << fmt::format("  {:<18} {:>22.12e} {:>22.12e}", name(w), pmb_micromodulus(w, s, mat, a.delta, measure(s)),
                               lps_weighted_volume(w, s, a.delta, measure(s)));
      if (a.G0 > 0) std::cout << fmt::format(" {:>16.8e}", critical_stretch(w, s, mat, a.G0, a.delta, measure(s)));
      std::cout << "\n";
    }
    const auto k = lps_coefficients(s, mat);
    const auto mo = madenci_oterkus(s, mat, a.delta, measure(s));
    std::cout << fmt::format("  LPS t = (A θ ω|ξ| + B ω e)/m: A = {:.10e}, B = {:.10e}, κ = {:.10e}\n", k.A, k.B, k.kappa);
    std::cout << fmt::format("  Madenci–Oterkus: a = {:.10e}, b = {:.10e}, d = {:.10e}\n", mo.a, mo.b, mo.d);
  }
  return 0;
}

}  // namespace pdmpm::app
