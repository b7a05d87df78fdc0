#include "solver/time/stable_step.hpp"

#include <cmath>
#include <limits>

#include "solver/core/error.hpp"

namespace pdmpm::time {

template <int D>
double silling_askari_step(const pd::System<D>& sys, const pd::Model<D>& model, double extra_row_sum) {
  double worst = 0.0;
  for (Index i = 0; i < sys.n_real(); ++i) worst = std::max(worst, model.stiffness_row_sum(sys, i));
  worst += extra_row_sum;
  if (!(worst > 0.0)) return std::numeric_limits<double>::infinity();
  return std::sqrt(2.0 * sys.material.rho / worst);
}

template <int D>
PowerIterationResult power_iteration_step(pd::System<D>& sys, pd::Model<D>& model, int max_iterations,
                                          double tolerance) {
  auto& p = sys.particles;
  const Index n = p.n_real;
  PowerIterationResult res;
  if (n == 0) return res;
  const auto u0 = p.u;
  const auto f0_saved = p.f;
  const auto broken0 = sys.broken;

  // Reference force at the current state, so any pre-stress cancels.
  model.compute_forces(sys, {});
  const std::vector<Vec<D>> f0 = p.f;

  // Start from the checkerboard (highest lattice frequency) with a small
  // smooth perturbation so the start is not orthogonal to the top mode.
  std::vector<Vec<D>> x(n);
  for (Index i = 0; i < n; ++i) {
    const int parity = p.site[i].sum() & 1;
    for (int a = 0; a < D; ++a) x[i][a] = (parity ? 1.0 : -1.0) * (1.0 + 0.1 * a) + 0.01 * std::sin(0.37 * i + a);
  }
  const double amplitude = 1e-7 * sys.spacing();  // linear regime: strain ~1e-7
  double lambda = 0.0;
  for (int it = 1; it <= max_iterations; ++it) {
    double norm = 0.0;
    for (const auto& xi : x) norm += xi.squaredNorm();
    norm = std::sqrt(norm);
    for (Index i = 0; i < n; ++i) p.u[i] = u0[i] + (amplitude / norm) * x[i];
    p.update_ghosts();
    model.compute_forces(sys, {});
    // y = ρ⁻¹ K x  with K x = −(f(u0 + a x̂) − f(u0)) / a · |x|
    double num = 0.0, den = 0.0;
    for (Index i = 0; i < n; ++i) {
      const Vec<D> y = -(p.f[i] - f0[i]) * (norm / amplitude) / sys.material.rho;
      num += x[i].dot(y);
      den += x[i].squaredNorm();
      x[i] = y;
    }
    const double next = num / den;
    res.relative_change = std::abs(next - lambda) / std::abs(next);
    lambda = next;
    res.iterations = it;
    if (it > 5 && res.relative_change < tolerance) break;
  }
  p.u = u0;
  p.update_ghosts();
  p.f = f0_saved;
  sys.broken = broken0;
  if (!(lambda > 0.0) || !std::isfinite(lambda)) throw RunError("stable step: power iteration found no positive stiffness");
  res.lambda_max = lambda;
  res.dt = 2.0 / std::sqrt(lambda);
  return res;
}

template double silling_askari_step<1>(const pd::System<1>&, const pd::Model<1>&, double);
template double silling_askari_step<2>(const pd::System<2>&, const pd::Model<2>&, double);
template double silling_askari_step<3>(const pd::System<3>&, const pd::Model<3>&, double);
template PowerIterationResult power_iteration_step<1>(pd::System<1>&, pd::Model<1>&, int, double);
template PowerIterationResult power_iteration_step<2>(pd::System<2>&, pd::Model<2>&, int, double);
template PowerIterationResult power_iteration_step<3>(pd::System<3>&, pd::Model<3>&, int, double);

}  // namespace pdmpm::time
