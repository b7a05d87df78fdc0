#include "solver/core/j_integral.hpp"

#include <cmath>
#include <stdexcept>

namespace pdmpm::core {

JResult domain_j_integral(const std::vector<JSample>& samples, const JDomain& d) {
  if (!(d.r_inner >= 0.0 && d.r_outer > d.r_inner))
    throw std::invalid_argument("J-integral ring: need 0 ≤ r_inner < r_outer");
  if (!(std::abs(d.direction.norm() - 1.0) < 1e-12))
    throw std::invalid_argument("J-integral: direction must be a unit vector");
  if (!(d.thickness > 0.0)) throw std::invalid_argument("J-integral: thickness must be > 0");
  JResult out;
  const double width = d.r_outer - d.r_inner;
  for (const JSample& s : samples) {
    const Vec<2> rel = s.X - d.tip;
    const double r = rel.norm();
    if (!(r > d.r_inner && r < d.r_outer)) continue;
    const Vec<2> grad_q = -rel / (r * width);
    // (P_ij ∂u_i/∂X_k a_k − W a_j) ∂q/∂X_j
    const Vec<2> du_da = s.grad_u * d.direction;
    const Vec<2> flux = s.stress.transpose() * du_da - s.energy * d.direction;
    out.J += s.volume * flux.dot(grad_q);
    ++out.particles;
  }
  out.J /= d.thickness;
  return out;
}

}  // namespace pdmpm::core
