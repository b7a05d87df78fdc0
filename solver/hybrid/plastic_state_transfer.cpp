#include "solver/hybrid/plastic_state_transfer.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "solver/pd/bond_kinematics.hpp"

namespace pdmpm::hybrid {

namespace {

// The deviatoric basis the fit solves for, as 3×3 tensors: 2D, the in-plane deviator
// (diag(1, −1, 0), sym e₁⊗e₂); 3D, the five traceless symmetric directions.
template <int D>
std::vector<Mat<3>> deviatoric_basis() {
  std::vector<Mat<3>> b;
  auto sym = [](int i, int j) {
    Mat<3> m = Mat<3>::Zero();
    m(i, j) = m(j, i) = i == j ? 1.0 : 0.5;
    return m;
  };
  if constexpr (D == 2) {
    Mat<3> d = Mat<3>::Zero();
    d(0, 0) = 1.0;
    d(1, 1) = -1.0;
    b = {d, 2.0 * sym(0, 1)};
  } else {
    Mat<3> d1 = Mat<3>::Zero(), d2 = Mat<3>::Zero();
    d1(0, 0) = 1.0;
    d1(1, 1) = -1.0;
    d2(1, 1) = 1.0;
    d2(2, 2) = -1.0;
    b = {d1, d2, 2.0 * sym(0, 1), 2.0 * sym(1, 2), 2.0 * sym(0, 2)};
  }
  return b;
}

}  // namespace

template <int D>
double bond_plastic_extension(const Mat<3>& eps_p, const Vec<D>& xi) {
  const double L = xi.norm();
  Mat<D> e = eps_p.template topLeftCorner<D, D>();
  if constexpr (D == 2) e -= 0.5 * e.trace() * Mat<D>::Identity();  // the bonds see the in-plane deviator
  return xi.dot(e * xi) / L;
}

double axial_plastic_strain(const Mat<3>& eps_p) { return (eps_p(0, 0) + eps_p(1, 1) - 2.0 * eps_p(2, 2)) / 6.0; }

namespace {

// The deviator whose bond extensions fit `values` best with weights w (normal equations
// over the deviatoric basis), and the share of Σ w v² the fit leaves. Empty when the bonds
// do not determine the deviator.
template <int D>
std::optional<std::pair<Mat<3>, double>> fit_deviator(const std::vector<Vec<D>>& xi, const std::vector<double>& w,
                                                      const std::vector<double>& values) {
  const std::vector<Mat<3>> basis = deviatoric_basis<D>();
  const int n = static_cast<int>(basis.size());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  double scale = 0.0;  // for the rank test: Σ w |ξ|² (the entries' size)
  double total = 0.0;  // Σ w v²
  for (std::size_t k = 0; k < xi.size(); ++k) {
    Eigen::VectorXd g(n);
    for (int a = 0; a < n; ++a) g[a] = bond_plastic_extension<D>(basis[a], xi[k]);
    A += w[k] * g * g.transpose();
    rhs += w[k] * values[k] * g;
    scale += w[k] * xi[k].squaredNorm();
    total += w[k] * values[k] * values[k];
  }
  // Rank: the smallest eigenvalue of the normal matrix against its scale; 1e-10 is far
  // above round-off (1e-16 relative) and far below any set of two non-parallel bonds
  // (a 45° pair gives ~0.1 of the scale).
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A);
  if (!(scale > 0.0) || eig.eigenvalues().minCoeff() <= 1e-10 * scale) return std::nullopt;
  const Eigen::VectorXd c = A.ldlt().solve(rhs);
  Mat<3> dev = Mat<3>::Zero();
  for (int a = 0; a < n; ++a) dev += c[a] * basis[a];
  // Least squares: Σ w (v − g·c)² = Σ w v² − c·rhs.
  const double left = total > 0.0 ? std::clamp((total - c.dot(rhs)) / total, 0.0, 1.0) : 0.0;
  return std::pair{dev, left};
}

}  // namespace

template <int D>
std::optional<Mat<3>> fit_plastic_strain(const std::vector<Vec<D>>& xi, const std::vector<double>& w,
                                         const std::vector<double>& p, double q_p) {
  const auto fit = fit_deviator<D>(xi, w, p);
  if (!fit) return std::nullopt;
  Mat<3> eps = fit->first;
  if constexpr (D == 2) {
    // The in-plane trace and ε_zz from q_p = ½ tr ε_p,2 and tr ε_p = 0.
    eps(0, 0) += q_p;
    eps(1, 1) += q_p;
    eps(2, 2) = -2.0 * q_p;
  }
  return eps;
}

template <int D>
void carry_plastic_state_into_pd(const pd::System<D>& sys, pd::LpsPlastic<D>& model, Index i,
                                 const mpm::PointHistory& history) {
  for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b)
    model.set_plastic_extension(b,
                                bond_plastic_extension<D>(history.plastic_strain, sys.table.xi[sys.families.shape[b]]));
  model.set_particle_plastic_state(i, D == 2 ? axial_plastic_strain(history.plastic_strain) : 0.0,
                                   history.eq_plastic_strain);
}

namespace {

// e − γθ_c|ξ| of the bond i → j of stencil offset k at the current displacements: the
// deviatoric extension lps_plastic's force state forms (e without cancellation, as its kernels).
template <int D>
double deviatoric_extension(const pd::System<D>& sys, double gamma_theta_c, Index i, Index j, int k) {
  const auto& t = sys.table;
  const auto& p = sys.particles;
  return pd::deform<D>(t.xi[k], t.length[k], p.u[j] - p.u[i]).e - gamma_theta_c * t.length[k];
}

}  // namespace

template <int D>
void carry_elastic_state_into_pd(const pd::System<D>& sys, pd::LpsPlastic<D>& model, Index i, const Mat<3>& eps_e,
                                 double eq_plastic) {
  const auto [theta, theta_c] = model.current_dilatations(sys, i);
  // The bonds see the deviator (bond_plastic_extension takes the in-plane one itself in 2D).
  const Mat<3> dev = D == 3 ? Mat<3>(eps_e - eps_e.trace() / 3.0 * Mat<3>::Identity()) : eps_e;
  for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b) {
    const int k = sys.families.shape[b];
    model.set_plastic_extension(
        b,
        deviatoric_extension<D>(sys, model.split_factor() * theta_c, i, sys.families.neighbor[b], k) -
            bond_plastic_extension<D>(dev, sys.table.xi[k]));
  }
  const double q_e = (eps_e(0, 0) + eps_e(1, 1) - 2.0 * eps_e(2, 2)) / 6.0;
  model.set_particle_plastic_state(i, model.axial_plastic_for(theta, q_e), eq_plastic);
}

namespace {

// The deviatoric elastic extensions e − γθ_c|ξ| − p of particle i's live bonds, with their
// reference vectors and weights ω V.
template <int D>
void live_elastic_extensions(const pd::System<D>& sys, const pd::LpsPlastic<D>& model, Index i, double theta_c,
                             std::vector<Vec<D>>& xi, std::vector<double>& w, std::vector<double>& elastic) {
  sys.for_each_live_bond(i, [&](BondIndex b, Index j, int k) {
    xi.push_back(sys.table.xi[k]);
    w.push_back(sys.table.weight[k] * sys.particles.volume[j]);
    elastic.push_back(deviatoric_extension<D>(sys, model.split_factor() * theta_c, i, j, k) -
                      model.plastic_extension(b));
  });
}

}  // namespace

template <int D>
std::optional<Mat<3>> elastic_strain_from_pd(const pd::System<D>& sys, const pd::LpsPlastic<D>& model, Index i) {
  const auto [theta, theta_c] = model.current_dilatations(sys, i);
  std::vector<Vec<D>> xi;
  std::vector<double> w, elastic;
  live_elastic_extensions<D>(sys, model, i, theta_c, xi, w, elastic);
  const double q_e = model.axial_elastic_for(theta, model.axial_plastic_strain(i));
  const std::optional<Mat<3>> dev = fit_plastic_strain<D>(xi, w, elastic, q_e);
  if (!dev) return std::nullopt;
  return Mat<3>(*dev + model.volumetric_elastic_for(theta, q_e) / 3.0 * Mat<3>::Identity());
}

template <int D>
double non_affine_share(const pd::System<D>& sys, const pd::LpsPlastic<D>& model, Index i) {
  const double theta_c = model.current_dilatations(sys, i).second;
  std::vector<Vec<D>> xi;
  std::vector<double> w, elastic;
  live_elastic_extensions<D>(sys, model, i, theta_c, xi, w, elastic);
  const auto fit = fit_deviator<D>(xi, w, elastic);
  return fit ? fit->second : 1.0;
}

template <int D>
std::optional<mpm::PointHistory> plastic_state_from_pd(const pd::System<D>& sys, const pd::LpsPlastic<D>& model,
                                                       Index i) {
  std::vector<Vec<D>> xi;
  std::vector<double> w, p;
  sys.for_each_live_bond(i, [&](BondIndex b, Index j, int k) {
    xi.push_back(sys.table.xi[k]);
    w.push_back(sys.table.weight[k] * sys.particles.volume[j]);
    p.push_back(model.plastic_extension(b));
  });
  const std::optional<Mat<3>> eps = fit_plastic_strain<D>(xi, w, p, model.axial_plastic_strain(i));
  if (!eps) return std::nullopt;
  mpm::PointHistory h;
  h.plastic_strain = *eps;
  h.eq_plastic_strain = model.committed_eq_plastic_strain(i);
  return h;
}

template void carry_plastic_state_into_pd<2>(const pd::System<2>&, pd::LpsPlastic<2>&, Index, const mpm::PointHistory&);
template void carry_plastic_state_into_pd<3>(const pd::System<3>&, pd::LpsPlastic<3>&, Index, const mpm::PointHistory&);
template void carry_elastic_state_into_pd<2>(const pd::System<2>&, pd::LpsPlastic<2>&, Index, const Mat<3>&, double);
template void carry_elastic_state_into_pd<3>(const pd::System<3>&, pd::LpsPlastic<3>&, Index, const Mat<3>&, double);
template std::optional<Mat<3>> elastic_strain_from_pd<2>(const pd::System<2>&, const pd::LpsPlastic<2>&, Index);
template std::optional<Mat<3>> elastic_strain_from_pd<3>(const pd::System<3>&, const pd::LpsPlastic<3>&, Index);
template double non_affine_share<2>(const pd::System<2>&, const pd::LpsPlastic<2>&, Index);
template double non_affine_share<3>(const pd::System<3>&, const pd::LpsPlastic<3>&, Index);
template std::optional<mpm::PointHistory> plastic_state_from_pd<2>(const pd::System<2>&, const pd::LpsPlastic<2>&,
                                                                   Index);
template std::optional<mpm::PointHistory> plastic_state_from_pd<3>(const pd::System<3>&, const pd::LpsPlastic<3>&,
                                                                   Index);
template double bond_plastic_extension<2>(const Mat<3>&, const Vec<2>&);
template double bond_plastic_extension<3>(const Mat<3>&, const Vec<3>&);
template std::optional<Mat<3>> fit_plastic_strain<2>(const std::vector<Vec<2>>&, const std::vector<double>&,
                                                     const std::vector<double>&, double);
template std::optional<Mat<3>> fit_plastic_strain<3>(const std::vector<Vec<3>>&, const std::vector<double>&,
                                                     const std::vector<double>&, double);

}  // namespace pdmpm::hybrid
