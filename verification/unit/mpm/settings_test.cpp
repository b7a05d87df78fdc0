// Settings validation: every bad value is an InputError naming the key path.
#include "solver/mpm/settings.hpp"

#include <gtest/gtest.h>

#include "solver/core/error.hpp"

namespace pdmpm::mpm {
namespace {

Settings<2> good() {
  Settings<2> s;
  s.material = {MaterialModel::j2, {200e9, 0.3, 7800}, {300e6, 2e9}};
  return s;
}

std::string key_of(const Settings<2>& s, double dx = 1e-3) {
  try {
    validate(s, dx, "scene.toml", "mpm");
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "scene.toml");
    return e.key();
  }
  return "";
}

TEST(MpmSettings, GoodSettingsPass) { EXPECT_EQ(key_of(good()), ""); }

TEST(MpmSettings, BadValuesNameTheirKey) {
  auto s = good();
  s.material.elastic.nu = 0.5;
  EXPECT_EQ(key_of(s), "mpm.material.nu");
  s = good();
  s.material.j2.tangent_modulus = 300e9;
  EXPECT_EQ(key_of(s), "mpm.material.tangent_modulus");
  s = good();
  s.cell_size = 0.5e-3;  // smaller than Δx: GIMP domains would span 4 nodes
  EXPECT_EQ(key_of(s), "mpm.grid.cell_size");
  s = good();
  s.flip = 1.5;
  EXPECT_EQ(key_of(s), "mpm.flip");
  s = good();
  s.cfl = 0.0;
  EXPECT_EQ(key_of(s), "mpm.cfl");
  s = good();
  s.setting = core::Setting::solid3d;
  EXPECT_EQ(key_of(s), "mpm.setting");
  s = good();
  s.material.model = MaterialModel::neo_hookean;
  EXPECT_EQ(key_of(s), "mpm.material.model");  // plane stress neo-Hookean not implemented
  s = good();
  GridBc<2> sym;
  sym.kind = BcKind::symmetry;
  sym.position = 0.3e-3;  // not on a grid line of h = 2 mm
  s.boundaries.push_back(sym);
  EXPECT_EQ(key_of(s), "mpm.boundary[0].position");
  s = good();
  GridBc<2> vel;
  vel.kind = BcKind::velocity;
  s.boundaries.push_back(vel);
  EXPECT_EQ(key_of(s), "mpm.boundary[0].components");
  s = good();
  s.failure.enabled = true;
  EXPECT_EQ(key_of(s), "mpm.failure.d0");
  s = good();
  s.nonlocal.enabled = true;
  EXPECT_EQ(key_of(s), "mpm.nonlocal.length");
}

TEST(MpmSettings, MessageGivesTheAllowedRange) {
  auto s = good();
  s.material.elastic.nu = 0.7;
  try {
    validate(s, 1e-3, "scene.toml", "mpm");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("(-1, 0.5)"), std::string::npos) << e.what();
  }
}

TEST(MpmSettings, NamesRoundTrip) {
  for (auto v : {ShapeFunction::linear, ShapeFunction::gimp, ShapeFunction::bspline2})
    EXPECT_EQ(parse_enum<ShapeFunction>(name(v), "", "k"), v);
  for (auto v : {UpdateScheme::usf, UpdateScheme::usl, UpdateScheme::musl})
    EXPECT_EQ(parse_enum<UpdateScheme>(name(v), "", "k"), v);
  EXPECT_THROW(parse_enum<MaterialModel>("elastic", "f", "mpm.material.model"), InputError);
}

}  // namespace
}  // namespace pdmpm::mpm
