#include "verification/support/scene_gate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "solver/sim/run.hpp"
#include "verification/support/gate.hpp"

namespace pdmpm::test {

namespace fs = std::filesystem;

std::string scene_file(const std::string& name) {
  return std::string(PDMPM_SOURCE_DIR) + "/verification/scenes/" + name;
}

GateRun run_for_gate(const io::Scene& scene, const std::string& problem, const std::string& tag) {
  GateRun g;
  g.dir = fs::path(results_dir()) / "work" / problem / tag;
  fs::remove_all(g.dir);
  fs::create_directories(g.dir.parent_path());
  sim::RunOptions o;
  o.out_dir = g.dir;
  o.threads = 0;  // OpenMP's default (ctest sets one thread)
  o.progress = false;
  const auto r = sim::run_scene(scene, o);
  if (r.status != "completed") {
    ADD_FAILURE() << scene.id << " did not complete: " << r.status << ": " << r.message;
    throw std::runtime_error("run did not complete");
  }
  g.summary = r.summary;
  return g;
}

std::vector<double> GateRun::history(const std::string& column) const {
  std::ifstream in(dir / "history.csv");
  std::string line, cell;
  if (!std::getline(in, line)) throw std::runtime_error("no history.csv in " + dir.string());
  std::istringstream header(line);
  int index = -1;
  for (int k = 0; std::getline(header, cell, ','); ++k)
    if (cell == column) index = k;
  if (index < 0) throw std::runtime_error("history.csv has no column " + column);
  std::vector<double> values;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    for (int k = 0; k <= index && std::getline(row, cell, ','); ++k)
      if (k == index) values.push_back(std::stod(cell));
  }
  return values;
}

void record_image(const std::string& problem, const std::string& name, const Raster& img, const std::string& title,
                  const std::string& caption) {
  const fs::path rel = fs::path("data") / problem / (name + ".png");
  fs::create_directories(fs::path(results_dir()) / rel.parent_path());
  img.write_png((fs::path(results_dir()) / rel).string());
  record_data(problem, name, {{"kind", "image"}, {"title", title}, {"path", rel.string()}, {"caption", caption}});
}

Frame2d read_frame_2d(const FieldsReader& f, const FrameInfo& frame) {
  Frame2d out;
  out.time = frame.time;
  const auto pos = f.read(frame, "position");
  const auto u = f.read(frame, "displacement");
  out.damage = f.read(frame, "damage");
  out.x0.resize(out.damage.size());
  for (std::size_t i = 0; i < out.x0.size(); ++i) out.x0[i] = {pos[3 * i] - u[3 * i], pos[3 * i + 1] - u[3 * i + 1]};
  return out;
}

Raster damage_with_paths(const Frame2d& frame, const nlohmann::json& crack, double dx, int ppc) {
  PlaneView v;
  Raster img = damage_map(frame.x0, frame.damage, dx, ppc, &v);
  for (const auto& c : crack.at("cracks")) {
    const auto& path = c.at("path");
    const auto& t = path.at("t");
    const auto& x = path.at("x");
    const auto& y = path.at("y");
    if (t.empty() || t.front().get<double>() > frame.time * (1 + 1e-9)) continue;
    const double ox = c.at("origin")[0].get<double>(), oy = c.at("origin")[1].get<double>();
    // Tip positions as dots: when a crack branches its tip alternates between the
    // branches, and dots then trace both where a polyline would zigzag.
    for (std::size_t k = 0; k < t.size() && t[k].get<double>() <= frame.time * (1 + 1e-9); ++k) {
      const int px = static_cast<int>(std::lround(v.px(x[k].get<double>())));
      const int py = static_cast<int>(std::lround(v.py(y[k].get<double>())));
      img.fill(px - 1, py - 1, px + 1, py + 1, {0, 0, 0});
    }
    const int ix = static_cast<int>(std::lround(v.px(ox))), iy = static_cast<int>(std::lround(v.py(oy)));
    img.fill(ix - 2, iy - 2, ix + 2, iy + 2, {255, 255, 255});
  }
  return img;
}

double mirror_asymmetry(const Frame2d& frame, int axis, double position, double dx) {
  std::map<std::pair<long, long>, std::size_t> at;
  auto key = [&](double a, double b) {
    return std::make_pair(std::lround(a / (0.5 * dx)), std::lround(b / (0.5 * dx)));
  };
  for (std::size_t i = 0; i < frame.x0.size(); ++i) at[key(frame.x0[i][0], frame.x0[i][1])] = i;
  double diff = 0.0, total = 0.0;
  for (std::size_t i = 0; i < frame.x0.size(); ++i) {
    auto m = frame.x0[i];
    m[axis] = 2.0 * position - m[axis];
    const auto it = at.find(key(m[0], m[1]));
    if (it == at.end()) continue;
    diff += std::abs(frame.damage[i] - frame.damage[it->second]);
    total += frame.damage[i];
  }
  return total > 0.0 ? diff / total : 0.0;
}

void record_crack_table(const std::string& problem, const nlohmann::json& crack, double rayleigh_speed,
                        const std::string& caption) {
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& c : crack.at("cracks"))
    if (c.at("members").get<double>() >= 5)
      rows.push_back({c.at("origin")[0], c.at("origin")[1], c.at("start_time"), c.at("tip")[0], c.at("tip")[1],
                      c.at("angle_deg"), c.at("max_speed"), rayleigh_speed});
  record_data(problem, "02_cracks",
              {{"kind", "table"},
               {"title", "Cracks (≥ 5 cracked particles) at the end of the run"},
               {"columns",
                {"origin x [m]", "origin y [m]", "start [s]", "tip x [m]", "tip y [m]", "angle [°]", "max speed [m/s]",
                 "Rayleigh speed [m/s]"}},
               {"rows", rows},
               {"caption", caption}});
}

}  // namespace pdmpm::test
