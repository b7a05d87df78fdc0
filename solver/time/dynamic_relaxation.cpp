#include "solver/time/dynamic_relaxation.hpp"

#include <algorithm>
#include <cmath>

namespace pdmpm::time {

template <int D>
DynamicRelaxation<D>::DynamicRelaxation(pd::Simulation<D>& sim) : sim_(sim) {
  const auto& sys = sim_.system();
  const Index n = sys.particles.n_real;
  const auto* contact_model = sim_.forcing().contact;
  const double contact = contact_model ? contact_model->stiffness_row_sum(sys) : 0.0;
  lambda_.resize(n);
  // λ_i ≥ ¼ Σ_j |K_ij| (Δt = 1); the row sum bounds Σ_j |K_ij| / 2, and 0.625 = ¼·2·1.25 adds a margin.
  for (Index i : sim_.movers()) lambda_[i] = 0.625 * (sim_.model().stiffness_row_sum(sys, i) + contact) + 1e-300;
  vhalf_.assign(n, Vec<D>::Zero());
  fprev_.assign(n, Vec<D>::Zero());
}

template <int D>
RelaxationResult DynamicRelaxation<D>::solve(double t, double tolerance, std::int64_t max_iterations) {
  auto& p = sim_.particles();
  const auto& bcs = sim_.boundaries();
  const auto& mask = bcs.mask();
  RelaxationResult res;
  for (auto& v : vhalf_) v.setZero();
  for (std::int64_t it = 0; it < max_iterations; ++it) {
    bcs.apply_displacement(p, t, 0.0);
    p.update_ghosts();
    sim_.forces(t, false);
    sim_.accept();
    // The residual and the damping's Rayleigh quotient, over the whole body in its global
    // particle order (a distributed run's sums are the one-process sums).
    const auto [r2, scale2, num, den] = p.template sum_in_order<4>([&](double* sum) {
      double &r2_sum = sum[0], &scale2_sum = sum[1], &num_sum = sum[2], &den_sum = sum[3];
      for (Index i : sim_.movers())
        for (int a = 0; a < D; ++a) {
          const double F = p.f[i][a] + p.b[i][a], V = p.volume[i];
          if (mask[static_cast<std::size_t>(i) * D + a]) {
            scale2_sum += V * V * F * F;  // support reactions set the scale of displacement-driven problems
            continue;
          }
          r2_sum += V * V * F * F;
          scale2_sum += V * V * p.b[i][a] * p.b[i][a];
          if (it > 0 && vhalf_[i][a] != 0.0)
            num_sum += p.u[i][a] * (-(F - fprev_[i][a]) / (lambda_[i] * vhalf_[i][a])) * p.u[i][a];
          den_sum += p.u[i][a] * p.u[i][a];
        }
    });
    res.iterations = it;
    res.residual = scale2 > 0.0 ? std::sqrt(r2 / scale2) : std::sqrt(r2);
    if (it > 0 && (res.residual < tolerance || r2 == 0.0)) {
      res.converged = true;
      break;
    }
    const double c = (it > 0 && num > 0.0 && den > 0.0) ? std::min(2.0 * std::sqrt(num / den), 1.999) : 0.0;
    for (Index i : sim_.movers())
      for (int a = 0; a < D; ++a) {
        if (mask[static_cast<std::size_t>(i) * D + a]) continue;
        const double F = p.f[i][a] + p.b[i][a];
        vhalf_[i][a] = it == 0 ? 0.5 * F / lambda_[i] : ((2.0 - c) * vhalf_[i][a] + 2.0 * F / lambda_[i]) / (2.0 + c);
        fprev_[i][a] = F;
        p.u[i][a] += vhalf_[i][a];
      }
    if (!std::isfinite(res.residual)) break;
  }
  for (Index i : sim_.movers()) p.v[i].setZero();
  sim_.internal_forces(true);
  sim_.accept();
  return res;
}

template class DynamicRelaxation<1>;
template class DynamicRelaxation<2>;
template class DynamicRelaxation<3>;

}  // namespace pdmpm::time
