#include "verification/support/patch_check.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "solver/core/particle_builder.hpp"
#include "solver/pd/constants.hpp"

namespace pdmpm::test {

double interior_margin(const std::string& model, double delta) {
  return (pd::model_info(model).state_based ? 2.0 : 1.0) * delta;
}

double default_measure(core::Setting s) {
  switch (s) {
    case core::Setting::bar1d:
      return 1e-6;
    case core::Setting::plane_stress:
    case core::Setting::plane_strain:
      return 1e-3;
    case core::Setting::solid3d:
      return 1.0;
  }
  return 1.0;
}

double classical_energy(const Eigen::Matrix3d& eps, int dim, core::Setting s, const core::Elastic& m) {
  const Eigen::MatrixXd e = eps.topLeftCorner(dim, dim);
  if (s == core::Setting::bar1d) return 0.5 * m.E * e(0, 0) * e(0, 0);
  const double G = m.shear();
  // Plane stress eliminates ε_zz: λ* = 2Gν/(1−ν) = Eν/(1−ν²).
  const double lambda = s == core::Setting::plane_stress ? m.E * m.nu / (1.0 - m.nu * m.nu) : m.lame();
  const double tr = e.trace();
  return 0.5 * lambda * tr * tr + G * e.cwiseProduct(e).sum();
}

namespace {

template <int D>
pd::System<D> make_body(const PatchConfig& cfg, Index sites) {
  core::Lattice<D> lat;
  lat.spacing = cfg.spacing;
  core::Geometry<D> g;
  const double half = 0.5 * (sites - 1) * cfg.spacing;
  if (cfg.ball)
    g.add(std::make_unique<core::Ball<D>>(Vec<D>::Constant(half), half));
  else
    g.add(std::make_unique<core::Box<D>>(Vec<D>::Zero(), Vec<D>::Constant(2.0 * half)));
  const double measure = default_measure(cfg.setting);
  pd::System<D> sys;
  sys.particles = core::fill_lattice<D>(g, lat, std::pow(cfg.spacing, D) * (D == 3 ? 1.0 : measure));
  sys.setting = cfg.setting;
  sys.material = cfg.material;
  sys.delta = cfg.horizon_ratio * cfg.spacing;
  sys.measure = D == 3 ? 1.0 : measure;
  sys.influence = cfg.influence;
  sys.partial_volume = cfg.partial_volume;
  sys.connect();
  return sys;
}

// Orthonormal basis (Frobenius) of the symmetric traceless D×D tensors.
template <int D>
std::vector<Mat<D>> deviatoric_basis() {
  std::vector<Mat<D>> b;
  auto sym = [](int a, int c) {
    Mat<D> m = Mat<D>::Zero();
    m(a, c) = m(c, a) = 1.0 / std::sqrt(2.0);
    return m;
  };
  if constexpr (D >= 2) {
    Mat<D> m = Mat<D>::Zero();
    m(0, 0) = 1.0 / std::sqrt(2.0), m(1, 1) = -1.0 / std::sqrt(2.0);
    b.push_back(m);
    b.push_back(sym(0, 1));
  }
  if constexpr (D == 3) {
    Mat<D> m = Mat<D>::Zero();
    m(0, 0) = m(1, 1) = 1.0 / std::sqrt(6.0), m(2, 2) = -2.0 / std::sqrt(6.0);
    b.push_back(m);
    b.push_back(sym(0, 2));
    b.push_back(sym(1, 2));
  }
  return b;
}

}  // namespace

template <int D>
PatchBlock<D>::PatchBlock(const PatchConfig& cfg) : cfg_(cfg) {
  const double margin = interior_margin(cfg.model, cfg.horizon_ratio * cfg.spacing);
  const Index n_margin = static_cast<Index>(std::floor(margin / cfg.spacing)) + 1;
  // Cube: 2 interior sites per axis. Ball: the centre site, n_margin + 1 sites from the surface.
  sites_ = cfg.ball ? 2 * (n_margin + 1) + 1 : 2 * n_margin + 2;
  sys_ = make_body<D>(cfg, sites_);
  model_ = pd::make_model<D>(cfg.model);
  model_->initialise(sys_);
  const auto& x0 = sys_.particles.x0;
  const double half = 0.5 * (sites_ - 1) * cfg.spacing;
  for (Index i = 0; i < sys_.n_real(); ++i) {
    double dist;
    if (cfg.ball) {
      dist = half - (x0[i] - Vec<D>::Constant(half)).norm();
    } else {
      dist = std::numeric_limits<double>::max();
      for (int a = 0; a < D; ++a) dist = std::min({dist, x0[i][a], 2.0 * half - x0[i][a]});
    }
    if (dist > margin * (1.0 + 1e-12)) interior_.push_back(i);
  }
}

template <int D>
void PatchBlock<D>::evaluate(const Eigen::Matrix3d& H, std::vector<double>& W, std::vector<double>& theta) {
  auto& p = sys_.particles;
  const Mat<D> h = H.topLeftCorner<D, D>();
  for (Index i = 0; i < p.size(); ++i) p.u[i] = h * p.x0[i];
  W.assign(sys_.n_real(), 0.0);
  pd::ForceRequest req;
  req.energy = &W;
  model_->compute_forces(sys_, req);
  model_->dilatation(sys_, theta);
}

template <int D>
double PatchBlock<D>::lattice_energy(Index i, const Eigen::Matrix3d& eps3) const {
  const Mat<D> eps = eps3.topLeftCorner<D, D>();
  const auto& fam = sys_.families;
  const auto& t = sys_.table;
  const auto& vol = sys_.particles.volume;
  if (cfg_.model == "pmb") {
    // W = ¼ c Σ ω β |ξ| (n·ε·n)² V_j (linearised PMB energy of pmb.cpp).
    const double c = pd::pmb_micromodulus(sys_.influence, sys_.setting, sys_.material, sys_.delta, sys_.measure);
    double w = 0.0;
    for (BondIndex b = fam.begin(i); b < fam.end(i); ++b) {
      const int k = fam.shape[b];
      const Vec<D> n = t.xi[k] / t.length[k];
      const double s = n.dot(eps * n);
      w += 0.25 * c * t.weight[k] * t.length[k] * s * s * vol[fam.neighbor[b]];
    }
    return w;
  }
  if (cfg_.model == "lps") {
    // θ = (d/m) Σ ω β |ξ|² (n·ε·n) V, W = ½ κ θ² + (B/2m) Σ ω β |ξ|² (n·ε·n − γθ)² V.
    const auto k = pd::lps_coefficients(sys_.setting, sys_.material);
    double m = 0.0, sum = 0.0;
    for (BondIndex b = fam.begin(i); b < fam.end(i); ++b) {
      const int s = fam.shape[b];
      const Vec<D> n = t.xi[s] / t.length[s];
      const double wv = t.weight[s] * t.length[s] * t.length[s] * vol[fam.neighbor[b]];
      m += wv;
      sum += wv * n.dot(eps * n);
    }
    const double theta = k.d * sum / m;
    double dev = 0.0;
    for (BondIndex b = fam.begin(i); b < fam.end(i); ++b) {
      const int s = fam.shape[b];
      const Vec<D> n = t.xi[s] / t.length[s];
      const double ed = n.dot(eps * n) - k.gamma * theta;
      dev += t.weight[s] * t.length[s] * t.length[s] * vol[fam.neighbor[b]] * ed * ed;
    }
    return 0.5 * k.kappa * theta * theta + 0.5 * k.B * dev / m;
  }
  if (cfg_.model == "hpd") {
    // Every bond's fitted strain is ε (exact for affine fields) and the bond weights sum to 1:
    // W = ½ λ (tr ε)² + G ε:ε, with λ* = Eν/(1 − ν²) in plane stress (docs/models/hpd.md).
    const auto& m = sys_.material;
    const double lambda = sys_.setting == core::Setting::plane_stress ? m.E * m.nu / (1.0 - m.nu * m.nu)
        : D == 1                                                      ? 0.0
                                                                      : m.lame();
    const double G = D == 1 ? 0.5 * m.E : m.shear();  // a bar: W = ½ E ε²
    return 0.5 * lambda * eps.trace() * eps.trace() + G * (eps.array() * eps.array()).sum();
  }
  return not_measured;
}

template <int D>
double PatchBlock<D>::deviatoric_bound() const {
  if (cfg_.model != "lps" || interior_.empty()) return not_measured;
  if constexpr (D == 1) {
    return 0.0;  // a bar has no deviatoric strain
  } else {
    const Index i = interior_.front();
    const auto k = pd::lps_coefficients(sys_.setting, sys_.material);
    const double G = sys_.material.shear();
    const auto basis = deviatoric_basis<D>();
    const int nb = static_cast<int>(basis.size());
    // Q_pq = (B / 2G) Σ ω β |ξ|² V (n·E_p·n)(n·E_q·n) / m: W_lattice / (G ε:ε) on the basis.
    Eigen::MatrixXd Q = Eigen::MatrixXd::Zero(nb, nb);
    double m = 0.0;
    const auto& fam = sys_.families;
    const auto& t = sys_.table;
    for (BondIndex b = fam.begin(i); b < fam.end(i); ++b) {
      const int s = fam.shape[b];
      const Vec<D> n = t.xi[s] / t.length[s];
      const double wv = t.weight[s] * t.length[s] * t.length[s] * sys_.particles.volume[fam.neighbor[b]];
      m += wv;
      for (int p = 0; p < nb; ++p)
        for (int q = 0; q < nb; ++q) Q(p, q) += wv * n.dot(basis[p] * n) * n.dot(basis[q] * n);
    }
    Q *= k.B / (2.0 * G * m);
    const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Q).eigenvalues();
    return std::max(std::abs(ev.maxCoeff() - 1.0), std::abs(ev.minCoeff() - 1.0));
  }
}

template <int D>
PatchResult PatchBlock<D>::affine(const Eigen::Matrix3d& H, bool small) {
  PatchResult r;
  r.interior = static_cast<int>(interior_.size());
  const double hmax = H.topLeftCorner<D, D>().cwiseAbs().maxCoeff();
  r.force_scale = sys_.material.wave_modulus(sys_.setting) * hmax / sys_.spacing();
  std::vector<double> W, theta;
  evaluate(H, W, theta);
  const auto& f = sys_.particles.f;
  for (Index i = 0; i < sys_.n_real(); ++i) r.largest_force = std::max(r.largest_force, f[i].norm());
  for (Index i : interior_) r.interior_force = std::max(r.interior_force, f[i].norm());
  r.largest_force /= r.force_scale;
  r.interior_force /= r.force_scale;
  if (!small) return r;

  std::vector<double> W_minus, theta_minus;
  evaluate(-H, W_minus, theta_minus);
  const Eigen::Matrix3d eps = 0.5 * (H + H.transpose());
  const double tr = eps.topLeftCorner<D, D>().trace();
  const double W_cl = classical_energy(eps, D, sys_.setting, sys_.material);
  r.theta_error = r.energy_error = r.predicted_error = r.prediction_mismatch = 0.0;
  for (Index i : interior_) {
    const double th = 0.5 * (theta[i] - theta_minus[i]);
    r.theta_error = std::max(r.theta_error, std::abs(th - tr) / hmax);
    const double w = 0.5 * (W[i] + W_minus[i]);
    const double err = w / W_cl - 1.0;
    if (std::abs(err) >= std::abs(r.energy_error)) r.energy_error = err;
    const double pred = lattice_energy(i, eps);
    const double perr = pred / W_cl - 1.0;
    if (std::isnan(pred) || std::abs(perr) >= std::abs(r.predicted_error)) r.predicted_error = perr;
    r.prediction_mismatch =
        std::isnan(pred) ? not_measured : std::max(r.prediction_mismatch, std::abs(w - pred) / W_cl);
  }
  return r;
}

template class PatchBlock<1>;
template class PatchBlock<2>;
template class PatchBlock<3>;

}  // namespace pdmpm::test
