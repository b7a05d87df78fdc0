#include "solver/analytic/kirsch.hpp"

#include <cmath>
#include <stdexcept>

namespace pdmpm::analytic {

std::array<double, 3> Kirsch::polar(double r, double theta) const {
  const double q = (radius * radius) / (r * r), q2 = q * q, h = 0.5 * stress;
  const double c2 = std::cos(2.0 * theta), s2 = std::sin(2.0 * theta);
  return {h * (1.0 - q) + h * (1.0 - 4.0 * q + 3.0 * q2) * c2,  //
          h * (1.0 + q) - h * (1.0 + 3.0 * q2) * c2,            //
          -h * (1.0 + 2.0 * q - 3.0 * q2) * s2};
}

std::array<double, 3> Kirsch::cartesian(double x, double y) const {
  // Load-axis frame: X along y, Y = −x, so θ = atan2(Y, X) is measured from y.
  const double X = y, Y = -x;
  const double r = std::hypot(X, Y), th = std::atan2(Y, X);
  const auto [srr, stt, srt] = polar(r, th);
  const double c = std::cos(th), s = std::sin(th);
  const double sXX = srr * c * c + stt * s * s - 2.0 * srt * s * c;
  const double sYY = srr * s * s + stt * c * c + 2.0 * srt * s * c;
  const double sXY = (srr - stt) * s * c + srt * (c * c - s * s);
  // Back to (x, y): σ_yy = σ_XX, σ_xx = σ_YY, σ_xy = −σ_XY.
  return {sYY, sXX, -sXY};
}

double finite_width_kt(double d_over_w, WidthCorrection fit) {
  const double x = d_over_w;
  if (!(x >= 0.0 && x < 1.0)) throw std::invalid_argument("finite_width_kt: d/W must lie in [0, 1)");
  const double net = fit == WidthCorrection::heywood ? 2.0 + std::pow(1.0 - x, 3)
                                                     : 3.0 - 3.13 * x + 3.66 * x * x - 1.53 * x * x * x;
  return net / (1.0 - x);
}

}  // namespace pdmpm::analytic
