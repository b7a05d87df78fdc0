#include "solver/sim/pd_state.hpp"

#include <omp.h>

namespace pdmpm::sim {

template <int D>
PdState<D>::PdState(PdSetup<D>& setup) : s_(setup), energy_(setup.system.particles.n_real, 0.0) {}

template <int D>
void PdState<D>::external_forces(double t) {
  auto& p = particles();
  for (Index i = 0; i < p.n_real; ++i) p.b[i].setZero();
  if (s_.has_body_force) {
    bc::ExpressionVariables vars;
    vars.t = t;
    for (Index i = 0; i < p.n_real; ++i) {
      vars.x = p.x0[i][0];
      if constexpr (D > 1) vars.y = p.x0[i][1];
      if constexpr (D > 2) vars.z = p.x0[i][2];
      for (int a = 0; a < D; ++a) p.b[i][a] = s_.body_force[a](vars);
    }
  }
  s_.boundaries.add_tractions(p, t);
  if (s_.indenter) indenter_force_ = s_.indenter->add_forces(p, t);
}

template <int D>
void PdState<D>::internal_forces(bool energy) {
  pd::ForceRequest req;
  req.break_bonds = s_.damage;
  req.critical_stretch = s_.critical_stretch;
  req.break_after_force = s_.break_after_force;
  req.energy = energy ? &energy_ : nullptr;
  const double t0 = omp_get_wtime();
  broken_sides_ += s_.model->compute_forces(s_.system, req);
  force_seconds_ += omp_get_wtime() - t0;
  bond_evaluations_ += s_.system.families.n_bonds();
  if (s_.contact) {
    const double t1 = omp_get_wtime();
    contact_pairs_ = s_.contact->add_forces(s_.system);
    contact_seconds_ += omp_get_wtime() - t1;
  }
}

template <int D>
double PdState<D>::kinetic_energy() const {
  const auto& p = particles();
  double ke = 0.0;
  for (Index i = 0; i < p.n_real; ++i) ke += p.volume[i] * p.v[i].squaredNorm();
  return 0.5 * density() * ke;
}

template <int D>
double PdState<D>::internal_energy() const {
  const auto& p = particles();
  double u = 0.0;
  for (Index i = 0; i < p.n_real; ++i) u += energy_[i] * p.volume[i];
  return u;
}

template <int D>
Vec<D> PdState<D>::momentum() const {
  const auto& p = particles();
  Vec<D> m = Vec<D>::Zero();
  for (Index i = 0; i < p.n_real; ++i) m += p.volume[i] * p.v[i];
  return density() * m;
}

template <int D>
Eigen::Vector3d PdState<D>::angular_momentum() const {
  const auto& p = particles();
  Eigen::Vector3d L = Eigen::Vector3d::Zero();
  for (Index i = 0; i < p.n_real; ++i) {
    Eigen::Vector3d x = Eigen::Vector3d::Zero(), q = Eigen::Vector3d::Zero();
    const Vec<D> xi = p.position(i);
    for (int a = 0; a < D; ++a) x[a] = xi[a], q[a] = p.volume[i] * p.v[i][a];
    L += x.cross(q);
  }
  return density() * L;
}

template class PdState<1>;
template class PdState<2>;
template class PdState<3>;

}  // namespace pdmpm::sim
