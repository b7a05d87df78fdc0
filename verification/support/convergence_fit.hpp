#pragma once
// Fits for convergence studies: the observed order of an error sequence
// (least-squares slope in log–log) and the limit of a sequence y = y∞ + C x^p.
#include <vector>

namespace pdmpm::test {

// Least-squares slope of log(err) against log(h): the observed order.
double fitted_order(const std::vector<double>& h, const std::vector<double>& err);

// y ≈ limit + coefficient · x^order, least squares: linear in (limit, coefficient)
// for each order on the grid p_min, p_min + step, … ≤ p_max (one order when
// p_min == p_max), the order with the smallest residual kept.
struct PowerFit {
  double limit = 0.0, coefficient = 0.0, order = 0.0;
  double residual = 0.0;  // root mean square of the fit's misses
};
PowerFit fit_power(const std::vector<double>& x, const std::vector<double>& y, double p_min, double p_max, double step = 0.005);

}  // namespace pdmpm::test
