#include "solver/pd/pmb.hpp"

#include "solver/pd/constants.hpp"

namespace pdmpm::pd {

template <int D>
void Pmb<D>::initialise(const System<D>& sys) {
  c_ = pmb_micromodulus(sys.influence, sys.setting, sys.material, sys.delta, sys.measure);
}

template <int D>
std::int64_t Pmb<D>::compute_forces(System<D>& sys, const ForceRequest& req) {
  auto& p = sys.particles;
  if (req.energy) req.energy->resize(p.n_real);
  kernels::PmbArgs a;
  a.fam = sys.family_view();
  a.table = sys.table.view();
  a.u = p.u.data()->data();
  a.volume = p.volume.data();
  a.uniform_volume = sys.uniform_volume();
  a.f = p.f.data()->data();
  a.energy = req.energy ? req.energy->data() : nullptr;
  a.c = c_;
  a.breaking = req.break_bonds;
  a.s0 = req.critical_stretch;
  a.after_force = req.break_after_force;
  return kernels::pmb_forces<D>(a);
}

template <int D>
double Pmb<D>::stiffness_row_sum(const System<D>& sys, Index i) const {
  // C_ij = c ω β / |ξ| for PMB (Silling & Askari 2005).
  double sum = 0.0;
  sys.for_each_live_bond(i, [&](BondIndex, Index j, int k) {
    sum += c_ * sys.table.weight[k] / sys.table.length[k] * sys.particles.volume[j];
  });
  return sum;
}

template class Pmb<1>;
template class Pmb<2>;
template class Pmb<3>;

}  // namespace pdmpm::pd
