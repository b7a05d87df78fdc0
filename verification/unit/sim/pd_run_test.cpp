#include "solver/sim/pd_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "solver/io/scene.hpp"
#include "solver/sim/run.hpp"
#include "verification/support/scene_text.hpp"
#include "verification/support/scratch_dir.hpp"

namespace pdmpm::sim {
namespace {

namespace fs = std::filesystem;

// A notched strip pulled apart fast enough to crack within a few hundred steps.
io::Scene pulled_strip() {
  test::SceneText t;
  t.id = "strip";
  t.plane = "strain";
  t.max = {0.04, 0.02};
  t.density = 2500;
  t.youngs_modulus = 50e9;
  t.poissons_ratio = "0.25";
  t.material_keys = "critical_stretch = 0.002";
  t.time = "steps = 400";
  t.tables = R"(
[[precrack]]
from = [0.0, 0.0105]
to = [0.008, 0.0105]
[[boundary]]
name = "bottom"
kind = "velocity"
region = { type = "box", min = [0, 0], max = [0.04, 0.001] }
value = [0, -5.0]
[[boundary]]
name = "top"
kind = "velocity"
region = { type = "box", min = [0, 0.019], max = [0.04, 0.02] }
value = [0, 5.0]
[crack]
exclude = [{ type = "box", min = [0, 0], max = [0.04, 0.0045] }, { type = "box", min = [0, 0.0155], max = [0.04, 0.02] }]
[[observe]]
name = "ahead"
point = [0.012, 0.0105]
[output]
frame_times = [0.0, 1e-6, 1e-3]
history_every = 5
fields = ["damage"]
)";
  return t.parse("strip.toml");
}

TEST(PdRun, CrackObservablesReachHistoryAndSummary) {
  const auto scene = pulled_strip();
  const test::ScratchDir scratch("pd_run");
  const fs::path dir = scratch.fresh("out");
  RunOptions o;
  o.out_dir = dir;
  o.threads = 1;
  o.progress = false;
  const auto r = run_scene(scene, o);
  ASSERT_EQ(r.status, "completed") << r.message;

  std::ifstream csv(dir / "history.csv");
  std::string header;
  std::getline(csv, header);
  for (const char* col : {"cracked_particles", "components", "pieces", "cracks", "crack_tip_x", "crack_tip_y", "crack_extent",
                          "crack_angle_deg", "crack_speed", "crack_overall_angle_deg", "broken_bonds_ahead"})
    EXPECT_NE(header.find(col), std::string::npos) << col;

  const auto& c = r.summary.at("metrics").at("crack");
  for (const char* key : {"initiation_time", "initiation_sites", "separation_time", "components", "pieces", "cracks",
                          "rayleigh_speed", "speed_window", "locations", "overall_angle_deg"})
    EXPECT_TRUE(c.contains(key)) << key;
  // The strip is pulled apart across the notch: the crack starts and cuts it in two.
  ASSERT_FALSE(c.at("initiation_time").is_null());
  ASSERT_FALSE(c.at("separation_time").is_null());
  EXPECT_LE(c.at("initiation_time").get<double>(), c.at("separation_time").get<double>());
  EXPECT_EQ(c.at("pieces").get<int>(), 2);
  EXPECT_FALSE(c.at("locations").at("ahead").at("first_bond_failure").is_null());
  // The strip breaks along the notch line (the x axis; from either end).
  bool along = false;
  for (const auto& k : c.at("cracks")) {
    const double a = std::abs(k.at("angle_deg").get<double>());
    along = along || (k.at("extent").get<double>() > 0.01 && std::min(a, 180.0 - a) < 20.0);
  }
  EXPECT_TRUE(along);

  // frame_times: frames at steps 0, nearest to 1 µs, and the last (1 ms is past the end).
  std::ifstream xdmf(dir / "fields.xdmf");
  const std::string text((std::istreambuf_iterator<char>(xdmf)), std::istreambuf_iterator<char>());
  std::size_t frames = 0;
  for (std::size_t pos = text.find("<Time "); pos != std::string::npos; pos = text.find("<Time ", pos + 1)) ++frames;
  EXPECT_EQ(frames, 3u);
}

}  // namespace
}  // namespace pdmpm::sim
