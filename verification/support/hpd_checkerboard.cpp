#include "verification/support/hpd_checkerboard.hpp"

#include <cmath>
#include <vector>

#include "solver/pd/hpd.hpp"
#include "solver/pd/lps.hpp"
#include "verification/support/pd_fixtures.hpp"

namespace pdmpm::test {

namespace {

// A particle-centred (correspondence) gradient H_i = Σ_j ω (u_j − u_i) ⊗ ξ V_j K_i⁻¹ with its
// force f_i = Σ_j ω (σ_i K_i⁻¹ + σ_j K_j⁻¹) ξ V_j (Silling et al. 2007), for the comparison only.
template <int D>
std::vector<Vec<D>> correspondence_forces(const pd::System<D>& sys) {
  const auto& p = sys.particles;
  const auto& t = sys.table;
  const Index n = sys.n_real();
  std::vector<Mat<D>> sk(n);  // σ_i K_i⁻¹
  for (Index i = 0; i < n; ++i) {
    Mat<D> K = Mat<D>::Zero(), N = Mat<D>::Zero();
    sys.for_each_live_bond(i, [&](BondIndex, Index j, int s) {
      K += t.weight[s] * p.volume[j] * t.xi[s] * t.xi[s].transpose();
      N += t.weight[s] * p.volume[j] * (p.u[j] - p.u[i]) * t.xi[s].transpose();
    });
    const Mat<D> H = N * K.inverse(), e = 0.5 * (H + H.transpose());
    const Mat<D> sigma = sys.material.lame() * e.trace() * Mat<D>::Identity() + 2.0 * sys.material.shear() * e;
    sk[i] = sigma * K.inverse();
  }
  std::vector<Vec<D>> f(n, Vec<D>::Zero());
  for (Index i = 0; i < n; ++i)
    sys.for_each_live_bond(
        i, [&](BondIndex, Index j, int s) { f[i] += t.weight[s] * p.volume[j] * (sk[i] + sk[j]) * t.xi[s]; });
  return f;
}

}  // namespace

template <int D>
CheckerboardForces checkerboard_forces(core::Setting setting, int sites, double horizon_ratio) {
  BlockSpec spec;
  spec.sites = sites;
  spec.horizon_ratio = horizon_ratio;
  spec.setting = setting;
  spec.material = {200e9, 0.3, 7850.0};
  spec.measure = D == 3 ? 1.0 : 1e-3;
  auto sys = make_block<D>(spec);
  sys.hpd.law = pd::HpdLaw::linear_elastic;
  const Index n = sys.n_real();
  const double a = 1e-9;
  for (Index i = 0; i < n; ++i) {
    const auto idx = (sys.particles.x0[i] / sys.spacing()).array().round().template cast<int>();
    sys.particles.u[i] = Vec<D>::Zero();
    sys.particles.u[i][0] = idx.sum() % 2 == 0 ? a : -a;
  }
  auto interior_mean = [&](const std::vector<Vec<D>>& f) {
    double sum = 0.0;
    int count = 0;
    for (Index i = 0; i < n; ++i)
      if (distance_to_boundary(sys, i) >= 2.0 * sys.delta - 1e-12) sum += f[i].norm(), ++count;
    return sum / count;
  };
  pd::ForceRequest req;
  auto hpd_force = [&](double end_weight, double stabilization) {
    sys.hpd.end_weight = end_weight;
    sys.hpd.stabilization = stabilization;
    pd::Hpd<D> hpd;
    hpd.initialise(sys);
    hpd.compute_forces(sys, req);
    return interior_mean(sys.particles.f);
  };
  const pd::HpdOptions defaults;
  const double f_hpd = hpd_force(defaults.end_weight, defaults.stabilization);
  const double f_unstabilized = hpd_force(defaults.end_weight, 0.0), f_plain = hpd_force(1.0, 0.0);
  pd::Lps<D> lps;
  lps.initialise(sys);
  lps.compute_forces(sys, req);
  const double f_lps = interior_mean(sys.particles.f);
  return {f_hpd / f_lps, f_unstabilized / f_lps, f_plain / f_lps, interior_mean(correspondence_forces(sys)) / f_lps};
}

template CheckerboardForces checkerboard_forces<2>(core::Setting, int, double);
template CheckerboardForces checkerboard_forces<3>(core::Setting, int, double);

}  // namespace pdmpm::test
