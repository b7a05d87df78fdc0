#include "solver/time/stable_step.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>

#include "solver/core/error.hpp"

namespace pdmpm::time {

template <int D>
double silling_askari_step(const pd::System<D>& sys, const pd::Model<D>& model, double extra_row_sum) {
  double worst = 0.0;
  for (Index i = 0; i < sys.n_real(); ++i)
    if (sys.particles.kind[i] == core::ParticleKind::pd) worst = std::max(worst, model.stiffness_row_sum(sys, i));
  worst = sys.particles.max_everywhere(worst) + extra_row_sum;
  if (!(worst > 0.0)) return std::numeric_limits<double>::infinity();
  return std::sqrt(2.0 * sys.material.rho / worst);
}

template <int D>
LanczosResult lanczos_step(pd::System<D>& sys, pd::Model<D>& model, int max_iterations, double tolerance) {
  auto& p = sys.particles;
  const Index n = p.n_real;
  LanczosResult res;
  if (n == 0) return res;
  const auto u0 = p.u;
  const auto f_saved = p.f;
  const double rho = sys.material.rho;
  // Only PD particles move in the probe: the others (MPM, transition) are held,
  // as the grid, not PD, integrates them.
  auto is_pd = [&](Index i) { return p.kind[i] == core::ParticleKind::pd; };

  // The probing evaluations ask for no bond breaking, so the bond state is untouched.
  model.compute_forces(sys, {});
  const std::vector<Vec<D>> f0 = p.f;
  // A x = M⁻¹K x from a force evaluation at a small displacement along x
  // (strain ~1e-7: linear regime). A is self-adjoint in ⟨x, y⟩ = Σ V_i x_i·y_i.
  // Dot products and the scale span every process of a distributed run, in the
  // global order, so each process finds the one-process λ_max to the bit.
  const double amplitude = 1e-7 * sys.spacing();
  auto dot = [&](const std::vector<Vec<D>>& a, const std::vector<Vec<D>>& b) {
    return p.template sum_in_order<1>([&](double* s) {
      for (Index i = 0; i < n; ++i) s[0] += p.volume[i] * a[i].dot(b[i]);
    })[0];
  };
  auto apply = [&](const std::vector<Vec<D>>& x, std::vector<Vec<D>>& y) {
    double scale = 0.0;
    for (const auto& xi : x) scale = std::max(scale, xi.cwiseAbs().maxCoeff());
    scale = p.max_everywhere(scale);
    for (Index i = 0; i < n; ++i) p.u[i] = u0[i] + (amplitude / scale) * x[i];
    p.update_ghosts();
    model.compute_forces(sys, {});
    for (Index i = 0; i < n; ++i)
      y[i] = is_pd(i) ? Vec<D>(-(p.f[i] - f0[i]) * (scale / amplitude) / rho) : Vec<D>::Zero();
  };

  // Start from the checkerboard (the highest lattice frequency) plus a small
  // irregular part so the start is not orthogonal to the top mode.
  std::vector<Vec<D>> v(n), v_prev(n, Vec<D>::Zero()), w(n);
  for (Index i = 0; i < n; ++i) {
    const int parity = p.site[i].sum() & 1;
    const auto g = static_cast<double>(p.global_index(i));
    for (int a = 0; a < D; ++a)
      v[i][a] = is_pd(i) ? (parity ? 1.0 : -1.0) * (1.0 + 0.1 * a) + 0.01 * std::sin(0.37 * g + a) : 0.0;
  }
  double norm = std::sqrt(dot(v, v));
  for (auto& x : v) x /= norm;

  std::vector<double> alpha, beta;
  double lambda = 0.0, lambda_10_ago = 0.0;
  double beta_j = 0.0;
  for (int j = 1; j <= max_iterations; ++j) {
    apply(v, w);
    for (Index i = 0; i < n; ++i) w[i] -= beta_j * v_prev[i];
    const double a = dot(w, v);
    for (Index i = 0; i < n; ++i) w[i] -= a * v[i];
    alpha.push_back(a);
    // Largest Ritz value of the tridiagonal T_j.
    Eigen::MatrixXd T = Eigen::MatrixXd::Zero(j, j);
    for (int k = 0; k < j; ++k) {
      T(k, k) = alpha[k];
      if (k + 1 < j) T(k, k + 1) = T(k + 1, k) = beta[k];
    }
    lambda = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(T, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
    res.iterations = j;
    if (j % 10 == 0) {
      res.relative_change = std::abs(lambda - lambda_10_ago) / std::abs(lambda);
      if (res.relative_change < tolerance) break;
      lambda_10_ago = lambda;
    }
    beta_j = std::sqrt(dot(w, w));
    if (!(beta_j > 1e-14 * std::abs(lambda))) break;  // invariant subspace: T_j is exact
    beta.push_back(beta_j);
    v_prev.swap(v);
    for (Index i = 0; i < n; ++i) v[i] = w[i] / beta_j;
  }
  p.u = u0;
  p.update_ghosts();
  p.f = f_saved;
  if (!(lambda > 0.0) || !std::isfinite(lambda))
    throw RunError("stable step: the Lanczos iteration found no positive stiffness");
  res.lambda_max = lambda;
  res.dt = 2.0 / std::sqrt(lambda);
  return res;
}

template double silling_askari_step<1>(const pd::System<1>&, const pd::Model<1>&, double);
template double silling_askari_step<2>(const pd::System<2>&, const pd::Model<2>&, double);
template double silling_askari_step<3>(const pd::System<3>&, const pd::Model<3>&, double);
template LanczosResult lanczos_step<1>(pd::System<1>&, pd::Model<1>&, int, double);
template LanczosResult lanczos_step<2>(pd::System<2>&, pd::Model<2>&, int, double);
template LanczosResult lanczos_step<3>(pd::System<3>&, pd::Model<3>&, int, double);

}  // namespace pdmpm::time
