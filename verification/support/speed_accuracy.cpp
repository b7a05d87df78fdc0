#include "verification/support/speed_accuracy.hpp"

#include <algorithm>
#include <map>
#include <numeric>

namespace pdmpm::test {

std::vector<std::size_t> pareto_front(const std::vector<SpeedAccuracyPoint>& points) {
  std::vector<std::size_t> order(points.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return points[a].seconds < points[b].seconds ||
           (points[a].seconds == points[b].seconds && points[a].error < points[b].error);
  });
  std::vector<std::size_t> front;
  for (std::size_t k : order)  // sweeping by time: a point is on the front if it beats every faster one
    if (front.empty() || points[k].error < points[front.back()].error) front.push_back(k);
  return front;
}

nlohmann::json speed_accuracy_plot(const std::vector<SpeedAccuracyPoint>& points, const std::string& title,
                                   const std::string& xlabel, const std::string& ylabel, const std::string& caption) {
  std::map<std::string, std::pair<std::vector<double>, std::vector<double>>> by_series;
  for (const auto& p : points) {
    by_series[p.series].first.push_back(p.seconds);
    by_series[p.series].second.push_back(p.error);
  }
  nlohmann::json series = nlohmann::json::array();
  for (const auto& [label, xy] : by_series)
    series.push_back({{"label", label}, {"x", xy.first}, {"y", xy.second}, {"style", "points"}});
  std::vector<double> fx, fy;
  for (std::size_t k : pareto_front(points)) fx.push_back(points[k].seconds), fy.push_back(points[k].error);
  series.push_back({{"label", "Pareto front"}, {"x", fx}, {"y", fy}, {"style", "dashed"}});
  return {{"kind", "plot"}, {"title", title},   {"xlabel", xlabel},  {"ylabel", ylabel},
          {"xscale", "log"}, {"yscale", "log"}, {"series", series}, {"caption", caption}};
}

}  // namespace pdmpm::test
