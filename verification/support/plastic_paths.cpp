#include "verification/support/plastic_paths.hpp"

#include <cmath>
#include <vector>

#include "verification/support/pd_fixtures.hpp"

namespace pdmpm::test {

template <int D>
PlasticBlock<D>::PlasticBlock(const PlasticBlockSpec& s) : spec(s) {
  BlockSpec block;
  // 4δ + 1 sites per side: the centre's family and its neighbours' families are full.
  block.sites = 2 * static_cast<int>(std::ceil(2.0 * s.horizon_ratio)) + 1;
  block.horizon_ratio = s.horizon_ratio;
  block.influence = s.influence;
  block.material = s.material;
  block.setting = s.setting;
  sys = make_block<D>(block);
  sys.hardening = s.hardening;
  sys.isotropic_deviatoric = s.isotropic;
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
  model.compute_forces(sys, {});
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

template class PlasticBlock<2>;
template class PlasticBlock<3>;

}  // namespace pdmpm::test
