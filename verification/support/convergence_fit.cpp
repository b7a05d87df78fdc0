#include "verification/support/convergence_fit.hpp"

#include <cmath>

namespace pdmpm::test {

double fitted_order(const std::vector<double>& h, const std::vector<double>& err) {
  const double n = static_cast<double>(h.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    const double x = std::log(h[i]), y = std::log(err[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

PowerFit fit_power(const std::vector<double>& x, const std::vector<double>& y, double p_min, double p_max, double step) {
  PowerFit best;
  double best_sq = 1e300;
  const long steps = p_max > p_min ? std::lround((p_max - p_min) / step) : 0;
  for (long k = 0; k <= steps; ++k) {
    const double p = p_min + static_cast<double>(k) * step;
    double s1 = 0, sx = 0, sxx = 0, sy = 0, sxy = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double xp = std::pow(x[i], p);
      s1 += 1, sx += xp, sxx += xp * xp, sy += y[i], sxy += xp * y[i];
    }
    const double C = (s1 * sxy - sx * sy) / (s1 * sxx - sx * sx), L = (sy - C * sx) / s1;
    double sq = 0;
    for (std::size_t i = 0; i < x.size(); ++i) sq += std::pow(L + C * std::pow(x[i], p) - y[i], 2);
    if (sq < best_sq) best_sq = sq, best = {L, C, p, 0.0};
  }
  best.residual = std::sqrt(best_sq / static_cast<double>(x.size()));
  return best;
}

}  // namespace pdmpm::test
