#include "solver/sim/crack_report.hpp"

#include <cmath>
#include <limits>
#include <optional>

#include "solver/sim/run_metrics.hpp"

namespace pdmpm::sim {

template <int D>
std::vector<std::string> crack_columns(const pd::CrackObservables<D>& c) {
  std::vector<std::string> cols{"cracked_particles", "components", "pieces", "cracks"};
  for (int a = 0; a < D; ++a) cols.push_back(std::string("crack_tip_") + axis_name(a));
  cols.insert(cols.end(), {"crack_extent", "crack_angle_deg", "crack_speed", "crack_overall_angle_deg"});
  for (const auto& loc : c.locations()) cols.push_back("broken_bonds_" + loc.name);
  return cols;
}

template <int D>
void crack_values(const pd::CrackObservables<D>& c, std::vector<double>& row) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::size_t active = 0;
  for (const auto& p : c.paths()) active += !p.ended;
  row.insert(row.end(), {static_cast<double>(c.cracked()), static_cast<double>(c.components()),
                         static_cast<double>(c.pieces()), static_cast<double>(active)});
  const auto* lead = c.leading();
  for (int a = 0; a < D; ++a) row.push_back(lead ? lead->tip.back()[a] : nan);
  row.push_back(lead ? lead->extent.back() : 0.0);
  row.push_back(lead ? lead->angle_deg() : nan);
  row.push_back(lead ? lead->speed.back() : nan);
  row.push_back(c.cracked() >= 2 ? c.overall_angle_deg() : nan);
  for (std::size_t k = 0; k < c.locations().size(); ++k) row.push_back(static_cast<double>(c.broken_at(k)));
}

template <int D>
nlohmann::json crack_summary(const pd::CrackObservables<D>& c, const pd::System<D>& sys) {
  auto opt = [](std::optional<double> v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); };
  auto vec = [](const Vec<D>& v) {
    std::vector<double> out(v.data(), v.data() + D);
    return out;
  };
  nlohmann::json j;
  j["threshold"] = c.settings().threshold;
  j["path_threshold"] = c.settings().path_threshold;
  j["min_piece_fraction"] = c.settings().min_piece_fraction;
  j["rayleigh_speed"] = pd::rayleigh_speed(sys.material, sys.setting);
  j["speed_window"] = c.speed_window();
  j["initiation_time"] = opt(c.initiation_time());
  // Where cracking started: the particles cracked at the initiation time.
  nlohmann::json sites = nlohmann::json::array();
  for (Index i : c.initiation_particles()) sites.push_back(vec(sys.particles.x0[i]));
  j["initiation_sites"] = sites;
  j["separation_time"] = opt(c.separation_time());
  j["components"] = c.components();
  j["pieces"] = c.pieces();
  j["initial_pieces"] = c.initial_pieces();
  j["cracked_particles"] = c.cracked();
  j["overall_angle_deg"] = c.overall_angle_deg();
  j["overall_angle_at_separation_deg"] =
      std::isfinite(c.separation_angle_deg()) ? nlohmann::json(c.separation_angle_deg()) : nlohmann::json(nullptr);
  j["max_speed"] = c.max_speed();
  nlohmann::json loc = nlohmann::json::object();
  for (std::size_t k = 0; k < c.locations().size(); ++k) {
    const auto& l = c.locations()[k];
    loc[l.name] = {{"point", vec(l.point)}, {"radius", l.radius}, {"first_bond_failure", opt(c.first_failure(k))},
                   {"broken_bonds", c.broken_at(k)}};
  }
  j["locations"] = loc;
  nlohmann::json cracks = nlohmann::json::array();
  for (const auto& p : c.paths()) {
    nlohmann::json path = {{"t", p.time}, {"extent", p.extent}};
    for (int a = 0; a < D; ++a) {
      std::vector<double> xa;
      for (const auto& tip : p.tip) xa.push_back(tip[a]);
      path[axis_name(a)] = xa;
    }
    std::vector<nlohmann::json> speed;
    for (double v : p.speed) speed.push_back(std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr));
    path["speed"] = speed;
    cracks.push_back({{"origin", vec(p.origin)},
                      {"start_time", p.time.front()},
                      {"last_time", p.time.back()},
                      {"ended", p.ended},
                      {"members", p.members},
                      {"tip", vec(p.tip.back())},
                      {"extent", p.extent.back()},
                      {"angle_deg", p.angle_deg()},
                      {"max_speed", p.max_speed()},
                      {"path", path}});
  }
  j["cracks"] = cracks;
  return j;
}

template std::vector<std::string> crack_columns<1>(const pd::CrackObservables<1>&);
template std::vector<std::string> crack_columns<2>(const pd::CrackObservables<2>&);
template std::vector<std::string> crack_columns<3>(const pd::CrackObservables<3>&);
template void crack_values<1>(const pd::CrackObservables<1>&, std::vector<double>&);
template void crack_values<2>(const pd::CrackObservables<2>&, std::vector<double>&);
template void crack_values<3>(const pd::CrackObservables<3>&, std::vector<double>&);
template nlohmann::json crack_summary<1>(const pd::CrackObservables<1>&, const pd::System<1>&);
template nlohmann::json crack_summary<2>(const pd::CrackObservables<2>&, const pd::System<2>&);
template nlohmann::json crack_summary<3>(const pd::CrackObservables<3>&, const pd::System<3>&);

}  // namespace pdmpm::sim
