#include "verification/support/scene_text.hpp"

#include <fmt/format.h>

#include "solver/pd/model.hpp"

namespace pdmpm::test {

namespace {

std::string list(const std::vector<double>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) s += fmt::format("{}{}", i ? ", " : "", v[i]);
  return s + "]";
}

std::string lines(const std::string& text) { return text.empty() || text.back() == '\n' ? text : text + "\n"; }

}  // namespace

std::string SceneText::toml() const {
  std::string s = fmt::format("[scene]\nid = \"{}\"\n[discretization]\ndimension = {}\n", id, dimension);
  if (dimension == 2) s += fmt::format("plane = \"{}\"\n", plane);
  s += fmt::format("spacing = {}\n", spacing);
  if (horizon_ratio > 0.0) s += fmt::format("horizon_ratio = {}\n", horizon_ratio);
  if (dimension == 2) s += fmt::format("thickness = {}\n", thickness);
  if (dimension == 1) s += fmt::format("area = {}\n", thickness);
  s += fmt::format("[[shape]]\ntype = \"box\"\nmin = {}\nmax = {}\n", list(min), list(max));
  s += fmt::format("[material]\ndensity = {}\nyoungs_modulus = {}\n", density, youngs_modulus);
  if (!poissons_ratio.empty()) s += "poissons_ratio = " + poissons_ratio + "\n";
  s += lines(material_keys);
  s += fmt::format("[model]\ntype = \"{}\"\n", model) + lines(model_keys);
  s += "[time]\n" + lines(time);
  return s + lines(tables);
}

std::string elastic_range_keys(const std::string& model) {
  return pd::model_info(model).plastic ? "yield_stress = 1e30\ntangent_modulus = 0\n" : "";
}

double gate_horizon_ratio(const std::string& model, int dimension) {
  return model == "hpd" && dimension == 3 ? 2.015 : 3.015;
}

std::string flowing_keys(const std::string& model) {
  return pd::model_info(model).plastic ? "yield_stress = 1e6\ntangent_modulus = 2e9\n" : "";
}

io::Scene SceneText::parse(const std::string& file) const { return io::parse_scene_text(toml(), file); }

}  // namespace pdmpm::test
