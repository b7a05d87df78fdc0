#include "benchmarks/bench_bodies.hpp"

#include <cmath>

#include "solver/core/particle_builder.hpp"

namespace pdmpm::bench {

template <int D>
pd::System<D> lattice_body(int n, double horizon_ratio) {
  const double dx = 1e-3;
  core::Lattice<D> lat;
  lat.spacing = dx;
  core::Geometry<D> g;
  g.add(std::make_unique<core::Box<D>>(Vec<D>::Zero(), Vec<D>::Constant((n - 1) * dx)));
  pd::System<D> sys;
  sys.particles = core::fill_lattice<D>(g, lat, std::pow(dx, D) * (D == 2 ? 1e-3 : 1.0));
  sys.setting = D == 3 ? core::Setting::solid3d : core::Setting::plane_strain;
  sys.material = {200e9, 0.25, 7850.0};
  sys.delta = horizon_ratio * dx;
  sys.measure = D == 3 ? 1.0 : 1e-3;
  sys.connect();
  return sys;
}

template <int D>
void deform(pd::System<D>& sys) {
  auto& p = sys.particles;
  for (Index i = 0; i < p.size(); ++i)
    for (int a = 0; a < D; ++a) p.u[i][a] = 1e-7 * std::sin(300.0 * p.x0[i][(a + 1) % D] + a);
}

template pd::System<2> lattice_body<2>(int, double);
template pd::System<3> lattice_body<3>(int, double);
template void deform<2>(pd::System<2>&);
template void deform<3>(pd::System<3>&);

}  // namespace pdmpm::bench
