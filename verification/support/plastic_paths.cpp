#include "verification/support/plastic_paths.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "solver/pd/lps.hpp"
#include "verification/support/pd_fixtures.hpp"

namespace pdmpm::test {

template <int D>
PlasticBlock<D>::PlasticBlock(const PlasticBlockSpec& s) : spec(s) {
  BlockSpec block;
  block.sites = s.sites > 0 ? s.sites : 2 * static_cast<int>(std::ceil(2.0 * s.horizon_ratio)) + 1;
  block.horizon_ratio = s.horizon_ratio;
  block.influence = s.influence;
  block.material = s.material;
  block.setting = s.setting;
  sys = make_block<D>(block);
  sys.hardening = s.hardening;
  sys.isotropic_deviatoric = s.isotropic;
  sys.ductile_failure = s.failure;
  model.initialise(sys);
  const Vec<D> mid = Vec<D>::Constant(0.5 * (block.sites - 1) * block.spacing);
  for (Index i = 0; i < sys.n_real(); ++i)
    if ((sys.particles.x0[i] - mid).norm() < (sys.particles.x0[centre] - mid).norm()) centre = i;
}

template <int D>
void PlasticBlock<D>::apply_affine(const Mat<D>& H) {
  for (Index i = 0; i < sys.n_real(); ++i) sys.particles.u[i] = H * sys.particles.x0[i];
}

template <int D>
Mat<D> PlasticBlock<D>::stress_under(const Mat<D>& H) {
  apply_affine(H);
  sys.bonds.pending_breaks += model.compute_forces(sys, request);  // as pd::Simulation books them
  return model.force_state_stress(sys, centre);
}

template <int D>
Mat<D> PlasticBlock<D>::uniaxial(double eps, double& lateral, const Mat<D>& R) {
  auto sigma_at = [&](double l) {
    Vec<D> diagonal = Vec<D>::Constant(l);
    diagonal[0] = eps;
    return Mat<D>(R.transpose() * stress_under(R * diagonal.asDiagonal() * R.transpose()) * R);
  };
  // Secant on σ_yy(l) = 0; σ_zz follows by symmetry of the path (checked by the callers).
  const double tol = 1e-9 * spec.hardening.yield_stress;
  double l0 = lateral, l1 = lateral - spec.material.nu * 1e-7;
  double f0 = sigma_at(l0)(1, 1), f1 = sigma_at(l1)(1, 1);
  for (int it = 0; it < 50 && std::abs(f1) > tol && f1 != f0; ++it) {
    const double l2 = l1 - f1 * (l1 - l0) / (f1 - f0);
    l0 = l1, f0 = f1, l1 = l2;
    f1 = sigma_at(l1)(1, 1);
  }
  lateral = l1;
  return sigma_at(l1);
}

template <int D>
double PlasticBlock<D>::shear(double gamma) {
  Mat<D> H = Mat<D>::Zero();
  H(0, 1) = H(1, 0) = 0.5 * gamma;
  return stress_under(H)(0, 1);
}

template <int D>
double PlasticBlock<D>::dilatation() const {
  std::vector<double> theta;
  model.dilatation(sys, theta);
  return theta[centre];
}

template <int D>
double PlasticBlock<D>::difference_from_elastic_lps() {
  auto elastic_sys = sys;
  pd::Lps<D> elastic;
  elastic.initialise(elastic_sys);
  model.compute_forces(sys, request);
  elastic.compute_forces(elastic_sys, request);
  double fmax = 0.0, diff = 0.0;
  for (Index i = 0; i < sys.n_real(); ++i) {
    fmax = std::max(fmax, elastic_sys.particles.f[i].norm());
    diff = std::max(diff, (sys.particles.f[i] - elastic_sys.particles.f[i]).norm());
  }
  return diff / fmax;
}

template <int D>
std::vector<int> PlasticBlock<D>::live_sides() const {
  std::vector<int> n(sys.n_real(), 0);
  for (Index i = 0; i < sys.n_real(); ++i)
    for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b)
      if (sys.bonds.live(b)) ++n[i], ++n[sys.families.neighbor[b]];
  return n;
}

template <int D>
FailureRecord PlasticBlock<D>::load_until_failure(const std::function<Mat<D>(double)>& path, double step,
                                                  int max_steps) {
  FailureRecord r;
  const auto& rule = sys.ductile_failure;
  const Index n = sys.n_real();
  std::vector<double> damage(n, 0.0), ep_committed(n, 0.0);
  std::vector<std::uint8_t> must_fail(n);
  for (int k = 1; k <= max_steps && !r.centre_failed; ++k) {
    PlasticBlock twin = *this;
    twin.request.break_bonds = false;
    twin.stress_under(path(k * step));
    const auto& ep = *twin.model.eq_plastic_strain();
    const std::vector<int> alive = live_sides();
    for (Index i = 0; i < n; ++i) {
      must_fail[i] = 0;
      if (ep[i] == 0.0 || alive[i] == 0) continue;
      const double eps_f = rule.d0 * std::exp(rule.c * pd::triaxiality(twin.model.own_stress(twin.sys, i)));
      if (rule.rule == core::FailureRule::strain) {
        must_fail[i] = ep[i] >= eps_f;
      } else {
        damage[i] += (ep[i] - ep_committed[i]) / eps_f;
        must_fail[i] = damage[i] >= 1.0;
      }
      ep_committed[i] = ep[i];
    }
    const std::vector<int> before = live_sides();
    stress_under(path(k * step));
    model.accept();
    sys.bonds.accept();
    const std::vector<int> after = live_sides();
    for (Index i = 0; i < n; ++i) {
      r.failures += must_fail[i];
      if (must_fail[i]) {
        r.mismatches += after[i] != 0;
        continue;
      }
      // Bonds of i lost this step must all lead to particles that failed.
      int lost_to_failed = 0;
      for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b)
        if (must_fail[sys.families.neighbor[b]]) lost_to_failed += 2;  // both sides
      r.mismatches += before[i] - after[i] > lost_to_failed;
    }
    r.centre_failed = after[centre] == 0;
    r.steps = k;
  }
  return r;
}

template <int D>
double PlasticBlock<D>::homogeneous_onset(const std::function<Mat<D>(double)>& path, double step, int max_steps) {
  const auto& rule = sys.ductile_failure;
  const bool breaking = request.break_bonds;
  request.break_bonds = false;
  double onset = 0.0;
  for (int k = 1; k <= max_steps && onset == 0.0; ++k) {
    stress_under(path(k * step));
    model.accept();
    const double ep = eq_plastic_strain();
    if (ep > 0.0 && ep >= rule.d0 * std::exp(rule.c * pd::triaxiality(model.own_stress(sys, centre)))) onset = ep;
  }
  request.break_bonds = breaking;
  return onset;
}

template class PlasticBlock<2>;
template class PlasticBlock<3>;

}  // namespace pdmpm::test
