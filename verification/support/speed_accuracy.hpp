#pragma once
// Speed against accuracy (issue 6 item 5): runs as (wall time, error) points,
// the Pareto front among them, and the report plot that shows both.
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace pdmpm::test {

struct SpeedAccuracyPoint {
  std::string series;  // legend entry the point is drawn under (e.g. the influence function)
  double seconds = 0.0;
  double error = 0.0;
};

// Indices of the points no other point beats in both time and error, fastest first.
std::vector<std::size_t> pareto_front(const std::vector<SpeedAccuracyPoint>& points);

// A log–log plot (report "plot" record): one point series per `series` name and
// the front as a dashed line.
nlohmann::json speed_accuracy_plot(const std::vector<SpeedAccuracyPoint>& points, const std::string& title,
                                   const std::string& xlabel, const std::string& ylabel, const std::string& caption);

}  // namespace pdmpm::test
